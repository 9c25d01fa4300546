#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/interpolation.hpp"
#include "freeturn/nurbs/least_squares.hpp"
#include "freeturn/nurbs/parameterization.hpp"
#include "freeturn/nurbs/surface_locator.hpp"

using namespace freeturn::test;
using freeturn::InputError;
using namespace freeturn::nurbs;

namespace {

// A cubic polynomial space curve: in the span of any cubic spline.
Vector3d cubic(double t) {
  return {1 + 2 * t - t * t * t, t * t - 3 * t, 0.5 * t * t * t + t};
}

// A polynomial surface of degree (3, 2): in the span of any bicubic × biquadratic spline.
Vector3d patch(double u, double v) {
  return {10 * u + u * v, 8 * v - u * u, u * u * u - 2 * u * v * v + v * v + 0.3};
}

}  // namespace

TEST_SUITE("nurbs") {
  TEST_CASE("chord-length parameters and averaged knots: The NURBS Book Ex. 9.1") {
    const std::vector<Vector3d> q = {{0, 0, 0}, {3, 4, 0}, {-1, 4, 0}, {-4, 0, 0}, {-4, -3, 0}};
    const auto u = chord_length_parameters(q);
    CHECK(u[1] == doctest::Approx(5.0 / 17).epsilon(1e-15));
    CHECK(u[2] == doctest::Approx(9.0 / 17).epsilon(1e-15));
    CHECK(u[3] == doctest::Approx(14.0 / 17).epsilon(1e-15));
    const auto knots = averaged_knots(u, 3);
    REQUIRE(knots.size() == 9);
    CHECK(knots[4] == doctest::Approx(28.0 / 51).epsilon(1e-15));
    CHECK_THROWS_WITH_AS(chord_length_parameters({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}),
                         "point 2: coincides with point 1: parameters need distinct consecutive "
                         "points",
                         InputError);
  }

  TEST_CASE("curve interpolation (A9.1) passes through its points and reproduces a cubic") {
    std::vector<Vector3d> q;
    std::vector<double> t;
    for (int k = 0; k <= 12; ++k) {
      t.push_back(k / 12.0);
      q.push_back(cubic(k / 12.0));
    }
    const NurbsCurve chord = interpolate_curve(q, 3);
    const auto params = chord_length_parameters(q);
    for (std::size_t k = 0; k < q.size(); ++k)
      CHECK((chord.point(params[k]) - q[k]).norm() <= 1e-12);
    const NurbsCurve exact = interpolate_curve(q, 3, t);
    for (int k = 0; k <= 100; ++k)
      CHECK((exact.point(k / 100.0) - cubic(k / 100.0)).norm() <= 1e-12);
  }

  TEST_CASE("surface interpolation (A9.4) passes through its grid") {
    std::vector<Vector3d> grid;
    const int rows = 7, cols = 9;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        const double x = i - 3.0, y = 0.5 * j - 2.0;
        grid.emplace_back(x, y, std::sin(x) * std::cos(y));
      }
    const NurbsSurface s = interpolate_surface(grid, rows, cols, 3, 3);
    // Every grid point lies on the surface: its closest point is at distance zero.
    const SurfaceLocator locator(s);
    for (const Vector3d& q : grid) CHECK(locator.closest_point(q).distance <= 1e-12);
  }

  TEST_CASE("least squares reproduces a polynomial of the spline's degree exactly") {
    std::vector<Vector3d> q;
    std::vector<double> t;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int k = 0; k < 200; ++k) t.push_back(unit(rng));
    std::sort(t.begin(), t.end());
    t.front() = 0;
    t.back() = 1;
    for (double x : t) q.push_back(cubic(x));
    CurveFitOptions o;
    o.count = 9;
    o.params = t;
    for (bool pin : {false, true}) {
      o.pin_ends = pin;
      const auto fit = fit_curve(q, o);
      CHECK(fit.max_error <= 1e-12);
      for (int k = 0; k <= 50; ++k)
        CHECK((fit.curve.point(k / 50.0) - cubic(k / 50.0)).norm() <= 1e-12);
    }
    // A straight line has C'' = 0, so smoothing does not move the fit.
    std::vector<Vector3d> line;
    for (double x : t) line.push_back(Vector3d(1, 2, 3) + x * Vector3d(4, -1, 2));
    o.smoothing = 10.0;
    o.pin_ends = false;
    CHECK(fit_curve(line, o).max_error <= 1e-11);
  }

  TEST_CASE("surface least squares: grid and scattered data of a polynomial, exactly") {
    SurfaceFitOptions o;
    o.degree_u = 3;
    o.degree_v = 2;
    o.count_u = 6;
    o.count_v = 5;
    // Scattered points with their true parameters.
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<Vector3d> pts;
    std::vector<double> us, vs;
    for (int k = 0; k < 600; ++k) {
      us.push_back(unit(rng));
      vs.push_back(unit(rng));
      pts.push_back(patch(us.back(), vs.back()));
    }
    const auto scattered = fit_surface_scattered(pts, us, vs, o);
    CHECK(scattered.max_error <= 1e-11);
    for (int k = 0; k < 100; ++k) {
      const double u = unit(rng), v = unit(rng);
      CHECK((scattered.surface.point(u, v) - patch(u, v)).norm() <= 1e-11);
    }
    // Grid data: the separable grid fit must equal the general scattered fit at the same
    // parameters and knots (two different solvers of one least-squares problem).
    const int rows = 15, cols = 12;
    std::vector<Vector3d> grid;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        const double x = i - 7.0, y = 0.8 * j - 4.0;
        grid.emplace_back(x, y, 0.2 * std::sin(x) * std::cos(0.7 * y));
      }
    o.knots_u = {0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1};
    o.knots_v = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
    const auto by_grid = fit_surface_grid(grid, rows, cols, o);
    const auto by_points = fit_surface_scattered(grid, by_grid.u, by_grid.v, o);
    for (int i = 0; i < by_grid.surface.count_u(); ++i)
      for (int j = 0; j < by_grid.surface.count_v(); ++j)
        CHECK(
            (by_grid.surface.control_point(i, j) - by_points.surface.control_point(i, j)).norm() <=
            1e-11);
    CHECK(by_grid.rms_error == doctest::Approx(by_points.rms_error).epsilon(1e-9));
  }

  TEST_CASE("parameter correction removes the tangential error of bad parameters") {
    // Points on a circle arc, given uniform parameters that do not match its speed.
    const NurbsCurve arc = quarter_circle(5.0);
    std::vector<Vector3d> q;
    for (int k = 0; k <= 60; ++k) q.push_back(arc.point(std::pow(k / 60.0, 1.4)));
    CurveFitOptions o;
    o.count = 12;
    for (int k = 0; k <= 60; ++k) o.params.push_back(k / 60.0);
    const auto plain = fit_curve(q, o);
    o.parameter_corrections = 20;
    const auto corrected = fit_curve(q, o);
    MESSAGE("circle fit max error: " << plain.max_error << " mm plain, " << corrected.max_error
                                     << " mm after correction");
    CHECK(corrected.max_error < 0.05 * plain.max_error);
    // What is left is the shape error of a polynomial cubic with 12 control points on a
    // 90° arc, which the ideal (orthogonal) residual bounds from below: tiny.
    CHECK(corrected.max_error <= 1e-4);
  }

  TEST_CASE("least squares refuses data that cannot determine the control points") {
    std::vector<Vector3d> q;
    std::vector<double> t;
    for (int k = 0; k <= 10; ++k) {
      t.push_back(0.5 * k / 10.0);  // all data in the first half of [0, 1]
      q.push_back(cubic(t.back()));
    }
    t.back() = 1.0;  // (parameters must reach 1, but one point cannot hold the second half)
    CurveFitOptions o;
    o.count = 10;
    o.params = t;
    o.knots = {0, 0, 0, 0, 0.1, 0.2, 0.3, 0.6, 0.7, 0.8, 1, 1, 1, 1};
    CHECK_THROWS_AS(fit_curve(q, o), InputError);
    o.smoothing = 1e-6;  // smoothing bridges the gap
    CHECK(fit_curve(q, o).curve.count() == 10);
    // Scattered surface data missing a corner of the domain.
    SurfaceFitOptions so;
    so.count_u = so.count_v = 8;
    std::vector<Vector3d> pts;
    std::vector<double> us, vs;
    for (int i = 0; i < 30; ++i)
      for (int j = 0; j < 30; ++j) {
        const double u = i / 29.0 * 0.6, v = j / 29.0 * 0.6;
        us.push_back(u);
        vs.push_back(v);
        pts.push_back(patch(u, v));
      }
    CHECK_THROWS_WITH_AS(fit_surface_scattered(pts, us, vs, so),
                         "control point 0,6: has no data under its basis function: use fewer "
                         "control points or add smoothing",
                         InputError);
  }

  TEST_CASE(
      "a smoothing weight that swamps the data is refused, and one under the bound keeps x-y") {
    // A 9 × 7 grid over [−3, 3] × [−2, 2] mm, x and y linear in the rows and columns: the
    // penalty is zero on linear functions, so x and y must come back exactly at any weight the
    // fit accepts. 1e16 had turned this domain into a few micrometres (rounding of λ·E).
    const int rows = 9, cols = 7;
    std::vector<Vector3d> grid;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        const double x = -3 + 6.0 * i / (rows - 1), y = -2 + 4.0 * j / (cols - 1);
        grid.emplace_back(x, y, 0.01 * std::sin(x) * std::cos(y));
      }
    SurfaceFitOptions o;
    o.count_u = 6;
    o.count_v = 5;
    for (int i = 0; i < rows; ++i) o.params_u.push_back(static_cast<double>(i) / (rows - 1));
    for (int j = 0; j < cols; ++j) o.params_v.push_back(static_cast<double>(j) / (cols - 1));
    o.smoothing = 1e16;
    double limit = 0;
    try {
      fit_surface_grid(grid, rows, cols, o);
      FAIL("a weight of 1e16 was accepted");
    } catch (const InputError& e) {
      CHECK(e.where() == "smoothing");
      const std::string text = e.problem();
      const auto at = text.find("at most ");
      REQUIRE(at != std::string::npos);
      limit = std::stod(text.substr(at + 8));
    }
    REQUIRE(limit > 0);
    // Just under the bound the fit is accepted, and x-y are those of the grid to 1e-8 of
    // their size: the rounding the bound allows is ε·1e8 ≈ 1e-8.
    o.smoothing = 0.9 * limit;
    const SurfaceFit heavy = fit_surface_grid(grid, rows, cols, o);
    for (int k = 0; k <= 20; ++k)
      for (int l = 0; l <= 20; ++l) {
        const Vector3d p = heavy.surface.point(k / 20.0, l / 20.0);
        CHECK(std::abs(p.x() - (-3 + 6.0 * k / 20)) <= 6e-8);
        CHECK(std::abs(p.y() - (-2 + 4.0 * l / 20)) <= 4e-8);
      }
    o.smoothing = 1.1 * limit;
    CHECK_THROWS_AS(fit_surface_grid(grid, rows, cols, o), InputError);
    // The scattered fit and the curve fit refuse such a weight the same way.
    std::vector<double> us, vs;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        us.push_back(o.params_u[i]);
        vs.push_back(o.params_v[j]);
      }
    o.params_u.clear();
    o.params_v.clear();
    o.smoothing = 1e30;
    try {
      fit_surface_scattered(grid, us, vs, o);
      FAIL("a weight of 1e30 was accepted");
    } catch (const InputError& e) {
      CHECK(e.where() == "smoothing");
    }
    o.smoothing = 1e-3;
    CHECK(fit_surface_scattered(grid, us, vs, o).surface.count_u() == 6);
    std::vector<Vector3d> line;
    for (int k = 0; k <= 20; ++k) line.push_back(cubic(k / 20.0));
    CurveFitOptions c;
    c.count = 8;
    c.smoothing = 1e30;
    try {
      fit_curve(line, c);
      FAIL("a weight of 1e30 was accepted");
    } catch (const InputError& e) {
      CHECK(e.where() == "smoothing");
    }
  }
}
