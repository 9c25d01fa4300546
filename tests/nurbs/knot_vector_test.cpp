#include <doctest/doctest.h>

#include <cmath>

#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/knot_vector.hpp"

using freeturn::InputError;
using freeturn::nurbs::KnotVector;

TEST_SUITE("nurbs") {
  TEST_CASE("bad knot vectors are refused naming the knot") {
    CHECK_THROWS_WITH_AS(KnotVector(2, {0, 0, 0, 0.5, 0.4, 1, 1, 1}),
                         "knot 4: 0.4 is smaller than knot 3 "
                         "(0.5): knots must be non-decreasing",
                         InputError);
    CHECK_THROWS_WITH_AS(KnotVector(2, {0, 0, 0, NAN, 1, 1, 1}), "knot 3: is not a finite number",
                         InputError);
    CHECK_THROWS_WITH_AS(KnotVector(3, {0, 0, 0, 1, 1, 1}),
                         "knots: degree 3 needs at least 8 knots, got 6", InputError);
    CHECK_THROWS_WITH_AS(KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}),
                         "knot 3: value 0.5 repeats 3 times; at most 2 allowed for degree 2 "
                         "inside",
                         InputError);
    CHECK_THROWS_WITH_AS(KnotVector(1, {0, 0, 0, 1, 1}),
                         "knot 0: value 0 repeats 3 times; at most 2 allowed for degree 1 at "
                         "an end",
                         InputError);
    CHECK_THROWS_WITH_AS(KnotVector(0, {0, 1}), "degree: must be at least 1, not 0", InputError);
  }

  TEST_CASE("span search (A2.1) agrees with a linear scan, with and without a hint") {
    const KnotVector k(3, {0, 0, 0, 0, 0.1, 0.1, 0.35, 0.5, 0.9, 1, 1, 1, 1});
    CHECK(k.count() == 9);
    CHECK(k.is_clamped());
    for (int t = 0; t <= 1000; ++t) {
      const double u = t / 1000.0;
      int expected = 3;
      for (int i = 3; i <= 8; ++i)
        if (k[i] <= u && u < k[i + 1]) expected = i;
      if (u == 1.0) expected = 8;  // the end point belongs to the last non-empty span
      CHECK(k.find_span(u) == expected);
      CHECK(k.find_span(u, 5) == expected);
      CHECK(k.find_span(u, expected - 1) == expected);
    }
    CHECK(k.multiplicity(0.1) == 2);
    CHECK(k.multiplicity(0.2) == 0);
    CHECK(k.breakpoints() == std::vector<double>{0, 0.1, 0.35, 0.5, 0.9, 1});
  }

  TEST_CASE("basis functions: partition of unity and the NURBS Book's Ex. 2.3 values") {
    // Ex. 2.3: U = {0,0,0,1,2,3,4,4,5,5,5}, p = 2, u = 5/2, span 4:
    // N_{2,2} = 1/8, N_{3,2} = 6/8, N_{4,2} = 1/8.
    const KnotVector k(2, {0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5});
    const int span = k.find_span(2.5);
    CHECK(span == 4);
    double n[3];
    freeturn::nurbs::basis_functions(span, 2.5, 2, k.knots().data(), n);
    CHECK(n[0] == doctest::Approx(1.0 / 8).epsilon(1e-15));
    CHECK(n[1] == doctest::Approx(6.0 / 8).epsilon(1e-15));
    CHECK(n[2] == doctest::Approx(1.0 / 8).epsilon(1e-15));
    // Derivatives at 5/2 (Ex. 2.4): N'_{2,2} = −1/2, N'_{3,2} = 0, N'_{4,2} = 1/2, and
    // second derivatives 1, −2, 1.
    double ders[9], work[freeturn::nurbs::basis_derivatives_work_size(2)];
    freeturn::nurbs::basis_function_derivatives(span, 2.5, 2, 2, k.knots().data(), ders, work);
    CHECK(ders[0] == doctest::Approx(1.0 / 8));
    CHECK(ders[3] == doctest::Approx(-0.5).epsilon(1e-14));
    CHECK(ders[4] == doctest::Approx(0.0).scale(1));
    CHECK(ders[5] == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(ders[6] == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(ders[7] == doctest::Approx(-2.0).epsilon(1e-14));
    CHECK(ders[8] == doctest::Approx(1.0).epsilon(1e-14));
  }

  TEST_CASE("basis derivatives match finite differences for degree 5, and vanish above it") {
    const KnotVector k(5, {0, 0, 0, 0, 0, 0, 0.2, 0.3, 0.3, 0.7, 1, 1, 1, 1, 1, 1});
    const int p = 5, n = 7;
    double d[8 * 6], dp[8 * 6], dm[8 * 6];
    double work[freeturn::nurbs::basis_derivatives_work_size(5)];
    const double h = 1e-6;
    for (double u : {0.05, 0.25, 0.5, 0.85}) {
      const int span = k.find_span(u);
      freeturn::nurbs::basis_function_derivatives(span, u, p, n, k.knots().data(), d, work);
      freeturn::nurbs::basis_function_derivatives(span, u + h, p, n, k.knots().data(), dp, work);
      freeturn::nurbs::basis_function_derivatives(span, u - h, p, n, k.knots().data(), dm, work);
      double sum = 0;
      for (int j = 0; j <= p; ++j) sum += d[j];
      CHECK(sum == doctest::Approx(1.0).epsilon(1e-15));
      for (int order = 1; order <= 3; ++order)
        for (int j = 0; j <= p; ++j) {
          const double fd = (dp[(order - 1) * 6 + j] - dm[(order - 1) * 6 + j]) / (2 * h);
          CHECK(d[order * 6 + j] ==
                doctest::Approx(fd).epsilon(1e-6).scale(1e-3 * std::pow(10.0, order)));
        }
      for (int j = 0; j <= p; ++j) {
        CHECK(d[6 * 6 + j] == 0.0);
        CHECK(d[7 * 6 + j] == 0.0);
      }
    }
  }
}
