#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

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

  TEST_CASE("span cache: the same bits in any order of queries, with its spans evicted") {
    // The cache keeps 64 spans (each in the slot its indices hash to); this net has 17 × 17.
    // Asked along a walk, in a shuffled order and from a fresh cache per point, every
    // point's S and partials must be the same bits: a span's power form depends on the span
    // alone, not on what the cache held before.
    const auto s = freeform_with_pole();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<std::pair<double, double>> points;
    double u = 0.02, v = 0.3;
    for (int k = 0; k < 3000; ++k) {
      if (k % 300 == 0) u = unit(rng), v = unit(rng);
      u = std::fmod(u + 0.0037, 1.0);
      v = std::fmod(v + 0.0061, 1.0);
      points.emplace_back(u, v);
    }
    const auto same = [](const SurfaceDerivatives& a, const SurfaceDerivatives& b) {
      return a.point == b.point && a.su == b.su && a.sv == b.sv && a.suu == b.suu &&
             a.suv == b.suv && a.svv == b.svv;
    };
    SurfaceSpanCache walked(s);
    std::vector<SurfaceDerivatives> along;
    for (const auto& [pu, pv] : points) along.push_back(walked.evaluate(pu, pv, 2));
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    SurfaceSpanCache shuffled(s);
    int differ = 0;
    for (const std::size_t i : order) {
      differ += !same(shuffled.evaluate(points[i].first, points[i].second, 2), along[i]);
      SurfaceSpanCache fresh(s);
      differ += !same(fresh.evaluate(points[i].first, points[i].second, 2), along[i]);
    }
    CHECK(differ == 0);
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
