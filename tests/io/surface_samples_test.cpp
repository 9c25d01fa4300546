#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "freeturn/io/surface_samples.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "test_files.hpp"

TEST_SUITE("io") {
  TEST_CASE("surface samples hold the sphere's sag and normal on an annulus") {
    freeturn::test::TempDir dir;
    const double radius = 20.0;
    const freeturn::EvenAsphere sphere(1.0 / radius, 0.0);
    const std::string path = dir.file("s.csv");
    const auto summary = freeturn::write_surface_samples_csv(sphere, 2.0, 10.0, 21, path);
    std::istringstream in(freeturn::test::read_file(path));
    std::string line;
    std::getline(in, line);
    CHECK(line == "x,y,z,nx,ny,nz");
    long rows = 0;
    double z_max = 0;
    while (std::getline(in, line)) {
      double v[6];
      char comma;
      std::istringstream row(line);
      row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3] >> comma >> v[4] >> comma >>
          v[5];
      const double r = std::hypot(v[0], v[1]);
      CHECK(r >= 2.0);
      CHECK(r <= 10.0 + 1e-12);
      // The sag round-trips exactly (shortest decimal form) and equals R - sqrt(R^2 - r^2).
      CHECK(v[2] == doctest::Approx(radius - std::sqrt(radius * radius - r * r)).epsilon(1e-14));
      // A sphere's normal points at its centre (0, 0, R).
      CHECK(v[3] == doctest::Approx(-v[0] / radius).epsilon(1e-14));
      CHECK(v[5] == doctest::Approx((radius - v[2]) / radius).epsilon(1e-14));
      z_max = std::max(z_max, v[2]);
      ++rows;
    }
    // Grid step 1 mm: integer pairs with 4 <= i^2 + j^2 <= 100 in [-10, 10]^2:
    // 317 with i^2 + j^2 <= 100, minus 9 with i^2 + j^2 < 4.
    CHECK(rows == 308);
    CHECK(summary.points == rows);
    CHECK(summary.z_max == z_max);
    CHECK(summary.max_slope == doctest::Approx(std::asin(10.0 / radius)).epsilon(1e-12));
  }
}
