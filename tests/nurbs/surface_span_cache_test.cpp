#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.hpp"
#include "freeturn/nurbs/surface_span_cache.hpp"

using namespace freeturn::test;
using freeturn::nurbs::SurfaceDerivatives;
using freeturn::nurbs::SurfaceSpanCache;

namespace {

// The largest difference of S and its partials, each relative to its own size (the
// second partials of this net reach the hundreds).
double worst_difference(const SurfaceDerivatives& a, const SurfaceDerivatives& b) {
  const auto rel = [](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    return (x - y).norm() / (1 + y.norm());
  };
  return std::max({rel(a.point, b.point), rel(a.su, b.su), rel(a.sv, b.sv), rel(a.suu, b.suu),
                   rel(a.suv, b.suv), rel(a.svv, b.svv)});
}

}  // namespace

TEST_SUITE("nurbs") {
  TEST_CASE("span cache: S and its partials to second order equal A3.6 + A4.4 to rounding") {
    const auto s = freeform_with_pole();
    SurfaceSpanCache cache(s);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    double worst = 0;
    // A walk (the cache's use), random jumps, knots, ends and outside the domain (clamped).
    double u = 0.05, v = 0.9;
    for (int k = 0; k < 4000; ++k) {
      if (k % 500 == 0) u = unit(rng), v = unit(rng);
      u = std::fmod(u + 0.00071, 1.0);
      v = std::fmod(v + 0.00113, 1.0);
      worst = std::max(worst, worst_difference(cache.evaluate(u, v, 2), s.evaluate(u, v, 2)));
    }
    for (double knot_u : s.knots_u().knots())
      for (double knot_v : s.knots_v().knots())
        worst = std::max(worst, worst_difference(cache.evaluate(knot_u, knot_v, 2),
                                                 s.evaluate(knot_u, knot_v, 2)));
    worst = std::max(worst, worst_difference(cache.evaluate(-0.5, 1.5, 2), s.evaluate(-0.5, 1.5, 2)));
    MESSAGE("largest relative difference from the direct evaluation: " << worst);
    CHECK(worst < 1e-12);
  }

  TEST_CASE("span cache: a rational sphere octant keeps its radius, first order alone too") {
    const double r = 7.0;
    const auto s = sphere_octant(r);
    SurfaceSpanCache cache(s);
    for (int a = 0; a <= 30; ++a)
      for (int b = 0; b <= 30; ++b) {
        const SurfaceDerivatives d = cache.evaluate(a / 30.0, b / 30.0, 1);
        CHECK(std::abs(d.point.norm() - r) <= 1e-12 * r);
        // Tangents of a sphere are perpendicular to its radius.
        CHECK(std::abs(d.su.dot(d.point)) <= 1e-11 * r * (1 + d.su.norm()));
        CHECK(std::abs(d.sv.dot(d.point)) <= 1e-11 * r * (1 + d.sv.norm()));
      }
  }
}
