#include <doctest/doctest.h>

#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/io/iges_surface.hpp"
#include "test_files.hpp"

using freeturn::InputError;
using freeturn::read_iges_surface;
using freeturn::read_iges_surfaces;
using freeturn::nurbs::Vector3d;

namespace {

const std::string kData = std::string(FREETURN_SOURCE_DIR) + "/tests/io/data/";

// The patch both fixture files hold (tests/io/data, written by hand): a rational bicubic
// Bézier patch, P_ij = (−6 + 4i, −4.5 + 3j, i²/4 − j/8 + ij/16) mm, all weights 1 except
// w_12 = 2 and w_30 = 1/2 (which catch a transposed net).
Vector3d expected_point(int i, int j) {
  return {-6.0 + 4.0 * i, -4.5 + 3.0 * j, 0.25 * i * i - 0.125 * j + 0.0625 * i * j};
}
double expected_weight(int i, int j) {
  return i == 1 && j == 2 ? 2.0 : i == 3 && j == 0 ? 0.5 : 1.0;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("IGES entity 128: a hand-written bicubic patch reads back exactly") {
    const auto s = read_iges_surface(kData + "bicubic_patch.igs");
    REQUIRE(s.degree_u() == 3);
    REQUIRE(s.degree_v() == 3);
    REQUIRE(s.count_u() == 4);
    REQUIRE(s.count_v() == 4);
    CHECK(s.is_rational());
    for (int k = 0; k < 8; ++k) {
      CHECK(s.knots_u()[k] == (k < 4 ? 0.0 : 1.0));
      CHECK(s.knots_v()[k] == (k < 4 ? 0.0 : 1.0));
    }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        CAPTURE(i);
        CAPTURE(j);
        CHECK(s.homogeneous_point(i, j).w() == expected_weight(i, j));
        CHECK((s.control_point(i, j) - expected_point(i, j)).norm() == 0.0);
      }
    // The corners of a Bézier patch are its corner control points.
    CHECK((s.point(0, 0) - expected_point(0, 0)).norm() < 1e-15);
    CHECK((s.point(1, 0) - expected_point(3, 0)).norm() < 1e-15);
    CHECK((s.point(0, 1) - expected_point(0, 3)).norm() < 1e-15);
  }

  TEST_CASE("IGES: inches become mm, a transformation matrix applies, entities are chosen") {
    const auto all = read_iges_surfaces(kData + "two_patches_inch.igs");
    REQUIRE(all.size() == 2);
    CHECK(all[0].directory_line == 1);
    CHECK(all[1].directory_line == 3);
    // The second patch is rotated 90° about z and moved by (1, 2, 3) in: x' = −y + 25.4,
    // y' = x + 50.8, z' = z + 76.2 (mm).
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const Vector3d p = expected_point(i, j);
        CHECK((all[0].surface.control_point(i, j) - p).norm() < 1e-13);
        const Vector3d moved(-p.y() + 25.4, p.x() + 50.8, p.z() + 76.2);
        CHECK((all[1].surface.control_point(i, j) - moved).norm() < 1e-13);
        CHECK(all[1].surface.homogeneous_point(i, j).w() == expected_weight(i, j));
      }
    CHECK_THROWS_WITH_AS(read_iges_surface(kData + "two_patches_inch.igs"),
                         doctest::Contains("2 B-spline surfaces (entity 128, directory lines 1, "
                                           "3); choose one with 'entity'"),
                         InputError);
    CHECK((read_iges_surface(kData + "two_patches_inch.igs", 3).control_point(0, 0) -
           Vector3d(4.5 + 25.4, -6.0 + 50.8, 76.2))
              .norm() < 1e-13);
    CHECK_THROWS_WITH_AS(read_iges_surface(kData + "two_patches_inch.igs", 5),
                         doctest::Contains("no rational B-spline surface (entity 128) at "
                                           "directory line 5 (there are: 1, 3)"),
                         InputError);
  }

  TEST_CASE("IGES: malformed files name the line and column") {
    freeturn::test::TempDir dir;
    std::string text = freeturn::test::read_file(kData + "bicubic_patch.igs");
    // Shorten the first parameter record: a record must have its section in column 73 (the
    // error is where the line ends, after its 7 characters).
    const std::size_t p1 = text.find("128,3,3");
    std::string broken = text;
    broken.replace(p1, 80, "128,3,3");
    CHECK_THROWS_WITH_AS(read_iges_surface(dir.write("short.igs", broken)),
                         doctest::Contains("short.igs:6:8: IGES records are 80 columns"),
                         InputError);
    // A knot that is not a number.
    broken = text;
    broken.replace(p1 + 22, 3, "0.x");  // the first knot, in column 23 after K1 … PROP5
    CHECK_THROWS_WITH_AS(
        read_iges_surface(dir.write("knot.igs", broken)),
        doctest::Contains("knot.igs:6:23: entity 128 (directory line 1): knot S(0) "
                          "must be a number, not '0.x'"),
        InputError);
    // A weight on the second parameter record: its tenth field, "0.5" in column 37.
    broken = text;
    const std::size_t p2 = text.find("0.0,0.0,1.0,1.0,1.0,1.0,1.0,1.0,1.0,0.5");
    REQUIRE(p2 != std::string::npos);
    broken.replace(p2 + 36, 3, "0.y");
    CHECK_THROWS_WITH_AS(
        read_iges_surface(dir.write("weight.igs", broken)),
        doctest::Contains("weight.igs:7:37: entity 128 (directory line 1): weight 3 "
                          "must be a number, not '0.y'"),
        InputError);
    // A transformation pointer (the directory entry's seventh field, columns 49-56) at no
    // entity 124.
    broken = text;
    const std::size_t d1 = text.find("     128       1");
    broken.replace(d1 + 55, 1, "3");
    CHECK_THROWS_WITH_AS(
        read_iges_surface(dir.write("pointer.igs", broken)),
        doctest::Contains("pointer.igs:4:49: transformation pointer 3 does not name"), InputError);
    CHECK_THROWS_AS(read_iges_surface(dir.file("missing.igs")), InputError);
  }

  TEST_CASE("IGES: a units flag that disagrees with the units name is refused at the global section") {
    freeturn::test::TempDir dir;
    const std::string text = freeturn::test::read_file(kData + "two_patches_inch.igs");
    // Flag 1 (inches) with the name "INCH" reads (the name is the third global record's
    // field from column 13); the name "2HMM" in its place (same
    // width as "4HINCH" less two, padded) does not: which one was meant cannot be told.
    std::string mm_name = text;
    const std::size_t at = mm_name.find("4HINCH");
    REQUIRE(at != std::string::npos);
    mm_name.replace(at, 6, "2HMM  ");
    CHECK_THROWS_WITH_AS(read_iges_surface(dir.write("units.igs", mm_name), 3),
                         doctest::Contains("units.igs:3:13: the global section's units flag 1 (IN) "
                                           "disagrees with its units name 'MM'"),
                         InputError);
    // The lower-case name of the same unit is the same unit.
    std::string lower = text;
    lower.replace(lower.find("4HINCH"), 6, "4Hinch");
    CHECK_NOTHROW(read_iges_surface(dir.write("lower.igs", lower), 3));
  }
}
