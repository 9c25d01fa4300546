#include <doctest/doctest.h>

#include <cmath>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/odd_asphere.hpp"
#include "surface/derivatives_check.hpp"

using freeturn::EvenAsphere;
using freeturn::OddAsphere;

TEST_SUITE("surface") {
  TEST_CASE("odd asphere: sag is the conic plus every power of r") {
    const std::vector<double> beta = {1e-3, 2e-3, -3e-4, 5e-5, 1e-6};
    const OddAsphere s(1.0 / 50.0, -0.5, beta);
    const double x = 2.4, y = -1.8, r = 3.0;
    const double c = 1.0 / 50.0, k = -0.5;
    double expected = c * r * r / (1 + std::sqrt(1 - (1 + k) * c * c * r * r));
    for (std::size_t i = 0; i < beta.size(); ++i) expected += beta[i] * std::pow(r, i + 1.0);
    CHECK(s.sag(x, y) == doctest::Approx(expected).epsilon(1e-15));
    freeturn::test::check_derivatives(s, 6.0, 100, 0.2);
  }

  TEST_CASE("odd asphere with even terms only equals the even asphere") {
    std::array<double, 9> a{};
    a[0] = 3e-4;   // A4
    a[1] = -2e-6;  // A6
    const EvenAsphere even(1.0 / 30.0, -1.2, a);
    const OddAsphere odd(1.0 / 30.0, -1.2, {0, 0, 0, 3e-4, 0, -2e-6});
    for (double x : {0.0, 0.7, -3.1})
      for (double y : {0.0, 2.2, -4.0}) {
        const auto e = even.height_derivatives(x, y), o = odd.height_derivatives(x, y);
        CHECK(o.z == doctest::Approx(e.z).epsilon(1e-14).scale(1));
        CHECK(o.zx == doctest::Approx(e.zx).epsilon(1e-13).scale(1));
        CHECK(o.zy == doctest::Approx(e.zy).epsilon(1e-13).scale(1));
        CHECK(o.zxx == doctest::Approx(e.zxx).epsilon(1e-12).scale(1));
        CHECK(o.zxy == doctest::Approx(e.zxy).epsilon(1e-12).scale(1));
        CHECK(o.zyy == doctest::Approx(e.zyy).epsilon(1e-12).scale(1));
      }
  }

  TEST_CASE("odd asphere at the vertex: the limits of the smooth terms, 0 for the cone") {
    // β₂ r² + β₃ r³ + β₄ r⁴: Hessian 2β₂ I at r = 0 (r³ and r⁴ add nothing there).
    const OddAsphere s(0.0, 0.0, {0.0, 0.04, 0.3, 0.5});
    const auto h = s.height_derivatives(0, 0);
    CHECK(h.z == 0);
    CHECK(h.zx == 0);
    CHECK(h.zxx == doctest::Approx(0.08).epsilon(1e-15));
    CHECK(h.zyy == doctest::Approx(0.08).epsilon(1e-15));
    CHECK(h.zxy == 0);
    // The r³ term's Hessian tends to that limit: at r = 1e-6 it is off by 3β₃·2r.
    const auto near = s.height_derivatives(1e-6, 0);
    CHECK(near.zxx == doctest::Approx(0.08 + 6 * 0.3 * 1e-6).epsilon(1e-9));
    // A cone β₁ r: the gradient is β₁ away from the vertex and 0 (its mean) at it.
    const OddAsphere cone(0.0, 0.0, {0.1});
    double z, zx, zy;
    cone.sag_gradient(0.6, 0.8, z, zx, zy);
    CHECK(z == doctest::Approx(0.1).epsilon(1e-15));
    CHECK(zx == doctest::Approx(0.06).epsilon(1e-15));
    cone.sag_gradient(0, 0, z, zx, zy);
    CHECK(zx == 0);
    CHECK(zy == 0);
  }
}
