#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixtures.hpp"
#include "freeturn/nurbs/arc_length.hpp"
#include "freeturn/nurbs/gauss_legendre.hpp"

using namespace freeturn::test;
using freeturn::nurbs::ArcLengthTable;

TEST_SUITE("nurbs") {
  TEST_CASE("Gauss-Legendre rules integrate polynomials of degree 2n-1 exactly") {
    for (int n : {1, 2, 5, 12, 30}) {
      const auto rule = freeturn::nurbs::gauss_legendre(n);
      const int degree = 2 * n - 1;
      double sum = 0, weights = 0;
      for (int i = 0; i < n; ++i) {
        sum += rule.weights[i] * std::pow(rule.nodes[i] + 1.0, degree);  // ∫_{-1}^{1} (x+1)^d
        weights += rule.weights[i];
      }
      CHECK(weights == doctest::Approx(2.0).epsilon(1e-15));
      CHECK(sum == doctest::Approx(std::pow(2.0, degree + 1) / (degree + 1)).epsilon(1e-13));
    }
  }

  TEST_CASE("arc length of circles to 1e-12 relative, and its inverse lands at angle s/R") {
    const double r = 7.5;
    const ArcLengthTable quarter(quarter_circle(r));
    const ArcLengthTable full(full_circle(r));
    CHECK(std::abs(quarter.total() - std::numbers::pi * r / 2) <= 1e-12 * quarter.total());
    CHECK(std::abs(full.total() - 2 * std::numbers::pi * r) <= 1e-12 * full.total());
    for (int k = 0; k <= 100; ++k) {
      const double s = full.total() * k / 100.0;
      const double u = full.parameter_at(s);
      const Vector3d expected(r * std::cos(s / r), r * std::sin(s / r), 0);
      CHECK((full.curve().point(u) - expected).norm() <= 1e-12 * full.total());
      CHECK(std::abs(full.length_to(u) - s) <= 1e-12 * full.total());
    }
    CHECK(full.length(0.25, 0.5) == doctest::Approx(std::numbers::pi * r / 2).epsilon(1e-13));
    CHECK(full.length(0.5, 0.25) == doctest::Approx(-std::numbers::pi * r / 2).epsilon(1e-13));
  }

  TEST_CASE("arc length of the parabola y = x^2 on [0, 1] matches the closed form") {
    // Quadratic Bézier (0,0), (1/2,0), (1,1) is y = x²; L = √5/2 + asinh(2)/4.
    const NurbsCurve parabola(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {0.5, 0, 0}, {1, 1, 0}});
    const ArcLengthTable table(parabola);
    const double exact = std::sqrt(5.0) / 2 + std::asinh(2.0) / 4;
    CHECK(std::abs(table.total() - exact) <= 1e-13 * exact);
    // Inverse: the point at s has x solving L(x) = s, L(x) = x√(1+4x²)/2 + asinh(2x)/4.
    for (double x : {0.1, 0.37, 0.8}) {
      const double s = x * std::sqrt(1 + 4 * x * x) / 2 + std::asinh(2 * x) / 4;
      const Vector3d p = parabola.point(table.parameter_at(s));
      CHECK(std::abs(p.x() - x) <= 1e-12);
    }
  }
}
