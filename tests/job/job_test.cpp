#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "freeturn/core/error.hpp"
#include "freeturn/io/iges_surface.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "test_files.hpp"

using freeturn::InputError;
using freeturn::load_job;
using freeturn::test::TempDir;

namespace {

std::string error_of(const std::string& yaml) {
  TempDir dir;
  const std::string path = dir.write("job.yaml", yaml);
  try {
    load_job(path);
  } catch (const InputError& e) {
    // Report relative to the file name so the table below is readable.
    std::string m = e.what();
    return m.replace(0, path.size(), "job.yaml");
  }
  return "no error";
}

const char* kGood =
    "name: lens-1\n"
    "aperture: {outer_radius: 5, inner_radius: 1}\n"
    "surface: {type: even_asphere, radius: 20, conic: -1, A4: 1e-4}\n";

}  // namespace

TEST_SUITE("job") {
  TEST_CASE("a good job loads with its values") {
    TempDir dir;
    const auto job = load_job(dir.write("job.yaml", kGood));
    CHECK(job.name == "lens-1");
    CHECK(job.aperture.outer_radius == 5.0);
    CHECK(job.aperture.inner_radius == 1.0);
    double z, zx, zy;
    job.surface->sag_gradient(2.0, 0.0, z, zx, zy);
    CHECK(z == doctest::Approx(4.0 / 40.0 + 1e-4 * 16).epsilon(1e-15));  // r²/2R + A4 r⁴
  }

  TEST_CASE("bad jobs give file:line:col and what is wrong") {
    struct Case {
      const char* yaml;
      const char* message;
    };
    const Case cases[] = {
        {"name: a\naperture: {outer_radius: 5\n",
         "job.yaml:3:1: YAML syntax error: end of map flow not found"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere, radius: 20}\nfoo: 1\n",
         "job.yaml:4:1: unknown key 'foo' in job"},
        {"name: a\naperture: {outer_radius: -5}\nsurface: {type: plane}\n",
         "job.yaml:2:26: aperture.outer_radius must be greater than 0, not -5"},
        {"name: a\naperture: {outer_radius: .nan}\nsurface: {type: plane}\n",
         "job.yaml:2:26: aperture.outer_radius must be a finite number, not '.nan'"},
        {"name: a\naperture: {outer_radius: five}\nsurface: {type: plane}\n",
         "job.yaml:2:26: aperture.outer_radius must be a number, not 'five'"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere}\n",
         "job.yaml:3:10: surface is missing the key 'radius'"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: torus}\n",
         "job.yaml:3:17: unknown surface type 'torus' (known: plane, sphere, conic, "
         "even_asphere, odd_asphere, biconic, toroidal, xy_polynomial, zernike, qbfs, "
         "sinusoidal_ring, sinusoidal_grid, alvarez, compound_eye, microlens_array, nurbs, "
         "height_grid, point_cloud)"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: compound_eye, base_radius: 20, "
         "lens_radius: -1.5, lens_diameter: 1.2, pitch: 1.0}\n",
         "job.yaml:3:82: a lenslet of diameter 1.2 mm is larger than its pitch 1 mm: neighbours "
         "would overlap"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere, radius: 4}\n",
         "job.yaml:3:33: the surface is undefined beyond r = 4 mm (the conic's square "
         "root goes negative), inside the aperture radius 5 mm"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: zernike, radius: 50, "
         "coefficients: {4: 1e-3}}\n",
         "job.yaml:3:10: surface is missing the key 'normalization_radius'"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: xy_polynomial, radius: 0, "
         "normalization_radius: 5, coefficients: {231: 1e-3}}\n",
         "job.yaml:3:83: surface.coefficients term '231' must be an index from 1 to 230"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: toroidal, radius: 20, "
         "rotation_radius: 3}\n",
         "job.yaml:3:17: the toroidal surface is undefined at (x, y) = (3.125, 0) mm, inside the "
         "aperture radius 5 mm"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: conic, radius: 200, conic: -1, "
         "decenter: {x: 30, z: 1}}\n",
         "job.yaml:3:66: unknown key 'z' in surface.decenter"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: sinusoidal_ring, amplitude: "
         "0.01}\n",
         "job.yaml:3:10: sinusoidal_ring takes exactly one of 'period' (mm) or "
         "'angular_frequency' (rad/mm)"},
        {"name: a b\naperture: {outer_radius: 5}\nsurface: {type: plane}\n",
         "job.yaml:1:7: job name 'a b' must use only letters, digits, '-', '_' and '.' (it "
         "names files)"},
        {"name: -rf\naperture: {outer_radius: 5}\nsurface: {type: plane}\n",
         "job.yaml:1:7: job name '-rf' must begin with a letter, a digit or '_' (it names files: a "
         "leading '-' reads as a command's option)"},
        {"name: ..\naperture: {outer_radius: 5}\nsurface: {type: plane}\n",
         "job.yaml:1:7: job name '..' must begin with a letter, a digit or '_' (it names files: a "
         "leading '.' hides them)"},
        {"name: a\naperture: {outer_radius: 5, inner_radius: 6}\nsurface: {type: plane}\n",
         "job.yaml:2:43: aperture.inner_radius must be smaller than outer_radius"},
        {"name: a\naperture: [5]\nsurface: {type: plane}\n",
         "job.yaml:2:11: aperture must be a map of keys to values"},
        {"", "job.yaml: the job file is empty"},
    };
    for (const Case& c : cases) {
      const std::string yaml = c.yaml;
      CAPTURE(yaml);
      CHECK(error_of(yaml) == std::string(c.message));
    }
  }

  TEST_CASE("a missing file is an input error naming it") {
    CHECK_THROWS_WITH_AS(load_job("/nonexistent/job.yaml"),
                         "/nonexistent/job.yaml: no such file", InputError);
  }
}

TEST_SUITE("job") {
  TEST_CASE("bad run sections give file:line:col and what is wrong") {
    const std::string head =
        "name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere, radius: 20}\n";
    const std::string good_tool = "tool: {nose_radius: 0.5}\n";
    const std::string good_strategy =
        "strategy: {mode: spiral, spiral: planar, pitch: 0.01, points: {equal_angle: {per_rev: 90}}}\n";
    const std::string good_rest = "cutting: {spindle_rpm: 10}\nmachine: iso-lathe-xzc\n";
    struct Case {
      std::string yaml;
      const char* message;
    };
    const Case cases[] = {
        {head + "tool: {nose_radius: -0.5}\n" + good_strategy + good_rest,
         "job.yaml:4:21: tool.nose_radius must be within (0, 100] mm, not -0.5"},
        {head + "tool: {nose_radius: .nan}\n" + good_strategy + good_rest,
         "job.yaml:4:21: tool.nose_radius must be a finite number"},
        {head + "tool: {nose_radius: 0.5, colour: red}\n" + good_strategy + good_rest,
         "job.yaml:4:26: unknown key 'colour' in tool"},
        {head + good_tool +
             "strategy: {mode: spiral, spiral: planar, pitch: abc, points: {equal_angle: {per_rev: "
             "90}}}\n" +
             good_rest,
         "job.yaml:5:49: strategy.pitch must be a number, not 'abc'"},
        {head + good_tool + "strategy: {mode: zigzag}\n" + good_rest,
         "job.yaml:5:18: strategy.mode must be spiral or profile, not 'zigzag'"},
        {head + good_tool + "strategy: {mode: profile, points: {equal_angle: {per_rev: 90}}}\n" +
             good_rest,
         "equal_angle points need a spiral"},
        {head + good_tool + "strategy: {mode: spiral, spiral: planar, pitch: 0.01, points: {}}\n" +
             good_rest,
         "strategy.points takes exactly one of equal_angle, equal_arc, chord"},
        {head + good_tool + good_strategy + "cutting: {feed: 3}\nmachine: iso-lathe-xzc\n",
         "cutting is missing the key 'spindle_rpm'"},
        // Under a thousandth the posts' three decimals would print S0.000 or F0.000.
        {head + good_tool + good_strategy +
             "cutting: {spindle_rpm: 1e-9}\nmachine: iso-lathe-xzc\n",
         "job.yaml:6:24: cutting.spindle_rpm must be within [0.001, 20000] rpm, not 1e-9"},
        {head + good_tool + "strategy: {mode: profile, points: {chord: {tolerance: 0.001}}}\n" +
             "cutting: {feed: 0.0004}\nmachine: iso-lathe-xz\n",
         "job.yaml:6:17: cutting.feed must be within [0.001, 10000] mm/min, not 0.0004"},
        {head + good_tool + good_strategy +
             "cutting: {spindle_rpm: 10, roughing: [0.01, 0.02]}\nmachine: m\n",
         "cutting.roughing depths must decrease"},
        {head + good_tool + good_strategy + good_rest.substr(0, good_rest.find("machine")),
         "job is missing the key 'machine'"},
        // A spiral over a ring narrower than its pitch turns less than once: 1 µm of ring at
        // 0.01 mm a turn is a tenth of a revolution.
        {"name: a\naperture: {outer_radius: 5, inner_radius: 4.999}\n"
         "surface: {type: sphere, radius: 20}\n" +
             good_tool + good_strategy + good_rest,
         "job.yaml:5:49: strategy.pitch 0.01 mm is wider than the aperture's ring (0.001 mm from "
         "r = 4.999 to 5 mm): the spiral would turn 0.1 of a revolution"},
    };
    for (const Case& c : cases) {
      CAPTURE(c.yaml);
      const std::string message = error_of(c.yaml);
      CAPTURE(message);
      CHECK(message.find(c.message) != std::string::npos);
    }
  }

  TEST_CASE("a key left to its default is placed at the section that would hold it") {
    TempDir dir;
    const std::string path =
        dir.write("job.yaml",
                  "name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere, radius: 20}\n"
                  "tool:\n  nose_radius: 0.5\nstrategy: {mode: spiral, spiral: planar, pitch: "
                  "0.01, points: {equal_angle: {per_rev: 90}}}\ncutting: {spindle_rpm: 10}\n"
                  "machine: iso-lathe-xzc\n");
    const freeturn::Job job = load_job(path);
    // Given: its own value's place (line 5, column 16).
    CHECK(job.place("tool.nose_radius").to_string() == path + ":5:16");
    // Left out: the tool map's first key (line 5, column 3), where a user would add it.
    CHECK(job.place("tool.included_angle_deg").to_string() == path + ":5:3");
    // No section of it given: the file alone.
    CHECK(job.place("limits.max_points").to_string() == path);
  }

  TEST_CASE("every surface type loads from YAML with its closed-form sag") {
    struct Case {
      const char* surface;
      double x, y, z;
    };
    const double s3 = std::sqrt(3.0);
    const Case cases[] = {
        {"{type: plane}", 1, 2, 0},
        {"{type: sphere, radius: 10}", 3, 4, 10 - std::sqrt(75.0)},
        {"{type: conic, curvature: 0.01, conic: -1}", 3, 4, 0.01 * 25 / 2},
        {"{type: even_asphere, radius: 0, A4: 1e-3, A6: 2e-5}", 1, 1, 1e-3 * 4 + 2e-5 * 8},
        {"{type: biconic, radius_x: 20, radius_y: 0}", 3, 1, 20 - std::sqrt(391.0)},
        {"{type: toroidal, radius: 0, rotation_radius: 0, alpha: [0.01]}", 4, 2, 0.04},
        {"{type: xy_polynomial, radius: 0, normalization_radius: 2, coefficients: {12: 0.5}}", 2, 2,
         0.5},
        {"{type: zernike, radius: 0, normalization_radius: 4, coefficients: [0, 0, 0, 0.01]}", 2, 0,
         0.01 * s3 * (2 * 0.25 - 1)},
        {"{type: sinusoidal_ring, amplitude: 0.1, period: 8, offset: 1}", 0, 2, 1.1},
        {"{type: sinusoidal_grid, amplitude: 0.1, wavelength_x: 4, wavelength_y: 8}", 1, 2, 0.1},
        {"{type: alvarez, A: 0.003, D: 0.1}", 3, 0, 0.003 * 9 + 0.3},
        {"{type: odd_asphere, radius: 0, coefficients: [0.01, 0, 0.002]}", 3, 4,
         0.01 * 5 + 0.002 * 125},
        // Q-bfs on a plane: u²(1 − u²)·a₀ with u² = 25/100.
        {"{type: qbfs, radius: 0, normalization_radius: 10, coefficients: [0.02]}", 3, 4,
         0.25 * 0.75 * 0.02},
        {"{type: qbfs, radius: 0, normalization_radius: 10, coefficients: {1: 0.02}}", 0, 0, 0.0},
        // A bilinear patch z = 0.1x + 0.2y.
        {"{type: nurbs, degree_u: 1, degree_v: 1, knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1], "
         "points: [[-6, -6, -1.8], [-6, 6, 0.6], [6, -6, -0.6], [6, 6, 1.8]]}",
         1, 2, 0.5},
        // z = x²/100 + y/10 on a 5 × 4 grid; bicubic interpolation reproduces it.
        {"{type: height_grid, x: [-6, -3, 0, 3, 6], y: [-6, -2, 2, 6], z: ["
         "[-0.24, -0.51, -0.6, -0.51, -0.24], [0.16, -0.11, -0.2, -0.11, 0.16], "
         "[0.56, 0.29, 0.2, 0.29, 0.56], [0.96, 0.69, 0.6, 0.69, 0.96]]}",
         1, 2, 0.21},
        // An off-axis parabola: the parent point (30, 0) on the axis, so
        // z = ((x + 30)² + y² − 900) / (2R).
        {"{type: conic, radius: 200, conic: -1, decenter: {x: 30}}", 2, 3,
         (32.0 * 32 + 9 - 900) / 400},
        // A segment of a bowl array: the parent point (0.5, 0), a bowl's centre, on the axis.
        // (4.55, 0) is (5.05, 0) in the parent, 0.05 mm from the bowl at (5, 0), past the
        // aperture's 5 mm about the parent's axis: the array fills the moved aperture, and
        // z = (the bowl's depth there) − (its depth at its centre).
        {"{type: microlens_array, lens_radius: 0.6, lens_diameter: 0.2, pitch: 0.25, "
         "lattice: square, decenter: {x: 0.5}}",
         4.55, 0, 0.6 - std::sqrt(0.36 - 0.0025)},
    };
    for (const Case& c : cases) {
      TempDir dir;
      const std::string yaml =
          std::string("name: t\naperture: {outer_radius: 5}\nsurface: ") + c.surface + "\n";
      CAPTURE(yaml);
      const auto job = load_job(dir.write("job.yaml", yaml));
      CHECK(job.surface->sag(c.x, c.y) == doctest::Approx(c.z).epsilon(1e-13).scale(1e-13));
    }
  }
}

namespace {

// z = 0.02x² − 0.01xy + 0.03y + 0.5: inside the bicubic spline space.
double data_surface(double x, double y) { return 0.02 * x * x - 0.01 * x * y + 0.03 * y + 0.5; }

// A job whose surface reads data files beside it (relative paths).
std::string write_data_job(const TempDir& dir, const std::string& surface) {
  std::string grid = "x,y,z\n", cloud;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double x = -6 + i, y = -5 + j;
      grid += std::to_string(x) + "," + std::to_string(y) + "," +
              std::to_string(data_surface(x, y)) + "\n";
    }
  // Scattered points: a jittered 25 × 25 lattice.
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 25; ++j) {
      const double x = -6 + 0.5 * i + 0.1 * std::sin(7.0 * j + i),
                   y = -6 + 0.5 * j + 0.1 * std::cos(3.0 * i + j);
      char line[96];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", x, y, data_surface(x, y));
      cloud += line;
    }
  dir.write("grid.csv", grid);
  dir.write("cloud.xyz", cloud);
  dir.write("bumps.xyz", "-6 -6 0\n6 -6 0\n-6 6 0\n6 6 0\n0 0 1\n" + cloud);
  std::filesystem::create_directories(dir.path() / "jobs");
  return dir.write("jobs/job.yaml",
                   "name: t\naperture: {outer_radius: 4.5}\nsurface: " + surface + "\n");
}

}  // namespace

TEST_SUITE("job") {
  TEST_CASE("data surfaces: height grid and point cloud files, IGES, relative to the job") {
    TempDir dir;
    for (const char* surface :
         {"{type: height_grid, file: ../grid.csv}",
          "{type: height_grid, file: ../grid.csv, fit: least_squares, control_points: [8, 7]}",
          "{type: point_cloud, file: ../cloud.xyz, control_points: [6, 6], tolerance: 1e-9}"}) {
      CAPTURE(surface);
      const auto job = load_job(write_data_job(dir, surface));
      for (double x : {-4.0, 0.3, 2.9})
        for (double y : {-1.7, 0.0, 3.1}) {
          double z, zx, zy;
          job.surface->sag_gradient(x, y, z, zx, zy);
          CHECK(z == doctest::Approx(data_surface(x, y)).epsilon(1e-11).scale(1));
          CHECK(zx == doctest::Approx(0.04 * x - 0.01 * y).epsilon(1e-10).scale(1));
          CHECK(zy == doctest::Approx(-0.01 * x + 0.03).epsilon(1e-10).scale(1));
        }
    }
    // The hand-written IGES patch (tests/io/data), seen as a height field.
    const std::string iges = std::string(FREETURN_SOURCE_DIR) + "/tests/io/data/bicubic_patch.igs";
    const auto job = load_job(dir.write(
        "iges.yaml", "name: t\naperture: {outer_radius: 4}\nsurface: {type: nurbs, iges: " + iges +
                         "}\n"));
    // Its corner (6, 4.5) is outside the aperture; its sag at the origin is the patch's.
    const auto patch = freeturn::read_iges_surface(iges);
    const auto* field = dynamic_cast<const freeturn::NurbsHeightField*>(job.surface.get());
    REQUIRE(field != nullptr);
    double u, v;
    REQUIRE(field->parameters_at(0.5, -0.25, u, v));
    const auto p = patch.point(u, v);
    CHECK(p.x() == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(p.y() == doctest::Approx(-0.25).epsilon(1e-14));
    CHECK(job.surface->sag(0.5, -0.25) == doctest::Approx(p.z()).epsilon(1e-14));
  }

  TEST_CASE("data surfaces: bad data names the key and why") {
    TempDir dir;
    struct Case {
      const char* surface;
      const char* message;
    };
    const Case cases[] = {
        {"{type: height_grid, file: ../missing.csv}",
         "missing.csv: no such file: give a point file"},
        // A directory read as empty, a device as a line without end (/dev/zero had hung).
        {"{type: height_grid, file: /dev/zero}",
         "/dev/zero: is not a regular file (a directory, device or pipe)"},
        {"{type: point_cloud, file: /tmp, control_points: [6, 6]}", "/tmp: is not a regular file"},
        {"{type: nurbs, iges: /dev/zero}", "/dev/zero: is not a regular file"},
        {"{type: height_grid, file: ../cloud.xyz}",
         "do not form a regular grid: they have 625 distinct x and 625 distinct y values"},
        {"{type: height_grid, file: ../grid.csv, fit: spline}",
         "surface.fit must be interpolate or least_squares, not 'spline'"},
        {"{type: point_cloud, file: ../cloud.xyz, control_points: [30, 30]}",
         "surface.control_points must be [count_x, count_y], each at least 4, with "
         "count_x·count_y at most the 625 points"},
        {"{type: point_cloud, file: ../bumps.xyz, control_points: [4, 4], tolerance: 1e-6}",
         "the fit misses point 3 (-6, 6) by 14"},
        {"{type: nurbs, degree_u: 1, degree_v: 1, knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1], "
         "points: [[-6, -6, 0], [-6, 6, 0], [6, -6, 0]]}",
         "the knots give 2 × 2 control points (u-major: 2 per row); the list has 3"},
        {"{type: nurbs, degree_u: 1, degree_v: 1, knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1], "
         "points: [[-2, -2, 0], [-2, 2, 0], [2, -2, 0], [2, 2, 0]]}",
         "undefined beyond r = 2 mm (the edge of its data in x-y), inside the aperture radius 4.5"},
    };
    for (const Case& c : cases) {
      const std::string surface = c.surface;
      CAPTURE(surface);
      const std::string path = write_data_job(dir, c.surface);
      try {
        load_job(path);
        FAIL("no error");
      } catch (const InputError& e) {
        const std::string message = e.what();
        CAPTURE(message);
        CHECK(message.find(c.message) != std::string::npos);
        CHECK(std::string(e.what()).find("job.yaml:3:") != std::string::npos);
      }
    }
  }
}
