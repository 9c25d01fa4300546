#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/surface/qbfs.hpp"
#include "surface/derivatives_check.hpp"

using freeturn::Qbfs;

TEST_SUITE("surface") {
  TEST_CASE("Q-bfs polynomials: Forbes (2007) closed forms of Q0, Q1, Q2") {
    for (double x : {0.0, 0.3, 0.77, 1.0}) {
      const auto q = Qbfs::polynomials(x, 3);
      REQUIRE(q.size() == 3);
      CHECK(q[0] == 1.0);
      CHECK(q[1] == doctest::Approx((13 - 16 * x) / std::sqrt(19.0)).epsilon(1e-15));
      CHECK(q[2] == doctest::Approx(std::sqrt(2.0) * (29 - 4 * x * (25 - 19 * x)) / std::sqrt(95.0))
                        .epsilon(1e-14)
                        .scale(1e-15));
    }
  }

  TEST_CASE("Q-bfs terms are orthonormal in slope over the unit disc to 1e-10") {
    // Forbes (2007): (2/π) ∫₀¹ S_m'(u) S_n'(u) du/√(1 − u²) = δ_mn, S_m = u²(1 − u²) Q_m(u²).
    // With u = sin t the weight becomes dt and the integrand is a smooth periodic function
    // of t, so the midpoint rule converges spectrally. S_m' is the surface's slope (c = 0).
    constexpr int kTerms = 12, kNodes = 400;
    std::vector<std::vector<double>> slope(kTerms, std::vector<double>(kNodes));
    for (int m = 0; m < kTerms; ++m) {
      std::vector<double> a(static_cast<std::size_t>(m + 1), 0.0);
      a[static_cast<std::size_t>(m)] = 1.0;
      const Qbfs s(0.0, 1.0, a);
      for (int k = 0; k < kNodes; ++k) {
        const double u = std::sin((k + 0.5) / kNodes * std::numbers::pi / 2);
        double z, zx, zy;
        s.sag_gradient(u, 0, z, zx, zy);
        slope[m][k] = zx;
      }
    }
    double worst = 0;
    for (int m = 0; m < kTerms; ++m)
      for (int n = 0; n <= m; ++n) {
        double sum = 0;
        for (int k = 0; k < kNodes; ++k) sum += slope[m][k] * slope[n][k];
        sum /= kNodes;  // (2/π)·(π/2)/kNodes
        worst = std::max(worst, std::abs(sum - (m == n ? 1.0 : 0.0)));
      }
    CHECK(worst < 1e-10);
  }

  TEST_CASE("Q-bfs sag: the sphere plus u²(1−u²)/√(1−c²r²)·Σ a_m Q_m, and its derivatives") {
    const double c = 1.0 / 40.0, rn = 8.0;
    const Qbfs s(c, rn, {0.01, -0.004, 0.002});
    const double x = 3.0, y = 4.0, r2 = 25.0, u2 = r2 / (rn * rn);
    const auto q = Qbfs::polynomials(u2, 3);
    const double root = std::sqrt(1 - c * c * r2);
    const double expected = c * r2 / (1 + root) +
                            u2 * (1 - u2) / root * (0.01 * q[0] - 0.004 * q[1] + 0.002 * q[2]);
    CHECK(s.sag(x, y) == doctest::Approx(expected).epsilon(1e-15));
    CHECK(s.defined_radius() == doctest::Approx(40.0));
    freeturn::test::check_derivatives(s, 5.5);
  }
}
