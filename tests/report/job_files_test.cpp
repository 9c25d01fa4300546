#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/pipeline/run_pipeline.hpp"
#include "freeturn/report/cl_file.hpp"
#include "freeturn/report/run_job.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

std::vector<std::vector<double>> read_csv_rows(const std::string& text, std::string& header) {
  std::istringstream in(text);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::size_t start = 0;
    while (start <= line.size()) {
      std::size_t end = line.find(',', start);
      if (end == std::string::npos) end = line.size();
      double v = 0;
      std::from_chars(line.data() + start, line.data() + end, v);
      row.push_back(v);
      start = end + 1;
    }
    rows.push_back(row);
  }
  return rows;
}

struct PluginPaths {
  PluginPaths() {
    setenv("FREETURN_PLUGIN_PATH", FREETURN_PLUGIN_DIR, 1);
    setenv("FREETURN_MACHINE_PATH", FREETURN_MACHINE_DIR, 1);
  }
};

// A concave sphere (R 50 mm) over 1 mm on the LinuxCNC X-Z-C lathe: 20 turns at 0.05 mm.
std::string sphere_job(const std::string& outputs) {
  return "name: plate\naperture: {outer_radius: 1.0}\nsurface: {type: sphere, radius: 50.0}\n"
         "tool:\n  nose_radius: 0.5\n"
         "strategy:\n  mode: spiral\n  spiral: planar\n  pitch: 0.05\n"
         "  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}\n"
         "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n" + outputs;
}

struct Streamed final : RunObserver {
  std::vector<CutterLocation> locations;
  std::vector<AxisRecord> records;
  void cutter_locations(const std::string&, std::span<const CutterLocation> l,
                        std::span<const AxisRecord> r) override {
    locations.insert(locations.end(), l.begin(), l.end());
    records.insert(records.end(), r.begin(), r.end());
  }
};

}  // namespace

TEST_SUITE("report") {
  TEST_CASE("the CL file reads back as the very doubles written") {
    test::TempDir dir;
    CutterLocation cl;
    cl.contact.theta = 1.0 / 3;
    cl.contact.point = {0.1, -2.0 / 7, 1e-300};
    cl.contact.normal = {std::sqrt(0.5), -std::sqrt(0.5), 0};
    cl.nose_centre = {std::nextafter(1.0, 2.0), 5e-324, -0.0};
    cl.b = 0.25;
    cl.contact.chord_error = 3.5e-7;
    AxisRecord r;
    r.x = 1.234567890123456;
    r.z = -0.000123;
    r.c = 359.99999999999994;
    r.b = 14.32394487827058;
    {
      AtomicFile out(dir.file("a.cl.csv"));
      ClFile file(out, 1e6);
      file.write(std::span<const CutterLocation>(&cl, 1), std::span<const AxisRecord>(&r, 1));
      out.commit();
    }
    std::string header;
    const auto rows = read_csv_rows(test::read_file(dir.file("a.cl.csv")), header);
    CHECK(header ==
          "theta_rad,x_mm,y_mm,z_mm,nx,ny,nz,tx_mm,ty_mm,tz_mm,b_deg,X_mm,Z_mm,C_deg,B_deg,chord_mm");
    REQUIRE(rows.size() == 1);
    const std::vector<double> expected = {cl.contact.theta, 0.1, -2.0 / 7, 1e-300,
                                          std::sqrt(0.5), -std::sqrt(0.5), 0,
                                          std::nextafter(1.0, 2.0), 5e-324, -0.0,
                                          0.25 * 180 / 3.14159265358979323846,
                                          r.x, r.z, r.c, r.b, 3.5e-7};
    REQUIRE(rows[0].size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) CHECK(rows[0][i] == expected[i]);
  }

  TEST_CASE("a CL file past its byte bound stops at limits.max_file_mb") {
    test::TempDir dir;
    AtomicFile out(dir.file("b.cl.csv"));
    // The header is 89 bytes; one row of zeros is 32 ("0," fifteen times, "0\n").
    ClFile file(out, 89 + 32);
    const CutterLocation cl;
    const AxisRecord r;
    file.write(std::span<const CutterLocation>(&cl, 1), std::span<const AxisRecord>(&r, 1));
    CHECK_THROWS_WITH_AS(
        file.write(std::span<const CutterLocation>(&cl, 1), std::span<const AxisRecord>(&r, 1)),
        doctest::Contains("limits.max_file_mb"), InputError);
  }

  TEST_CASE("run_pipeline writes the programs and leaves every other file to its RunFiles") {
    const PluginPaths paths;
    test::TempDir dir;
    const Job job = load_job(dir.write("plate.yaml", sphere_job("outputs: {cl_csv: true}\n")));
    struct CountingFiles final : RunFiles {
      long rows = 0, finished = 0;
      void finishing_chunk(std::span<const CutterLocation> l, std::span<const AxisRecord> r) override {
        CHECK(l.size() == r.size());
        rows += static_cast<long>(r.size());
      }
      void finish(const Job&, const RunReport&, const Surface&, const std::string&,
                  OutputSet&) override {
        ++finished;
      }
    } counting;
    RunOptions options;
    options.output_dir = dir.file("own");
    const RunResult own = run_pipeline(job, options, counting);
    CHECK(own.files == std::vector<std::string>{dir.file("own/plate.iso-lathe-xzc.nc")});
    CHECK(counting.finished == 1);
    CHECK(counting.rows == own.report.passes.back().points);

    // run_job adds the job's own files: the CL rows are the streamed locations, exactly.
    Streamed streamed;
    options.output_dir = dir.file("job");
    const RunResult full = run_job(job, options, &streamed);
    CHECK(std::filesystem::exists(dir.file("job/plate.report.json")));
    CHECK(std::filesystem::exists(dir.file("job/plate.report.html")));
    std::string header;
    const auto rows = read_csv_rows(test::read_file(dir.file("job/plate.cl.csv")), header);
    REQUIRE(rows.size() == streamed.locations.size());
    CHECK(static_cast<long>(rows.size()) == full.report.passes.back().points);
    for (std::size_t k = 0; k < rows.size(); k += 97) {
      CHECK(rows[k][0] == streamed.locations[k].contact.theta);
      CHECK(rows[k][3] == streamed.locations[k].contact.point.z());
      CHECK(rows[k][11] == streamed.records[k].x);
      CHECK(rows[k][13] == streamed.records[k].c);
    }
  }
}
