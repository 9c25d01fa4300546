#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/io/nc_line.hpp"
#include "freeturn/io/nc_program.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

// The X values of the blocks, in the order read.
std::vector<double> xs(const std::vector<NcBlock>& blocks) {
  std::vector<double> out;
  for (const NcBlock& b : blocks)
    for (const NcWord& w : b.words)
      if (w.numeric && w.letter == 'X') out.push_back(w.value);
  return out;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("an axis or F word twice in one block is refused at its column") {
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1 Z0\nC4 X1.9 Z0.3 X2\n", "p.nc"),
                         doctest::Contains("p.nc:2:14: X is given twice in one block (first at column 4)"),
                         InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G93 F0.1 X1 f0.2\n", "p.nc"), doctest::Contains("p.nc:1:13: F is given twice"),
                         InputError);
    // Codes may repeat (G01 G18 G90 …), and so may words no controller reads as a target.
    const std::vector<NcBlock> codes = parse_nc("G71 G01 G18 G40 X1 M03 M08\n", "p.nc");
    REQUIRE(codes.size() == 1);
    CHECK(codes[0].words.size() == 7);
    CHECK(codes[0].words[4].column == 17);
  }

  TEST_CASE("a '%' line is the tape's start when first, its end after: nothing past it is read") {
    CHECK(xs(parse_nc("%\nG1 X1\nG1 X2\nM2\n%\n", "p.nc")) == std::vector<double>{1, 2});
    CHECK(xs(parse_nc("\n % \nG1 X1\n", "p.nc")) == std::vector<double>{1});
    // After a first line (a comment), a '%' ends the tape: X2 is never run.
    CHECK(xs(parse_nc("(program)\nG1 X1\n%\nG1 X2\n", "p.nc")) == std::vector<double>{1});
    CHECK(xs(parse_nc("%\nG1 X1\n%\nG1 X2\n%\n", "p.nc")) == std::vector<double>{1});
    // A comment beside a mark leaves it a mark, as the guard reads it (post/nc_guard.cpp).
    CHECK(xs(parse_nc("% (start)\nG1 X1\n%;end\nG1 X2\n", "p.nc")) == std::vector<double>{1});
    // In a comment a '%' is text.
    CHECK(xs(parse_nc("G1 X1 (50 %)\nG1 X2 ; 10 %\n", "p.nc")) == std::vector<double>{1, 2});
  }

  TEST_CASE("a '%' that is no tape mark is refused where it stands, as the guard refuses it") {
    // Before, the reader skipped it: "G1 X1 %" read as G1 X1, and "% G1 X2" as G1 X2.
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1\nG1 X2 %\n", "p.nc"),
                         doctest::Contains("p.nc:2:7: '%' inside a block, where it is not a word"),
                         InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1\n  % G1 X2\n", "p.nc"),
                         doctest::Contains("p.nc:2:3: '%' with words after it on its line"),
                         InputError);
    CHECK_THROWS_WITH_AS(parse_nc("(c) % X2\n", "p.nc"),
                         doctest::Contains("p.nc:1:5: '%' with words"), InputError);
  }

  TEST_CASE("two G codes of one RS-274 modal group in a block are refused at the second") {
    CHECK_THROWS_WITH_AS(parse_nc("G90\nG1 G0 X1\n", "p.nc"),
                         doctest::Contains("p.nc:2:4: G0 after G1 (column 1) in one block: both "
                                           "are codes of RS-274's motion group"),
                         InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G93 g94 X1 F2\n", "p.nc"),
                         doctest::Contains("p.nc:1:5: g94 after G93 (column 1) in one block: "
                                           "both are codes of RS-274's feed-rate mode group"),
                         InputError);
    // Each code as written.
    CHECK_THROWS_WITH_AS(parse_nc("G38.2 G01 X1\n", "p.nc"),
                         doctest::Contains("p.nc:1:7: G01 after G38.2"), InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G01.0 G00 X1\n", "p.nc"),
                         doctest::Contains("p.nc:1:7: G00 after G01.0 (column 1)"), InputError);
    // One code of each group, and codes of no group (G4, G53, G71 on a Moore), are a block.
    CHECK(parse_nc("G0 G90 G40 G18 G21 G94 G54 G64 X1\n", "p.nc").size() == 1);
    CHECK(parse_nc("G71 G4 G53 G1 X1\n", "p.nc").size() == 1);
  }

  TEST_CASE("g_code_modal_group follows RS-274's groups as LinuxCNC lists them") {
    // LinuxCNC's G-code reference, "Modal Groups": group numbers as it numbers them.
    for (const double g : {0.0, 1.0, 2.0, 3.0, 33.0, 38.2, 38.5, 73.0, 76.0, 80.0, 89.0})
      CHECK(g_code_modal_group(g) == 1);
    for (const double g : {17.0, 18.0, 19.0, 17.1, 19.1}) CHECK(g_code_modal_group(g) == 2);
    CHECK(g_code_modal_group(90) == 3);
    CHECK(g_code_modal_group(91.1) == 4);
    for (const double g : {93.0, 94.0, 95.0}) CHECK(g_code_modal_group(g) == 5);
    CHECK(g_code_modal_group(21) == 6);
    CHECK(g_code_modal_group(41.1) == 7);
    CHECK(g_code_modal_group(43.1) == 8);
    CHECK(g_code_modal_group(99) == 10);
    CHECK(g_code_modal_group(59.3) == 12);
    CHECK(g_code_modal_group(61.1) == 13);
    CHECK(g_code_modal_group(97) == 14);
    CHECK(g_code_modal_group(7) == 15);
    // Non-modal codes (G4 dwell, G53, G92), a Moore's own (G71, G63), and no code at all.
    for (const double g : {4.0, 53.0, 92.0, 71.0, 63.0, 1.5, 0.05, -1.0, 1e300})
      CHECK(g_code_modal_group(g) == -1);
    CHECK(std::string(g_code_modal_group_name(5)) == "feed-rate mode");
    CHECK(std::string(g_code_modal_group_name(9)) == "no");
  }

  TEST_CASE("tape_mark reads a line's code as a mark, a mark with words, or neither") {
    std::string code;
    const auto mark_of = [&](const std::string& line) {
      strip_nc_comments(line, code);
      return tape_mark(code);
    };
    CHECK(mark_of("%") == TapeMark::kMark);
    CHECK(mark_of(" \t%\r") == TapeMark::kMark);
    CHECK(mark_of("%(tape start) ; and more") == TapeMark::kMark);
    CHECK(mark_of("% G1") == TapeMark::kWordsAfter);
    CHECK(mark_of("%%") == TapeMark::kWordsAfter);
    CHECK(mark_of("G1 X1 %") == TapeMark::kNone);
    CHECK(mark_of("(50 %)") == TapeMark::kNone);
    CHECK(mark_of("") == TapeMark::kNone);
  }

  TEST_CASE("strip_nc_comments drops what a controller skips and finds what it stops on") {
    std::string code;
    CHECK(!strip_nc_comments("G1 (a; b) X1 ; (d (e", code));
    CHECK(code == "G1  X1 ");
    // LinuxCNC's reader: a '(' in a comment is a nested comment, a comment open at the
    // line's end an unclosed one, both errors; a lone ')' is no word either.
    NcCommentError error = strip_nc_comments("G1 (a (b) c) X1", code);
    CHECK(error.column == 7);
    CHECK(std::string(error.what) == "'(' inside a comment: controllers do not nest comments");
    error = strip_nc_comments("G1 X1 (open", code);
    CHECK(error.column == 7);
    CHECK(std::string(error.what).find("without ')'") != std::string::npos);
    error = strip_nc_comments("(a)) X1", code);
    CHECK(error.column == 4);
    CHECK(std::string(error.what) == "')' outside a comment");
    error = {};
    CHECK(nc_comment_close("X(abc)", 1, error) == 5);
    CHECK(!error);
  }

  TEST_CASE("the reader refuses a line longer than a controller reads, as the guard does") {
    CHECK(xs(parse_nc("G1 X1 (" + std::string(247, 'a') + ")\r\n", "p.nc")) ==
          std::vector<double>{1});
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1\nG1 X2 (" + std::string(248, 'a') + ")\n", "p.nc"),
                         doctest::Contains("p.nc:2:256: a line of 256 characters"), InputError);
  }

  TEST_CASE("the reader refuses the comments the guard refuses, at their column") {
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1\nG1 (a (b) c) X2\n", "p.nc"),
                         doctest::Contains("p.nc:2:7: '(' inside a comment"), InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1 (open\n", "p.nc"),
                         doctest::Contains("p.nc:1:7: a comment '(' without ')'"), InputError);
    CHECK_THROWS_WITH_AS(parse_nc("G1 X1 ) Z2\n", "p.nc"),
                         doctest::Contains("p.nc:1:7: ')' outside a comment"), InputError);
    // Beside a tape mark too: before, "% (open" read as a mark.
    CHECK_THROWS_WITH_AS(parse_nc("% (open\nG1 X1\n", "p.nc"),
                         doctest::Contains("p.nc:1:3: a comment '(' without ')'"), InputError);
    CHECK(xs(parse_nc("G1 X1 (a; b) ; c (d\nM98(child.nc)\n", "p.nc")) == std::vector<double>{1});
  }

  TEST_CASE("a child program is read beside its caller, by its name: never a path") {
    const test::TempDir dir;
    const std::string up = dir.write("up.nc", "G1 X1\nM98(../../etc/hostname)\nM30\n");
    CHECK_THROWS_WITH_AS(read_nc_program(up),
                         doctest::Contains("up.nc:2:1: M98 calls '../../etc/hostname'"),
                         InputError);
    const std::string root = dir.write("root.nc", "G1 X1\n  M98(/etc/passwd)\nM30\n");
    CHECK_THROWS_WITH_AS(read_nc_program(root),
                         doctest::Contains("root.nc:2:3: M98 calls '/etc/passwd'"), InputError);
    const std::string missing = dir.write("missing.nc", "G1 X1\nM98(gone.nc)\nM30\n");
    CHECK_THROWS_WITH_AS(
        read_nc_program(missing),
        doctest::Contains("missing.nc:2:1: M98 calls 'gone.nc', which is not beside missing.nc"),
        InputError);
  }

  TEST_CASE("a program is read as it runs: it ends at M30, M02 or M99, a child returns at M99") {
    const test::TempDir dir;
    dir.write("child.nc", "G93 F0.1\nC1 X1\nC2 X2\nM99\nC3 X-99\n");
    const std::string main = dir.write("main.nc", "G1 X0 Z1\nM98(child.nc)\nG1 X5\nM30\nG1 X-50 Z-50\n");
    std::vector<std::string> files;
    const std::vector<NcBlock> blocks = read_nc_program(main, &files);
    CHECK(xs(blocks) == std::vector<double>{0, 1, 2, 5});
    REQUIRE(files.size() == 2);
    CHECK(files[0] == main);
    CHECK(files[1] == dir.file("child.nc"));
    CHECK(blocks.back().line == 4);  // the M30 itself is read
    CHECK(blocks.back().file == 0);
    CHECK(blocks[3].file == 1);      // C2 X2, the child's line 3
    CHECK(blocks[3].line == 3);
    // M02 ends it in a child too; M99 in the main program ends it.
    dir.write("ends.nc", "C1 X1\nM02\nC2 X-99\n");
    CHECK(xs(read_nc_program(dir.write("a.nc", "X0\nM98(ends.nc)\nX-98\n"))) == std::vector<double>{0, 1});
    CHECK(xs(read_nc_program(dir.write("b.nc", "X0\nM99\nX-98\n"))) == std::vector<double>{0});
    CHECK(xs(read_nc_program(dir.write("c.nc", "X0\nM2\nX-98\n"))) == std::vector<double>{0});
  }
}
