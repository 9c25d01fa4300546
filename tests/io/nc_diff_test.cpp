#include <doctest/doctest.h>

#include <string>

#include "freeturn/io/nc_program.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

NcDiffResult diff(const std::string& a, const std::string& b) {
  return nc_diff(parse_nc(a, "a.nc"), "a.nc", parse_nc(b, "b.nc"), "b.nc");
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("ncdiff: modal codes and F hold until replaced; restating them changes nothing") {
    // G1 on every line, or once; F100 on every feed move, or once (G94: F is modal).
    CHECK(diff("G21 G18 G94\nG1 X1 Z0 F100\nG1 X2 F100\nG1 Z-1 F100\n",
               "G21 G18 G94\nG1 X1 Z0 F100\nX2\nZ-1\n")
              .same);
    // Modal codes on a line of their own before the move, or on the move.
    CHECK(diff("G21\nG18\nG90\nG1 X1 F50\n", "G90 G18 G21 G1 X1 F50\n").same);
    // G01 is G1, G0 is G00.
    CHECK(diff("G00 X1\nG01 X2 F10\n", "G0 X1\nG1 X2 F10\n").same);
  }

  TEST_CASE("ncdiff: a different modal state, or a word moved to another block, is a difference") {
    // A rapid where the other program feeds: the motion group differs at the second move.
    const NcDiffResult rapid = diff("G1 X1 F100\nX2\n", "G1 X1 F100\nG0 X2\n");
    CHECK_FALSE(rapid.same);
    CHECK(rapid.first_difference == "a.nc:2 vs b.nc:2: modal G1 vs G0");
    // The feed changed before the last move in one program only.
    const NcDiffResult feed = diff("G94 G1 X1 F100\nX2\n", "G94 G1 X1 F100\nF50\nX2\n");
    CHECK_FALSE(feed.same);
    CHECK(feed.first_difference == "a.nc:2 vs b.nc:3: F 100 ≠ 50");
    // Inverse time (G93): each move states its F, so a move without one is not the same.
    CHECK_FALSE(diff("G93 G1 X1 F10\nX2 F10\n", "G93 G1 X1 F10\nX2\n").same);
    CHECK(diff("G93 G1 X1 F10\nX2 F10\n", "G93\nG1 F10 X1\nF10 X2\n").same);
    // An M code is an act where it stands: M3 before the move is not M3 after it.
    CHECK_FALSE(diff("M3 S100\nG1 X1 F10\n", "G1 X1 F10\nM3 S100\n").same);
    // A dialect's own G code (Moore's G63) has no modal group here: it counts where it is.
    CHECK_FALSE(diff("G63\nG1 X1 F10\n", "G1 X1 F10\n").same);
    CHECK_FALSE(diff("G63 G1 X1 F10\nG1 X2\n", "G1 X1 F10\nG63 G1 X2\n").same);
    // One more move: the counts of blocks that act differ.
    const NcDiffResult longer = diff("G1 X1 F10\n", "G1 X1 F10\nX2\n");
    CHECK_FALSE(longer.same);
    CHECK(longer.first_difference == "a.nc has 1 blocks that act, b.nc has 2");
  }

  TEST_CASE("ncdiff: an arc's centre offsets belong to their block") {
    // I and J are stated by each arc; an arc without them is not the one before's again.
    CHECK_FALSE(diff("G17 G2 X1 Y0 I0.5 J0 F10\nG2 X2 Y0 I0.5 J0\n",
                     "G17 G2 X1 Y0 I0.5 J0 F10\nG2 X2 Y0\n")
                    .same);
    const NcDiffResult near = diff("G2 X1 I0.5 F10\n", "G2 X1 I0.5000000001 F10\n");
    CHECK(near.same);
    CHECK(near.largest['I' - 'A'] == doctest::Approx(1e-10).epsilon(0.01));
  }

  TEST_CASE("ncdiff of program files follows their calls: the layout in files does not count") {
    // One program written whole, and the same split into a main program and a point file:
    // the same. A moved block inside the point file: different, named at the child's line.
    test::TempDir dir;
    const std::string whole = dir.write("whole.nc", "G93 F0.1\nC4 X1 Z0\nC8 X0.9 Z0\nM30\n");
    dir.write("split_001.nc", "C4 X1 Z0\nC8 X0.9 Z0\nM99\n");
    const std::string split = dir.write("split.nc", "G93 F0.1\nM98(split_001.nc)\nM30\n");
    CHECK(nc_diff_files(whole, split).same);
    dir.write("moved_001.nc", "C4 X1 Z0\nC8 X0.9001 Z0\nM99\n");
    const std::string moved = dir.write("moved.nc", "G93 F0.1\nM98(moved_001.nc)\nM30\n");
    const NcDiffResult d = nc_diff_files(split, moved);
    CHECK_FALSE(d.same);
    CHECK(d.first_difference.find("split_001.nc:2 vs ") != std::string::npos);
    CHECK(d.first_difference.find("moved_001.nc:2: X 0.9 ≠ 0.9001") != std::string::npos);
    // Read one file at a time, the calls are words like any other.
    CHECK_FALSE(nc_diff(parse_nc("M98(a.nc)\n", "a"), "a", parse_nc("M98(b.nc)\n", "b"), "b").same);
  }
}
