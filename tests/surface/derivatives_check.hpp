#pragma once
// Central-difference check of a surface's gradient and Hessian, shared by the surface
// tests.

#include <doctest/doctest.h>

#include <random>

#include "freeturn/surface/surface.hpp"

namespace freeturn::test {

// Checks height_derivatives and sag_gradient against central differences at `count`
// random points in [−half_width, half_width]², skipping points closer than `skip_radius`
// to the origin (a cone vertex).
inline void check_derivatives(const Surface& s, double half_width, int count = 100,
                              double skip_radius = 0, double h = 1e-4) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-half_width, half_width);
  for (int k = 0; k < count; ++k) {
    const double x = u(rng), y = u(rng);
    if (std::hypot(x, y) < skip_radius) continue;
    const HeightDerivatives d = s.height_derivatives(x, y);
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    CHECK(z == doctest::Approx(d.z).epsilon(1e-14).scale(1e-12));
    CHECK(zx == doctest::Approx(d.zx).epsilon(1e-13).scale(1e-12));
    CHECK(zy == doctest::Approx(d.zy).epsilon(1e-13).scale(1e-12));
    const auto px = s.height_derivatives(x + h, y), mx = s.height_derivatives(x - h, y);
    const auto py = s.height_derivatives(x, y + h), my = s.height_derivatives(x, y - h);
    const double scale = 1e-6 * (1 + std::abs(d.zxx) + std::abs(d.zyy) + std::abs(d.zxy));
    CHECK(d.zx == doctest::Approx((px.z - mx.z) / (2 * h)).epsilon(1e-7).scale(scale));
    CHECK(d.zy == doctest::Approx((py.z - my.z) / (2 * h)).epsilon(1e-7).scale(scale));
    CHECK(d.zxx == doctest::Approx((px.zx - mx.zx) / (2 * h)).epsilon(1e-6).scale(scale));
    CHECK(d.zxy == doctest::Approx((py.zx - my.zx) / (2 * h)).epsilon(1e-6).scale(scale));
    CHECK(d.zxy == doctest::Approx((px.zy - mx.zy) / (2 * h)).epsilon(1e-6).scale(scale));
    CHECK(d.zyy == doctest::Approx((py.zy - my.zy) / (2 * h)).epsilon(1e-6).scale(scale));
    CHECK(s.normal(x, y).norm() == doctest::Approx(1.0).epsilon(1e-15));
  }
}

}  // namespace freeturn::test
