#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "freeturn/surface/even_asphere.hpp"

using freeturn::EvenAsphere;

TEST_SUITE("surface") {
  TEST_CASE("sphere sag is R - sqrt(R^2 - r^2), both signs of R") {
    for (double radius : {25.0, -40.0}) {
      const EvenAsphere s(1.0 / radius, 0.0);
      for (double r : {0.0, 0.5, 3.0, 9.9}) {
        double z, zx, zy;
        s.sag_gradient(r * 0.6, r * 0.8, z, zx, zy);
        const double expected = radius - std::copysign(std::sqrt(radius * radius - r * r), radius);
        CHECK(z == doctest::Approx(expected).epsilon(1e-14));
        // Slope of a sphere: dz/dr = r / sqrt(R^2 - r^2) (sign of R).
        const double dzdr = r / std::copysign(std::sqrt(radius * radius - r * r), radius);
        CHECK(std::hypot(zx, zy) == doctest::Approx(std::abs(dzdr)).epsilon(1e-13));
      }
    }
  }

  TEST_CASE("paraboloid (k = -1) sag is r^2 / (2R)") {
    const EvenAsphere s(1.0 / 30.0, -1.0);
    double z, zx, zy;
    s.sag_gradient(7.0, -4.0, z, zx, zy);
    CHECK(z == doctest::Approx(65.0 / 60.0).epsilon(1e-15));
    CHECK(zx == doctest::Approx(7.0 / 30.0).epsilon(1e-15));
    CHECK(zy == doctest::Approx(-4.0 / 30.0).epsilon(1e-15));
    CHECK(s.defined_radius() == INFINITY);
  }

  TEST_CASE("polynomial terms add A4 r^4 + A6 r^6 exactly on a plane base") {
    std::array<double, 9> a{};
    a[0] = 2e-3;   // A4
    a[1] = -1e-5;  // A6
    a[8] = 1e-20;  // A20
    const EvenAsphere s(0.0, 0.0, a);
    const double r = 3.0;
    const auto h = s.height_derivatives(r, 0.0);
    CHECK(h.z ==
          doctest::Approx(2e-3 * 81 - 1e-5 * 729 + 1e-20 * std::pow(3.0, 20)).epsilon(1e-14));
    CHECK(h.zx ==
          doctest::Approx(4 * 2e-3 * 27 - 6e-5 * 243 + 20e-20 * std::pow(3.0, 19)).epsilon(1e-14));
    CHECK(h.zxx ==
          doctest::Approx(12 * 2e-3 * 9 - 30e-5 * 81 + 380e-20 * std::pow(3.0, 18)).epsilon(1e-14));
  }

  TEST_CASE("gradient and Hessian match central differences at random points") {
    std::array<double, 9> a{};
    a[0] = 1.2e-6;
    a[1] = -3e-9;
    a[2] = 4e-12;
    const EvenAsphere s(1.0 / 50.0, -0.8, a);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    const double h = 1e-4;
    for (int trial = 0; trial < 200; ++trial) {
      const double x = u(rng), y = u(rng);
      const auto d = s.height_derivatives(x, y);
      const auto px = s.height_derivatives(x + h, y), mx = s.height_derivatives(x - h, y);
      const auto py = s.height_derivatives(x, y + h), my = s.height_derivatives(x, y - h);
      CHECK(d.zx == doctest::Approx((px.z - mx.z) / (2 * h)).epsilon(1e-8));
      CHECK(d.zy == doctest::Approx((py.z - my.z) / (2 * h)).epsilon(1e-8));
      CHECK(d.zxx == doctest::Approx((px.zx - mx.zx) / (2 * h)).epsilon(1e-7));
      CHECK(d.zxy == doctest::Approx((py.zx - my.zx) / (2 * h)).epsilon(1e-7).scale(1e-6));
      CHECK(d.zyy == doctest::Approx((py.zy - my.zy) / (2 * h)).epsilon(1e-7));
      CHECK(s.normal(x, y).norm() == doctest::Approx(1.0).epsilon(1e-15));
      CHECK(s.normal(x, y).z() > 0);
    }
  }

  TEST_CASE("the conic's square root limits the defined radius") {
    const EvenAsphere s(1.0 / 10.0, 0.0);
    CHECK(s.defined_radius() == doctest::Approx(10.0).epsilon(1e-15));
    const EvenAsphere e(1.0 / 10.0, 3.0);  // oblate: (1+k) c^2 r^2 < 1 -> r < 5
    CHECK(e.defined_radius() == doctest::Approx(5.0).epsilon(1e-15));
  }
}
