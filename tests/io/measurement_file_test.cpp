#include <doctest/doctest.h>

#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/io/measurement_file.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

// A Zygo XYZ file in the layout docs/metrology.md describes: 14 header lines, '#', the
// pixels, '#'. 3 × 2 pixels from (10, 20), 0.5 µm a pixel, one "No Data".
std::string zygo_file(const std::string& phase_line, int pixels) {
  std::string s =
      "Zygo XYZ Data File - Format 1\n"
      "1 9 2 0 \"Mx\"\n"
      "0 0 0 0 0 0\n" +
      phase_line + "\n" +
      "\"comment\"\n\"\"\n\"\"\n"
      "0 0.5 6.328e-07 0 1 1 5e-07 1700000000\n"
      "640 480 0 0 0 0 \"Objective\"\n"
      "0 0 0 0 0 0 0 0 0 0\n"
      "0 0 0 0 0 0 0 0 0\n"
      "0 \"\"\n"
      "1 0\n"
      "\"\"\n"
      "#\n";
  const char* rows[] = {"10 20 0.125", "11 20 -0.25", "12 20 No Data",
                        "10 21 1e-3",  "11 21 0.5",   "12 21 2"};
  for (int k = 0; k < pixels; ++k) s += std::string(rows[k]) + "\n";
  return s + "#\n";
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("Zygo XYZ: a file in the documented layout reads back exactly, No Data masked") {
    test::TempDir dir;
    const std::string path = dir.write("m.xyz", zygo_file("10 20 3 2", 6));
    MeasurementFileOptions o;
    o.format = MeasurementFormat::kZygoXyz;
    o.height_scale = 1e-3;  // µm
    const Measurement m = read_measurement(path, o);
    CHECK(m.invalid == 1);
    REQUIRE(m.points.size() == 5);
    // Lateral: index × (5e-7 m × 1000 mm/m); heights µm → mm.
    CHECK(m.points[0].x() == 10 * (5e-07 * 1000));
    CHECK(m.points[0].y() == 20 * (5e-07 * 1000));
    CHECK(m.points[0].z() == 0.125 * 1e-3);
    CHECK(m.points[1].z() == -0.25 * 1e-3);
    CHECK(m.points[2].x() == 10 * (5e-07 * 1000));
    CHECK(m.points[2].y() == 21 * (5e-07 * 1000));
    CHECK(m.points[2].z() == 1e-3 * 1e-3);
    CHECK(m.points[4].z() == 2 * 1e-3);
  }

  TEST_CASE("Zygo XYZ: a truncated or inconsistent file is refused at its line") {
    test::TempDir dir;
    MeasurementFileOptions o;
    o.format = MeasurementFormat::kZygoXyz;
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("short.xyz", "Zygo XYZ Data File\n1 2 3\n"), o),
                         doctest::Contains("short.xyz:2:1: the Zygo XYZ header is truncated"),
                         InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("short.xyz", "Zygo XYZ Data File\n1 2 3\n"), o),
                         doctest::Contains("and the file ends after 2 lines"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("empty.xyz", ""), o),
                         doctest::Contains("empty.xyz: the measurement file is empty"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("cut.xyz", zygo_file("10 20 3 2", 4)), o),
                         doctest::Contains("holds 4 pixels, the header (line 4) says 3 × 2 = 6: truncated"),
                         InputError);
    CHECK_THROWS_WITH_AS(
        read_measurement(dir.write("size.xyz", zygo_file("10 20 3", 6)), o),
        doctest::Contains("size.xyz:4:1: the phase origin and size line must hold 4 numbers"),
        InputError);
    CHECK_THROWS_WITH_AS(
        read_measurement(dir.write("out.xyz", zygo_file("10 20 2 2", 6)), o),
        doctest::Contains("out.xyz:18:1: pixel (12, 20) is outside the header's phase area"),
        InputError);
  }

  TEST_CASE("a field that is not a number is refused at its line and column") {
    test::TempDir dir;
    MeasurementFileOptions o;
    o.format = MeasurementFormat::kZygoXyz;
    const auto replaced = [](std::string text, const std::string& from, const std::string& to) {
      return text.replace(text.find(from), from.size(), to);
    };
    // Line 17 is the second pixel, "11 20 -0.2x5": its height starts in column 7.
    CHECK_THROWS_WITH_AS(
        read_measurement(
            dir.write("h.xyz", replaced(zygo_file("10 20 3 2", 6), "11 20 -0.25", "11 20 -0.2x5")),
            o),
        doctest::Contains("h.xyz:17:7: the height '-0.2x5' is not a finite number"), InputError);
    // Line 8's seventh field, after "0 0.5 6.328e-07 0 1 1 " (22 characters).
    CHECK_THROWS_WITH_AS(
        read_measurement(
            dir.write("r.xyz", replaced(zygo_file("10 20 3 2", 6), " 5e-07 ", " -5e-07 ")), o),
        doctest::Contains("r.xyz:8:23: the camera resolution must be greater than 0"), InputError);
    o.format = MeasurementFormat::kXyz;
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("p.xyz", "0 0 5\n1  0 z5\n"), o),
                         doctest::Contains("p.xyz:2:6: a point is 'x y z'"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("p.xyz", "0 0 5\n1  0 z5\n"), o),
                         doctest::Contains(": 'z5' is not a finite number"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("f.xyz", "0 0 5\n1 0 5 6\n"), o),
                         doctest::Contains("f.xyz:2:7: a point is 'x y z'"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("f.xyz", "0 0 5\n1 0 5 6\n"), o),
                         doctest::Contains("field 4 is one too many"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("s.xyz", "0 0 5\n1 0\n"), o),
                         doctest::Contains("s.xyz:2:1: a point is 'x y z'"), InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("s.xyz", "0 0 5\n1 0\n"), o),
                         doctest::Contains("the line holds 2 fields"), InputError);
    o.format = MeasurementFormat::kCsv;  // an empty y: the third byte of "1,,4"
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("e.csv", "0,0,5\n1,,4\n"), o),
                         doctest::Contains("e.csv:2:3: a point is 'x y z'"), InputError);
    o.format = MeasurementFormat::kGrid;
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("g.csv", ",0,1\n0,1,x\n"), o),
                         doctest::Contains("g.csv:2:5: the height 'x' is not a finite number"),
                         InputError);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("g.csv", ",0, a\n0,1,2\n"), o),
                         doctest::Contains("g.csv:1:5: the column's x 'a' is not a finite number"),
                         InputError);
  }

  TEST_CASE("xyz, csv, grid and profile files: units applied, invalid points masked, not zero") {
    test::TempDir dir;
    MeasurementFileOptions o;
    o.lateral_scale = 1;
    o.height_scale = 1e-6;  // nm
    const Measurement xyz = read_measurement(dir.write("p.xyz", "x y z\n0 0 5\n1 0 nan\n0 1 -7\n"), o);
    CHECK(xyz.invalid == 1);
    REQUIRE(xyz.points.size() == 2);
    CHECK(xyz.points[1].z() == -7e-6);
    o.format = MeasurementFormat::kCsv;
    const Measurement csv = read_measurement(dir.write("p.csv", "0,0,5\n1,0,\n2,0,3\n"), o);
    CHECK(csv.invalid == 1);
    CHECK(csv.points.size() == 2);
    o.format = MeasurementFormat::kGrid;
    const Measurement grid = read_measurement(dir.write("g.csv", ",0,0.5,1\n0,1,2,\n1,4,nan,6\n"), o);
    CHECK(grid.invalid == 2);
    REQUIRE(grid.points.size() == 4);
    CHECK(grid.points[3].x() == 1);
    CHECK(grid.points[3].y() == 1);
    CHECK(grid.points[3].z() == 6e-6);
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("bad.csv", ",0,1\n0,1\n"), o),
                         doctest::Contains("bad.csv:2:1: the row has 2 cells, the first row 3"),
                         InputError);
    o.format = MeasurementFormat::kProfile;
    const Measurement profile = read_measurement(dir.write("p.txt", "0 1\n0.5 2\n"), o);
    CHECK(profile.profile);
    CHECK(profile.points[1] == Eigen::Vector3d(0.5, 0, 2e-6));
    o.format = MeasurementFormat::kXyz;
    CHECK_THROWS_WITH_AS(read_measurement(dir.write("none.xyz", "0 0 nan\n"), o),
                         doctest::Contains("holds no valid point (1 marked invalid)"), InputError);
  }
}
