#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

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
         "tool:\n  nose_radius: 0.5\n" +
         checks +
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

// The programmed positions (X, C, Z; C 0 where the program has none) of the cut in the NC
// file `nc`: the plunge's target (the program's first G1 block) and every G1 block after it.
std::vector<std::array<double, 3>> cut_positions(const std::string& nc) {
  std::vector<std::array<double, 3>> cut;
  std::array<double, 3> at{0, 0, 0};
  for (const NcBlock& b : parse_nc(test::read_file(nc), nc)) {
    bool g1 = false;
    for (const NcWord& w : b.words) {
      if (!w.numeric) continue;
      if (w.letter == 'G' && w.value == 1) g1 = true;
      if (w.letter == 'X') at[0] = w.value;
      if (w.letter == 'C') at[1] = w.value;
      if (w.letter == 'Z') at[2] = w.value;
    }
    if (g1) cut.push_back(at);
  }
  return cut;
}

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
    // A sphere of radius 2 mm decentred 0.5 mm: about the axis its flank faces the cut at
    // atan(0.5/√(4 − 0.25)) = 14.48° and more, past the tool's 10° clearance.
    const std::string tight =
        "name: cup\naperture: {outer_radius: 0.2}\n"
        "surface: {type: sphere, radius: 2.0, decenter: {x: 0.5}}\n"
        "tool:\n  nose_radius: 0.1\nCHECKS"
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
    const RunReport r =
        check_job(job_with("warn.yaml", "  checks: {clearance: warning}\n"), {}, &observer);
    REQUIRE_FALSE(r.safe());
    CHECK(r.unsafe_reasons().front().find("clearance") != std::string::npos);
    // The same finding as a record: its kind, where, by how much, against what.
    const ReportWarning& w = r.warnings.front();
    CHECK(w.severity == ReportWarning::Severity::kUnsafe);
    CHECK(w.kind == "clearance");
    CHECK(w.value >= 14.47);
    CHECK(w.limit == doctest::Approx(10.0));
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
    // The report's block charts read the controller's cubics as the mapper judges them:
    // their largest values are the pass's peaks (every block drawn: fewer than 4000).
    for (const PassFigures& f : a.report.passes) {
      REQUIRE(f.block_stride == 1);
      for (int axis = 0; axis < 3; ++axis) {
        double v = 0, acc = 0;
        for (const BlockPoint& q : f.blocks)
          v = std::max(v, std::abs(q.v[axis])), acc = std::max(acc, std::abs(q.a[axis]));
        CAPTURE(axis);
        CHECK(v == doctest::Approx(f.dynamics.peak_velocity[axis]).epsilon(1e-9));
        CHECK(acc == doctest::Approx(f.dynamics.peak_acceleration[axis]).epsilon(1e-9));
      }
    }
    REQUIRE(a.files.size() == b.files.size());
    REQUIRE(a.files.size() >= 3);  // two programs and the report
    for (std::size_t i = 0; i < a.files.size(); ++i) {
      const std::filesystem::path name = std::filesystem::path(a.files[i]).filename();
      CHECK(std::filesystem::path(b.files[i]).filename() == name);
      CHECK_MESSAGE(test::read_file(a.files[i]) == test::read_file(b.files[i]), name);
    }
  }

  TEST_CASE("equal-angle blocks stand off the design: the motion between them stays above it") {
    // A convex sphere (R −5 mm) decentred 0.5 mm in x, 64 blocks a revolution on the X-Z-C
    // lathe: Z swings with θ, and linear X, C, Z between blocks sags below the nose's path
    // by about Z''(θ)Δθ²/8, some 0.2 µm, all of it into the dome where the blocks sat on it.
    const PluginPaths paths;
    test::TempDir dir;
    const std::string text =
        "name: dome\naperture: {outer_radius: 2.0}\n"
        "surface: {type: sphere, radius: -5.0, decenter: {x: 0.5}}\n"
        "tool: {nose_radius: 0.5, included_angle_deg: 100, clearance_angle_deg: 10}\n"
        "strategy:\n  mode: spiral\n  spiral: planar\n  pitch: 0.05\n"
        "  points: {equal_angle: {per_rev: 64}}\n"
        "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n";
    RunOptions options;
    options.output_dir = dir.file("out");
    const RunResult r = run_job(load_job(dir.write("dome.yaml", text)), options);
    CHECK(r.safe());
    const double stand_off = r.report.parameters.stand_off;
    CHECK(stand_off > 50e-6);  // the dip it covers is a sizeable fraction of a micrometre
    CHECK(stand_off < 1e-3);
    // The dome in the part's frame: the parent's centre (0, 0, −5) moved by −(0.5, 0) and
    // down by the parent's sag at (0.5, 0). The nose's edge is the arc of radius 0.5 about
    // the programmed centre (X cos C, X sin C, Z) in the radial plane, ±50° about −z; its
    // height over the dome is |E − c| − 5, found by sampling the arc and refining by golden
    // sections (the distance is smooth and single-troughed over the arc).
    const Eigen::Vector3d centre(-0.5, 0.0, -5.0 - (-5.0 + std::sqrt(25.0 - 0.25)));
    const auto clearance = [&](double x, double c_deg, double z) {
      const double c = c_deg * std::numbers::pi / 180;
      const Eigen::Vector3d p(x * std::cos(c), x * std::sin(c), z),
          radial(std::cos(c), std::sin(c), 0);
      const auto height = [&](double phi) {
        const Eigen::Vector3d e =
            p - 0.5 * (std::sin(phi) * radial + std::cos(phi) * Eigen::Vector3d::UnitZ());
        return (e - centre).norm() - 5.0;
      };
      const double half = 50 * std::numbers::pi / 180;
      double best = -half;
      for (int k = 0; k <= 200; ++k) {
        const double phi = -half + 2 * half * k / 200;
        if (height(phi) < height(best)) best = phi;
      }
      double a = std::max(-half, best - 2 * half / 200), b = std::min(half, best + 2 * half / 200);
      for (int it = 0; it < 60; ++it) {
        const double m1 = a + 0.382 * (b - a), m2 = a + 0.618 * (b - a);
        (height(m1) < height(m2) ? b : a) = height(m1) < height(m2) ? m2 : m1;
      }
      return height(0.5 * (a + b));
    };
    double lowest = 1e300, lowest_block = 1e300;
    const auto cut = cut_positions(dir.file("out/dome.iso-lathe-xzc.nc"));
    for (std::size_t i = 1; i < cut.size(); ++i) {
      const auto& [x, c, z] = cut[i - 1];
      const auto& [nx, nc_deg, nz] = cut[i];
      for (int k = 1; k <= 16; ++k) {
        const double t = k / 16.0;
        lowest =
            std::min(lowest, clearance(x + t * (nx - x), c + t * (nc_deg - c), z + t * (nz - z)));
      }
      lowest_block = std::min(lowest_block, clearance(nx, nc_deg, nz));
    }
    CHECK(static_cast<long>(cut.size()) == r.report.passes.back().points);
    // Every block stands off by the stand-off the report gives, along the radial section's
    // normal: as a distance in space that is shorter by the cosine of the dome's slope
    // across the section (below 0.1 here, under 1 %), give or take the words' rounding
    // (1.2 nm).
    CHECK(lowest_block <= stand_off + 1.5e-6);
    CHECK(lowest_block >= 0.99 * stand_off - 1.5e-6);
    CHECK(lowest >= 0);
    CHECK(lowest < stand_off);  // the chords do sag: the stand-off is what holds them up
  }

  TEST_CASE("a profile's equal arcs stand off a dome, its last one joined without a jump") {
    // A convex sphere (R −8 mm) turned in profile on the X-Z lathe at 0.2 mm arcs: each
    // chord of the nose centre's circle (R 8.5 mm) sags L²/(8·8.5) ≈ 0.59 µm below it. The
    // last arc, a sliver joined to the one before, had been read as a jump against the
    // chord rule's tolerance once the blocks stood off.
    const PluginPaths paths;
    test::TempDir dir;
    const std::string text =
        "name: dome\naperture: {outer_radius: 5.0}\nsurface: {type: sphere, radius: -8.0}\n"
        "tool: {nose_radius: 0.5, included_angle_deg: 120, clearance_angle_deg: 10}\n"
        "strategy:\n  mode: profile\n  points: {equal_arc: {length: 0.2}}\n"
        "cutting: {feed: 5}\nmachine: iso-lathe-xz\n";
    RunOptions options;
    options.output_dir = dir.file("out");
    const RunResult r = run_job(load_job(dir.write("dome.yaml", text)), options);
    CHECK(r.safe());
    CHECK(r.report.warnings.empty());
    // The edge's arc (±60° about −z) over the dome, centre (0, −8), along every segment.
    double lowest = 1e300;
    const auto cut = cut_positions(dir.file("out/dome.iso-lathe-xz.nc"));
    REQUIRE(static_cast<long>(cut.size()) == r.report.passes.back().points);
    for (std::size_t i = 1; i < cut.size(); ++i) {
      const double x = cut[i - 1][0], z = cut[i - 1][2], nx = cut[i][0], nz = cut[i][2];
      for (int k = 1; k <= 64; ++k) {
        const double t = k / 64.0, px = x + t * (nx - x), pz = z + t * (nz - z);
        for (int j = -1000; j <= 1000; ++j) {
          const double phi = j * (std::numbers::pi / 3) / 1000;
          lowest = std::min(
              lowest, std::hypot(px - 0.5 * std::sin(phi), pz - 0.5 * std::cos(phi) + 8.0) - 8.0);
        }
      }
    }
    CHECK(lowest >= 0);
    CHECK(lowest < r.report.parameters.stand_off);
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
