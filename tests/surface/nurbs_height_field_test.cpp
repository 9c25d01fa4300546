#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/interpolation.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "nurbs/fixtures.hpp"
#include "surface/derivatives_check.hpp"

using freeturn::NurbsHeightField;
using freeturn::nurbs::NurbsSurface;
using freeturn::nurbs::Vector3d;

namespace {

// A spherical cap of radius R about (0, 0, R) out to polar angle θ: the exact rational
// arc from the vertex (u = 0, a pole) to the rim, revolved 360° on the nine-point circle
// (The NURBS Book, Ex. 7.1 and A8.1). z = R − √(R² − r²) for r ≤ R sin θ.
NurbsSurface spherical_cap(double radius, double theta) {
  const double half = theta / 2;
  const double pr[3] = {0, radius * std::tan(half), radius * std::sin(theta)};
  const double pz[3] = {0, 0, radius * (1 - std::cos(theta))};
  const double pw[3] = {1, std::cos(half), 1};
  const double h = std::sqrt(0.5);
  const double cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  const double cw[9] = {1, h, 1, h, 1, h, 1, h, 1};
  std::vector<Vector3d> points;
  std::vector<double> weights;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 9; ++j) {
      points.emplace_back(pr[i] * cx[j], pr[i] * cy[j], pz[i]);
      weights.push_back(pw[i] * cw[j]);
    }
  return NurbsSurface(2, 2, {0, 0, 0, 1, 1, 1},
                      {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, points, weights);
}

// A bicubic Bézier patch on a skewed net (x depends on v, y on u): no shortcut applies.
NurbsSurface skewed_patch() {
  std::vector<Vector3d> points;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      points.emplace_back(3.0 * i - 5.1 + 0.4 * j, 3.0 * j - 4.05 - 0.3 * i + 0.1 * i * j,
                          0.2 * std::sin(1.0 + i * 1.3 + j * 0.7) + 0.05 * i * j);
  return NurbsSurface(3, 3, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, points);
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("NURBS height field: a rational spherical cap has the sphere's sag and derivatives") {
    const double radius = 20.0;
    const NurbsHeightField cap(spherical_cap(radius, std::numbers::pi / 6));
    const freeturn::EvenAsphere sphere(1 / radius, 0);
    CHECK_FALSE(cap.affine_parameters());
    for (double r : {0.0, 1e-7, 0.3, 2.0, 5.5, 9.0, 9.99})
      for (double phi : {0.0, 0.4, 2.0, 3.9, 5.5}) {
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        CAPTURE(x);
        CAPTURE(y);
        const auto a = cap.height_derivatives(x, y), b = sphere.height_derivatives(x, y);
        CHECK(a.z == doctest::Approx(b.z).epsilon(1e-13).scale(1));
        CHECK(a.zx == doctest::Approx(b.zx).epsilon(1e-11).scale(1));
        CHECK(a.zy == doctest::Approx(b.zy).epsilon(1e-11).scale(1));
        // At the pole the Hessian comes from differences of the gradient (step 1e-4·size).
        const double tol = r < 1e-3 ? 1e-6 : 1e-9;
        CHECK(a.zxx == doctest::Approx(b.zxx).epsilon(tol));
        CHECK(a.zxy == doctest::Approx(b.zxy).epsilon(tol).scale(1));
        CHECK(a.zyy == doctest::Approx(b.zyy).epsilon(tol));
      }
    // The projection is the disc r ≤ R sin 30° = 10: the edge itself, found to rounding (a
    // polyline alone put it 1.6e-5 mm inside, and refused an aperture of 10 mm).
    CHECK(cap.defined_radius() == doctest::Approx(10.0).epsilon(1e-12));
    CHECK(std::isnan(cap.sag(7.2, 7.2)));  // r = 10.18: outside
  }

  TEST_CASE("NURBS height field: derivatives of a skewed bicubic patch match finite differences") {
    const NurbsHeightField patch(skewed_patch());
    CHECK_FALSE(patch.affine_parameters());
    freeturn::test::check_derivatives(patch, 2.5);
    // The sag is the surface point whose x and y are the query's.
    double u, v;
    REQUIRE(patch.parameters_at(1.3, -0.7, u, v));
    const Vector3d p = patch.nurbs().point(u, v);
    CHECK(p.x() == doctest::Approx(1.3).epsilon(1e-14));
    CHECK(p.y() == doctest::Approx(-0.7).epsilon(1e-14));
    CHECK(patch.sag(1.3, -0.7) == doctest::Approx(p.z()).epsilon(1e-15));
  }

  TEST_CASE("NURBS height field: data on x-y parameters is affine and needs no inversion") {
    // z = x²y − 2xy² + 3 lies in the bicubic spline space, so interpolation reproduces it.
    const std::vector<double> xs = {-4, -2.5, -1, 0, 1.5, 3, 4}, ys = {-3, -1, 0.5, 2, 3};
    std::vector<Vector3d> grid;
    const auto f = [](double x, double y) { return x * x * y - 2 * x * y * y + 3; };
    for (double x : xs)
      for (double y : ys) grid.emplace_back(x, y, f(x, y));
    freeturn::nurbs::GridParameters params;
    for (double x : xs) params.u.push_back((x + 4) / 8);
    for (double y : ys) params.v.push_back((y + 3) / 6);
    const NurbsHeightField field(freeturn::nurbs::interpolate_surface(
        grid, static_cast<int>(xs.size()), static_cast<int>(ys.size()), 3, 3, &params));
    CHECK(field.affine_parameters());
    for (double x : {-3.7, -0.2, 2.9})
      for (double y : {-2.8, 0.0, 2.6}) {
        const auto h = field.height_derivatives(x, y);
        CHECK(h.z == doctest::Approx(f(x, y)).epsilon(1e-12));
        CHECK(h.zx == doctest::Approx(2 * x * y - 2 * y * y).epsilon(1e-11).scale(1));
        CHECK(h.zyy == doctest::Approx(-4 * x).epsilon(1e-10).scale(1));
        CHECK(h.zxy == doctest::Approx(2 * x - 4 * y).epsilon(1e-10).scale(1));
      }
    CHECK(field.defined_radius() == doctest::Approx(3.0).epsilon(1e-12));  // the edge y = −3
    CHECK(std::isnan(field.sag(4.5, 0)));
  }

  TEST_CASE("NURBS height field: a surface that folds over in x is refused") {
    std::vector<Vector3d> points;
    const double xs[4] = {0, 6, -2, 4};  // x'(u) changes sign twice
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) points.emplace_back(xs[i], 2.0 * j, 0.1 * i);
    const NurbsSurface s(3, 3, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, points);
    CHECK_THROWS_AS(NurbsHeightField{s}, freeturn::InputError);
    try {
      NurbsHeightField{s};
    } catch (const freeturn::InputError& e) {
      CHECK(std::string(e.problem()).find("folds over") != std::string::npos);
    }
  }
}

#include "freeturn/surface/height_field_queries.hpp"

TEST_SUITE("surface") {
  TEST_CASE("NURBS height field: ray and closest point queries agree with the NURBS kernel") {
    const NurbsHeightField cap(spherical_cap(20.0, std::numbers::pi / 6));
    const Eigen::Vector3d origin(1.0, -2.0, 8.0), direction(0.3, 0.4, -1.0);
    const auto hit = freeturn::intersect_ray(cap, origin, direction);
    REQUIRE(hit.status == freeturn::Status::kOk);
    const auto kernel_hit = cap.locator().intersect_ray(origin, direction);
    REQUIRE(kernel_hit.status == freeturn::Status::kOk);
    CHECK((hit.point - kernel_hit.point).norm() < 1e-9);
    // And both lie on the sphere |p − (0, 0, 20)| = 20.
    CHECK((hit.point - Eigen::Vector3d(0, 0, 20)).norm() == doctest::Approx(20.0).epsilon(1e-13));
    const Eigen::Vector3d p(3.0, 4.0, 2.0);
    const auto near = freeturn::closest_point(cap, p);
    REQUIRE(near.status == freeturn::Status::kOk);
    const auto kernel_near = cap.locator().closest_point(p);
    CHECK((near.point - kernel_near.point).norm() < 1e-9);
    // Closed form: the sphere point on the line from its centre through p.
    const Eigen::Vector3d c(0, 0, 20), expected = c + 20.0 * (p - c).normalized();
    CHECK((near.point - expected).norm() < 1e-9);
  }

  TEST_CASE("NURBS height field: a C⁰ seam is a crease, found where each section crosses it") {
    // The groove x = 0.6 (a triple knot in a cubic): crossed by the section at θ at
    // ρ = 0.6/cos θ, in closed form; a twin with uneven control points takes the general
    // route (sign changes of u − 1/2 along the section, then bisection) and must agree.
    for (const bool skewed : {false, true}) {
      const NurbsHeightField groove(freeturn::test::v_groove(0.6, 0.1, skewed));
      CHECK(groove.affine_parameters() == !skewed);
      CHECK(groove.has_creases());
      REQUIRE(groove.crease_knots_u().size() == 1);
      CHECK(groove.crease_knots_u()[0] == 0.5);
      CHECK(groove.crease_knots_v().empty());
      for (const double theta_deg : {0.0, 30.0, 60.0, 180.0}) {
        const double theta = theta_deg * std::numbers::pi / 180;
        double rho[4];
        const int n = groove.section_creases(theta, -1.4, 1.4, rho);
        REQUIRE(n == 1);
        CHECK(rho[0] == doctest::Approx(0.6 / std::cos(theta)).epsilon(1e-11));
        // Either side of it z_x is ∓m: the normal turns there.
        const double y = rho[0] * std::sin(theta);
        double z, zx, zy;
        groove.sag_gradient(0.6 - 1e-6, y, z, zx, zy);
        CHECK(zx == doctest::Approx(-0.1).epsilon(1e-9));
        groove.sag_gradient(0.6 + 1e-6, y, z, zx, zy);
        CHECK(zx == doctest::Approx(0.1).epsilon(1e-9));
      }
      // Parallel to the groove (θ = 90°) no section crosses it.
      double rho[4];
      CHECK(groove.section_creases(std::numbers::pi / 2, -1.4, 1.4, rho) == 0);
      // Outside the window: none.
      CHECK(groove.section_creases(0.0, -1.4, 0.5, rho) == 0);
    }
  }

  TEST_CASE("NURBS height field: C⁰ knots of a smooth shape are no creases") {
    // The spherical cap's nine-point circle has double knots in its quadratic v direction:
    // C⁰ in parameter, smooth in shape. And a flat groove (m = 0) keeps its triple knot.
    const NurbsHeightField cap(spherical_cap(10.0, 0.5));
    CHECK_FALSE(cap.has_creases());
    CHECK_FALSE(NurbsHeightField(freeturn::test::v_groove(0.6, 0.0)).has_creases());
  }
}
