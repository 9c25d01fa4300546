#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/io/nc_program.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/pipeline/run_pipeline.hpp"
#include "freeturn/report/run_job.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

// A concave sphere (R 50 mm) over 2 mm on the LinuxCNC X-Z-C lathe: 40 turns at 0.05 mm.
std::string sphere_job(const std::string& checks) {
  return "name: plate\naperture: {outer_radius: 2.0}\nsurface: {type: sphere, radius: 50.0}\n"
         "tool:\n  nose_radius: 0.5\n" + checks +
         "strategy:\n  mode: spiral\n  spiral: planar\n  pitch: 0.05\n"
         "  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}\n"
         "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n";
}

struct Recorder final : RunObserver {
  std::vector<std::string> warnings, passes_done;
  long progress_calls = 0, last_points = 0;
  double last_r = -1;
  void warning(const std::string& text) override { warnings.push_back(text); }
  void progress(const std::string&, double, double r, long points) override {
    ++progress_calls;
    last_r = r;
    last_points = points;
  }
  void pass_done(const std::string& pass) override { passes_done.push_back(pass); }
};

struct PluginPaths {
  PluginPaths() {
    setenv("FREETURN_PLUGIN_PATH", FREETURN_PLUGIN_DIR, 1);
    setenv("FREETURN_MACHINE_PATH", FREETURN_MACHINE_DIR, 1);
  }
};

}  // namespace

TEST_SUITE("pipeline") {
  TEST_CASE("run_job writes the program, tells the observer, and returns the figures") {
    const PluginPaths paths;
    test::TempDir dir;
    const Job job = load_job(dir.write("plate.yaml", sphere_job("")));
    Recorder observer;
    RunOptions options;
    options.output_dir = dir.file("out");
    const RunResult r = run_job(job, options, &observer);
    CHECK(r.safe());
    REQUIRE(r.report.passes.size() == 1);
    const PassFigures& f = r.report.passes.back();
    // A planar spiral from r = 2 to 0 at 0.05 mm a turn: 40 revolutions.
    CHECK(f.revolutions == doctest::Approx(40).epsilon(1e-9));
    CHECK(f.chord_max <= 1e-3);
    // The observer saw the pass stream to the centre, and end.
    CHECK(observer.progress_calls >= 1);
    CHECK(observer.last_r == doctest::Approx(0).scale(1));
    CHECK(observer.last_points == f.points);
    CHECK(observer.passes_done == std::vector<std::string>{"finish"});
    CHECK(observer.warnings.empty());
    // The program written holds one G1 block per point after the first.
    const std::string nc = dir.file("out/plate.iso-lathe-xzc.nc");
    REQUIRE(std::find(r.files.begin(), r.files.end(), nc) != r.files.end());
    long g1 = 0;
    for (const NcBlock& b : parse_nc(test::read_file(nc), nc))
      for (const NcWord& w : b.words)
        if (w.numeric && w.letter == 'G' && w.value == 1) ++g1;
    CHECK(g1 == f.points);  // the plunge to the first point, then one per later point
  }

  TEST_CASE("check_job: a PASS, an UNSAFE program with its reasons, a check that stops it") {
    const PluginPaths paths;
    test::TempDir dir;
    // A 0.5 mm nose in a 0.3 mm concave sphere's section cannot follow it.
    const std::string tight = "name: cup\naperture: {outer_radius: 0.1}\nsurface: {type: sphere, radius: 0.3}\n"
                              "tool:\n  nose_radius: 0.5\nCHECKS"
                              "strategy:\n  mode: spiral\n  spiral: planar\n  pitch: 0.01\n"
                              "  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}\n"
                              "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n";
    const auto job_with = [&](const std::string& name, const std::string& checks) {
      std::string text = tight;
      text.replace(text.find("CHECKS"), 6, checks);
      return load_job(dir.write(name, text));
    };
    CHECK(check_job(load_job(dir.write("plate.yaml", sphere_job("")))).safe());
    CHECK_THROWS_AS(check_job(job_with("stop.yaml", "")), CheckFailure);
    Recorder observer;
    const RunReport r = check_job(
        job_with("warn.yaml", "  checks: {gouge: warning, global_gouge: warning}\n"), {}, &observer);
    REQUIRE_FALSE(r.safe());
    CHECK(r.unsafe_reasons().front().find("gouge") != std::string::npos);
    // The same finding as a record: its kind, where, by how much, against what.
    const ReportWarning& w = r.warnings.front();
    CHECK(w.severity == ReportWarning::Severity::kUnsafe);
    CHECK((w.kind == "local_gouge" || w.kind == "global_gouge"));
    CHECK(w.pass == "finish");
    CHECK(w.count > 0);
    CHECK(w.r_mm >= 0);
    CHECK(w.r_mm <= 2.0);
    CHECK(w.theta_deg >= 0);
    CHECK(w.theta_deg < 360);
    CHECK(std::hypot(w.x_mm, w.y_mm) == doctest::Approx(w.r_mm).epsilon(1e-9));
    CHECK_FALSE(observer.warnings.empty());
    // Nothing is written by a check: the folder holds the three jobs alone.
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 3);
  }

  TEST_CASE(
      "a constant-rpm run written from the probe's kept path is the same bytes as one planned "
      "twice") {
    // The Precitech's dialect keeps one block time: the run finds the highest rpm every
    // block allows, then writes at it. With a roughing pass, two paths are kept.
    const PluginPaths paths;
    test::TempDir dir;
    std::string text = sphere_job("");
    text.replace(text.find("cutting: {spindle_rpm: 20}"), 26,
                 "cutting: {spindle_rpm: 2000, roughing: [0.01]}");
    text.replace(text.find("iso-lathe-xzc"), 13, "precitech-nanoform-250");
    const Job job = load_job(dir.write("plate.yaml", text));
    RunOptions kept, planned_twice;
    kept.output_dir = dir.file("kept");
    planned_twice.output_dir = dir.file("twice");
    planned_twice.max_replay_bytes = 0;
    const RunResult a = run_job(job, kept), b = run_job(job, planned_twice);
    REQUIRE(a.report.passes.size() == 2);
    // The speed is the machine's, not the job's: the probe's answer was used.
    CHECK(a.report.spindle_rpm < 2000);
    CHECK(a.report.spindle_rpm == b.report.spindle_rpm);
    REQUIRE(a.files.size() == b.files.size());
    REQUIRE(a.files.size() >= 3);  // two programs and the report
    for (std::size_t i = 0; i < a.files.size(); ++i) {
      const std::filesystem::path name = std::filesystem::path(a.files[i]).filename();
      CHECK(std::filesystem::path(b.files[i]).filename() == name);
      CHECK_MESSAGE(test::read_file(a.files[i]) == test::read_file(b.files[i]), name);
    }
  }

  TEST_CASE("an error is an exception with the place of the setting that causes it") {
    const PluginPaths paths;
    test::TempDir dir;
    std::string text = sphere_job("");
    text.replace(text.find("iso-lathe-xzc"), 13, "no-such-lathe");
    const Job job = load_job(dir.write("plate.yaml", text));
    CHECK_THROWS_WITH_AS(run_job(job), doctest::Contains("plate.yaml:12:10: "), InputError);
  }
}
