#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/principal_curvatures.hpp"

using freeturn::InputError;
using namespace freeturn::test;
using freeturn::nurbs::principal_curvatures;

TEST_SUITE("nurbs") {
  TEST_CASE("the sphere octant keeps its radius to 1e-12, normals radial, curvature 1/r") {
    const double r = 7.0;
    const auto s = sphere_octant(r);
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; b <= 40; ++b) {
        const double u = a / 40.0, v = b / 40.0;
        const auto d = s.evaluate(u, v, 2);
        CHECK(std::abs(d.point.norm() - r) <= 1e-12 * r);
        CHECK((s.point(u, v) - d.point).norm() <= 1e-13 * r);
        if (a == 40) continue;  // the pole: Su × Sv vanishes there
        const auto pc = principal_curvatures(d);
        REQUIRE(pc.regular);
        // n = Su × Sv points into the sphere here (u climbs to the pole, v turns
        // counter-clockwise), so both principal curvatures are +1/r.
        CHECK(std::abs(std::abs(pc.normal.dot(d.point / r)) - 1.0) <= 1e-12);
        const double sign = pc.normal.dot(d.point) < 0 ? 1.0 : -1.0;
        CHECK(pc.k1 == doctest::Approx(sign / r).epsilon(1e-10));
        CHECK(pc.k2 == doctest::Approx(sign / r).epsilon(1e-10));
      }
    CHECK(s.evaluate(1.0, 0.3, 1).sv.norm() <= 1e-12);  // degenerate edge
    // The normal at the pole is the limit from inside: the sphere's normal there, ±z,
    // with the same orientation as nearby regular points.
    for (double v : {0.0, 0.3, 1.0}) {
      const Vector3d n_pole = s.normal(1.0, v);
      const Vector3d n_near = s.normal(1.0 - 1e-6, v);
      CHECK(std::abs(n_pole.z()) == doctest::Approx(1.0).epsilon(1e-14));
      CHECK(n_pole.dot(n_near) > 0.999999);
    }
  }

  TEST_CASE("surface partials up to second order match finite differences") {
    const auto s = freeform_with_pole();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> p(0.02, 0.98);
    const double h = 1e-6;
    for (int t = 0; t < 50; ++t) {
      const double u = p(rng), v = p(rng);
      const auto d = s.evaluate(u, v, 2);
      const auto up = s.evaluate(u + h, v, 1), um = s.evaluate(u - h, v, 1);
      const auto vp = s.evaluate(u, v + h, 1), vm = s.evaluate(u, v - h, 1);
      const double tol = 1e-5 * (1 + d.suu.norm() + d.svv.norm());
      CHECK((d.su - (up.point - um.point) / (2 * h)).norm() <= 1e-6 * (1 + d.su.norm()));
      CHECK((d.sv - (vp.point - vm.point) / (2 * h)).norm() <= 1e-6 * (1 + d.sv.norm()));
      CHECK((d.suu - (up.su - um.su) / (2 * h)).norm() <= tol);
      CHECK((d.suv - (vp.su - vm.su) / (2 * h)).norm() <= tol);
      CHECK((d.svv - (vp.sv - vm.sv) / (2 * h)).norm() <= tol);
    }
  }

  TEST_CASE("principal curvatures of a saddle z = (x² − y²)/2 at the origin are ±1") {
    // Bézier patch of degree 2 reproducing z = (x² − y²)/2 on [−1, 1]²: control heights
    // follow from the blossom, z_ij = (x_i x_j' … ); for a quadratic in x alone the middle
    // control height is −1/2 at the ends' average. Built here from the polynomial form.
    std::vector<Vector3d> pts;
    const double xs[3] = {-1, 0, 1};
    const double zx[3] = {0.5, -0.5, 0.5};  // control heights of x²/2 on [−1, 1]
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) pts.emplace_back(xs[i], xs[j], zx[i] - zx[j]);
    const NurbsSurface saddle(2, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, pts);
    const auto d = saddle.evaluate(0.5, 0.5, 2);
    CHECK(d.point.norm() <= 1e-15);
    const auto pc = principal_curvatures(d);
    CHECK(pc.k1 == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(pc.k2 == doctest::Approx(-1.0).epsilon(1e-14));
    CHECK(std::abs(pc.d1.x()) == doctest::Approx(1.0).epsilon(1e-14));  // along x
    CHECK(std::abs(pc.d2.y()) == doctest::Approx(1.0).epsilon(1e-14));
  }

  TEST_CASE("surface knot insertion in u and v leaves the geometry unchanged to 1e-14") {
    const auto s = freeform_with_pole();
    const auto su = s.insert_knot_u(0.333);
    const auto sv = s.insert_knot_v(0.61, 2);
    CHECK(su.count_u() == 21);
    CHECK(sv.count_v() == 22);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> p(0, 1);
    for (int t = 0; t < 500; ++t) {
      const double u = p(rng), v = p(rng);
      const Vector3d ref = s.point(u, v);
      CHECK((su.point(u, v) - ref).norm() <= 1e-14 * 10);
      CHECK((sv.point(u, v) - ref).norm() <= 1e-14 * 10);
    }
  }

  TEST_CASE("isoparametric curves lie on the surface") {
    const auto s = freeform_with_pole();
    const auto cu = s.curve_at_u(0.37), cv = s.curve_at_v(0.81);
    for (int t = 0; t <= 50; ++t) {
      const double w = t / 50.0;
      CHECK((cu.point(w) - s.point(0.37, w)).norm() <= 1e-13);
      CHECK((cv.point(w) - s.point(w, 0.81)).norm() <= 1e-13);
    }
  }

  TEST_CASE("bad surface data is refused naming the item") {
    const std::vector<double> k = {0, 0, 1, 1};
    const std::vector<Vector3d> four = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}};
    CHECK_THROWS_WITH_AS(NurbsSurface(1, 1, {0, 0, 1, 0.5}, k, four),
                         "u knot 3: 0.5 is smaller than knot 2 (1): knots must be non-decreasing",
                         InputError);
    CHECK_THROWS_WITH_AS(NurbsSurface(1, 1, k, k, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}),
                         "control points: 3 control points, but the knot vectors need 4",
                         InputError);
    CHECK_THROWS_WITH_AS(NurbsSurface(1, 1, k, k, four, {1, 1, 0, 1}),
                         "weight 1,0: must be a finite number greater than 0, not 0",
                         InputError);
  }
}
