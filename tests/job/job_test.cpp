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
         "even_asphere)"},
        {"name: a\naperture: {outer_radius: 5}\nsurface: {type: sphere, radius: 4}\n",
         "job.yaml:3:33: the surface is undefined beyond r = 4.000000 mm (the conic's square "
         "root goes negative), inside the aperture radius 5.000000 mm"},
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
