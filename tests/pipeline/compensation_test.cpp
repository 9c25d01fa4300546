#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/pipeline/run_pipeline.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

struct Paths {
  Paths() {
    setenv("FREETURN_PLUGIN_PATH", FREETURN_PLUGIN_DIR, 1);
    setenv("FREETURN_MACHINE_PATH", FREETURN_MACHINE_DIR, 1);
  }
};

// A concave sphere, R 50 mm: z = r² / (R (1 + √(1 − r²/R²))).
double sphere(double x, double y) {
  const double r2 = x * x + y * y;
  return r2 / (50 * (1 + std::sqrt(1 - r2 / 2500)));
}

// The part's error: astigmatism Z6 = √6 ρ² cos 2φ, 0.2 µm, over R_n = 2 mm.
double astigmatism(double x, double y) {
  return 0.2e-3 * std::sqrt(6.0) * (x * x - y * y) / 4;
}

std::string job_text(const std::string& compensation) {
  return "name: plate\naperture: {outer_radius: 2.0}\nsurface: {type: sphere, radius: 50.0}\n" +
         compensation +
         "tool:\n  nose_radius: 0.5\nstrategy:\n  mode: spiral\n  spiral: planar\n  pitch: 0.05\n"
         "  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}\n"
         "cutting: {spindle_rpm: 20}\nmachine: iso-lathe-xzc\n";
}

}  // namespace

TEST_SUITE("pipeline") {
  TEST_CASE("compensation: the path's contact points lie on design − gain × the measured error") {
    const Paths paths;
    test::TempDir dir;
    // The measured part, heights in nm on a 0.05 mm grid: the sphere plus the astigmatism
    // and a 3 µm piston (the instrument's zero is not the part's).
    std::string xyz = "x y z\n";
    for (double x = -2; x <= 2 + 1e-9; x += 0.05)
      for (double y = -2; y <= 2 + 1e-9; y += 0.05) {
        if (std::hypot(x, y) > 2) continue;
        xyz += shortest_text(x) + " " + shortest_text(y) + " " +
               shortest_text((sphere(x, y) + astigmatism(x, y) + 3e-3) * 1e6) + "\n";
      }
    dir.write("part1.xyz", xyz);
    const Job job = load_job(dir.write(
        "plate.yaml", job_text("compensation:\n  measured: part1.xyz\n  height_unit: nm\n"
                               "  gain: 0.8\n  register: [piston]\n  fit: {zernike: 10}\n")));
    REQUIRE(job.compensation.size() == 1);
    const Registration& r = job.compensation[0].registration;
    CHECK(r.piston == doctest::Approx(-3e-3).epsilon(1e-9));
    CHECK(r.zernike[5] == doctest::Approx(0.2e-3).epsilon(1e-6));
    const PlannedPath path = plan_job(job);
    REQUIRE(path.locations.size() > 1000);
    double worst = 0;
    for (const CutterLocation& cl : path.locations) {
      const double x = cl.contact.point.x(), y = cl.contact.point.y();
      worst = std::max(worst, std::abs(cl.contact.point.z() - (sphere(x, y) - 0.8 * astigmatism(x, y))));
    }
    MESSAGE("contact points off design − 0.8 × error by at most " << worst * 1e6 << " nm");
    CHECK(worst <= 1e-6);
  }

  TEST_CASE("compensation: two measured parts add up; bad entries are located") {
    const Paths paths;
    test::TempDir dir;
    std::string a = "x y z\n", b = "x y z\n";
    for (double x = -2; x <= 2 + 1e-9; x += 0.1)
      for (double y = -2; y <= 2 + 1e-9; y += 0.1) {
        if (std::hypot(x, y) > 2) continue;
        a += shortest_text(x) + " " + shortest_text(y) + " " + shortest_text(sphere(x, y) + astigmatism(x, y)) + "\n";
        b += shortest_text(x) + " " + shortest_text(y) + " " + shortest_text(sphere(x, y) + 0.25 * astigmatism(x, y)) + "\n";
      }
    dir.write("a.xyz", a);
    dir.write("b.xyz", b);
    const Job job = load_job(dir.write(
        "plate.yaml", job_text("compensation:\n  - {measured: a.xyz, register: [piston], fit: {zernike: 10}}\n"
                               "  - {measured: b.xyz, register: [piston], fit: {zernike: 10}}\n")));
    REQUIRE(job.compensation.size() == 2);
    // design − 1 × (E + E/4) at a point off the axis.
    CHECK(job.surface->sag(1.2, 0.5) ==
          doctest::Approx(sphere(1.2, 0.5) - 1.25 * astigmatism(1.2, 0.5)).epsilon(1e-12).scale(1));
    CHECK_THROWS_WITH_AS(load_job(dir.write("f.yaml", job_text("compensation: {measured: a.xyz, format: dat}\n"))),
                         doctest::Contains("f.yaml:4:41: compensation.format must be zygo_xyz"), InputError);
    CHECK_THROWS_WITH_AS(load_job(dir.write("g.yaml", job_text("compensation: {measured: a.xyz, register: [spin]}\n"))),
                         doctest::Contains("g.yaml:4:44: compensation.register takes piston"), InputError);
    CHECK_THROWS_WITH_AS(load_job(dir.write("h.yaml", job_text("compensation: {measured: none.xyz}\n"))),
                         doctest::Contains("none.xyz"), InputError);
  }
}
