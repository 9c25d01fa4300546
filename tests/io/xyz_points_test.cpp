#include <doctest/doctest.h>

#include "freeturn/core/error.hpp"
#include "freeturn/io/xyz_points.hpp"
#include "test_files.hpp"

using freeturn::InputError;
using freeturn::read_xyz_points;

TEST_SUITE("io") {
  TEST_CASE("xyz points: commas, spaces, a header and comments") {
    freeturn::test::TempDir dir;
    const auto points = read_xyz_points(
        dir.write("p.csv", "x,y,z\n1,2,3\n# a comment\n-1.5e-1  2\t0.25 # trailing\r\n\n4;5;6\n"));
    REQUIRE(points.size() == 3);
    CHECK(points[0] == Eigen::Vector3d(1, 2, 3));
    CHECK(points[1] == Eigen::Vector3d(-0.15, 2, 0.25));
    CHECK(points[2] == Eigen::Vector3d(4, 5, 6));
  }

  TEST_CASE("xyz points: a bad line is an error at its line") {
    freeturn::test::TempDir dir;
    CHECK_THROWS_WITH_AS(
        read_xyz_points(dir.write("p.csv", "1,2,3\n1,2\n")),
        doctest::Contains("p.csv:2:1: expected three numbers x y z (mm); the line holds 2 numbers"),
        InputError);
    CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("q.csv", "1,2,3\n1,2,nan\n")),
                         doctest::Contains("q.csv:2:"), InputError);
    CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("r.csv", "x y z\n")),
                         doctest::Contains("the file has no points"), InputError);
  }

  TEST_CASE("xyz points: every field is a whole finite number, stray bytes included") {
    freeturn::test::TempDir dir;
    // A NUL inside a line once ended the line early, and "1 2 3<NUL>junk" read as a point.
    CHECK_THROWS_WITH_AS(
        read_xyz_points(dir.write("n.csv", std::string("1 2 3\n4 5 6\0junk\n", 17))),
        doctest::Contains("n.csv:2:"), InputError);
    for (const char* bad : {"1 2 3.4.5\n", "1 2 3x\n", "1 2 1e400\n", "1 2 3 4\n", "1 2 0x10\n"}) {
      CAPTURE(bad);
      CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("b.csv", std::string("0 0 0\n") + bad)),
                           doctest::Contains("b.csv:2:"), InputError);
    }
    // A first row of NaN or infinity is no header of column names.
    for (const char* row : {"nan nan nan\n", "NaN 1 2\n", "inf 0 0\n", "x -INF z\n"}) {
      CAPTURE(row);
      CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("h.csv", std::string(row) + "0 0 0\n1 0 0\n")),
                           doctest::Contains("h.csv:1:"), InputError);
      CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("h.csv", std::string(row) + "0 0 0\n1 0 0\n")),
                           doctest::Contains("is not a finite number"), InputError);
    }
    // The column is the offending field's, counted in bytes from 1.
    CHECK_THROWS_WITH_AS(
        read_xyz_points(dir.write("c.csv", "0 0 0\n1 2 3x\n")),
        doctest::Contains(
            "c.csv:2:5: expected three numbers x y z (mm); '3x' is not a finite number"),
        InputError);
    CHECK_THROWS_WITH_AS(
        read_xyz_points(dir.write("c.csv", "0 0 0\n1, 2, 3, 4\n")),
        doctest::Contains("c.csv:2:10: expected three numbers x y z (mm); '4' is a fourth field"),
        InputError);
    CHECK_THROWS_WITH_AS(read_xyz_points(dir.write("c.csv", "x -INF z\n0 0 0\n")),
                         doctest::Contains("c.csv:1:3: '-INF' is not a finite number"), InputError);
    CHECK(read_xyz_points(dir.write("names.csv", "x y z\n0 0 0\n")).size() == 1);
    const auto points = read_xyz_points(dir.write("s.csv", "+1.5 -2E+01 .25\n"));
    REQUIRE(points.size() == 1);
    CHECK(points[0] == Eigen::Vector3d(1.5, -20, 0.25));
  }
}
