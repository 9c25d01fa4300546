#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.hpp"
#include "freeturn/core/error.hpp"

using freeturn::InputError;
using namespace freeturn::test;

TEST_SUITE("nurbs") {
  TEST_CASE("the rational quarter and full circles keep their radius to 1e-12") {
    for (double r : {1.0, 12.5}) {
      const auto q = quarter_circle(r);
      const auto f = full_circle(r);
      CHECK(q.is_rational());
      for (int t = 0; t <= 1000; ++t) {
        const double u = t / 1000.0;
        CHECK(std::abs(q.point(u).norm() - r) <= 1e-12 * r);
        CHECK(std::abs(f.point(u).norm() - r) <= 1e-12 * r);
        CHECK(q.point(u).z() == 0.0);
      }
      CHECK(f.is_closed());
      CHECK_FALSE(q.is_closed());
    }
  }

  TEST_CASE("circle derivatives match the closed form: C' ⟂ C, curvature 1/r") {
    // Closed form of the rational quarter circle: with t = u, C(u) = r (1 − u², √2 u(1−u)... )
    // is awkward; instead use the invariants: C'·C = 0 (tangent ⟂ radius), and the
    // curvature of a circle is 1/r everywhere, and C'' has the component |C'|²/r toward
    // the centre.
    const double r = 3.0;
    const auto f = full_circle(r);
    for (int t = 0; t <= 200; ++t) {
      const double u = t / 200.0;
      const auto d = f.evaluate(u, 2);
      CHECK(std::abs(d.d1.dot(d.point)) <= 1e-12 * r * d.d1.norm());
      CHECK(f.curvature(u) == doctest::Approx(1.0 / r).epsilon(1e-12));
      CHECK(-d.d2.dot(d.point) / r == doctest::Approx(d.d1.squaredNorm() / r).epsilon(1e-12));
    }
    // At u = 0 the quarter circle's tangent is 2·w1/w0·(P1 − P0)·p/(u_{p+1} − u_1) … for
    // degree 2 on [0,1]: C'(0) = 2 w1 (P1 − P0) / w0 = 2·(√2/2)·(0, r, 0).
    const auto q = quarter_circle(r);
    const auto d0 = q.evaluate(0.0, 1);
    CHECK(d0.d1.x() == doctest::Approx(0.0).scale(1));
    CHECK(d0.d1.y() == doctest::Approx(2 * kHalfRoot2 * r).epsilon(1e-15));
  }

  TEST_CASE("curve derivatives up to third order match finite differences") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> c(-5, 5), w(0.5, 2);
    std::vector<Vector3d> pts;
    std::vector<double> wts;
    for (int i = 0; i < 9; ++i) {
      pts.emplace_back(c(rng), c(rng), c(rng));
      wts.push_back(w(rng));
    }
    const NurbsCurve curve(4, {0, 0, 0, 0, 0, 0.2, 0.45, 0.6, 0.8, 1, 1, 1, 1, 1}, pts, wts);
    const double h = 1e-5;
    for (double u : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      Vector3d d[4], dp[4], dm[4];
      curve.derivatives(u, 3, d);
      curve.derivatives(u + h, 3, dp);
      curve.derivatives(u - h, 3, dm);
      for (int k = 1; k <= 3; ++k) {
        const Vector3d fd = (dp[k - 1] - dm[k - 1]) / (2 * h);
        CHECK((d[k] - fd).norm() <= 1e-6 * (1 + d[k].norm()));
      }
      CHECK((curve.point(u) - d[0]).norm() <= 1e-14 * (1 + d[0].norm()));
    }
    // Knot insertion at an existing knot (0.45, multiplicity 1 → 3 ≤ p = 4).
    const auto refined = curve.insert_knot(0.45, 2);
    CHECK(refined.knots().multiplicity(0.45) == 3);
    for (int t = 0; t <= 200; ++t)
      CHECK((refined.point(t / 200.0) - curve.point(t / 200.0)).norm() <= 1e-13);
  }

  TEST_CASE("knot insertion (A5.1) leaves the curve unchanged to 1e-14") {
    const auto f = full_circle(5.0);
    const auto once = f.insert_knot(0.3);
    const auto twice = f.insert_knot(0.6, 2);
    CHECK(once.count() == f.count() + 1);
    CHECK(twice.count() == f.count() + 2);
    for (int t = 0; t <= 500; ++t) {
      const double u = t / 500.0;
      CHECK((once.point(u) - f.point(u)).norm() <= 1e-14 * 5);
      CHECK((twice.point(u) - f.point(u)).norm() <= 1e-14 * 5);
    }
    // The circle is only C0 at its double knots; inserting to multiplicity 3 would exceed p.
    CHECK_THROWS_AS(f.insert_knot(0.25, 1), InputError);
  }

  TEST_CASE("bad curve data is refused naming the item") {
    CHECK_THROWS_WITH_AS(NurbsCurve(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {1, 0, 0}}),
                         "control points: 2 control points, but degree 2 and 6 knots need 3",
                         InputError);
    CHECK_THROWS_WITH_AS(
        NurbsCurve(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {1, -1, 1}),
        "weight 1: must be a finite number greater than 0, not -1", InputError);
    CHECK_THROWS_WITH_AS(NurbsCurve(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {1, NAN, 0}, {2, 0, 0}}),
                         "control point 1: has a coordinate that is not finite", InputError);
    CHECK_THROWS_WITH_AS(
        NurbsCurve(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {1, 1}),
        "weights: 2 weights for 3 control points", InputError);
  }
}
