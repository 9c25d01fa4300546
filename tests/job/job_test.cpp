#include <doctest/doctest.h>

#include <cmath>

#include "freeturn/core/error.hpp"
#include "freeturn/job/job.hpp"
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
         "even_asphere, biconic, toroidal, xy_polynomial, zernike, sinusoidal_ring, "
         "sinusoidal_grid, alvarez, compound_eye, microlens_array)"},
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
                         "/nonexistent/job.yaml: cannot open the file for reading", InputError);
  }
}

TEST_SUITE("job") {
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
        // An off-axis parabola: the parent point (30, 0) on the axis, so
        // z = ((x + 30)² + y² − 900) / (2R).
        {"{type: conic, radius: 200, conic: -1, decenter: {x: 30}}", 2, 3,
         (32.0 * 32 + 9 - 900) / 400},
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
