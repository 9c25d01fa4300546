#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "derivatives_check.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/gauss_legendre.hpp"
#include "freeturn/surface/zernike.hpp"

using namespace freeturn;

namespace {

// A surface that is the single Noll term j, unit coefficient, R_norm = 1, flat base.
Zernike single_term(int j) {
  std::vector<double> a(static_cast<std::size_t>(j), 0.0);
  a.back() = 1.0;
  return Zernike(0.0, 0.0, {}, 1.0, a);
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("Noll ordering and the notes' check values Z4, Z5, Z6, Z231") {
    CHECK(noll_to_nm(1).n == 0);
    CHECK((noll_to_nm(4).n == 2 && noll_to_nm(4).m == 0));
    CHECK((noll_to_nm(5).n == 2 && noll_to_nm(5).m == -2));
    CHECK((noll_to_nm(6).n == 2 && noll_to_nm(6).m == 2));
    CHECK((noll_to_nm(231).n == 20 && noll_to_nm(231).m == -20));
    CHECK_THROWS_AS(noll_to_nm(232), InputError);
    const double rho = 0.73, phi = 0.41;
    const double x = rho * std::cos(phi), y = rho * std::sin(phi);
    CHECK(single_term(4).sag(x, y) ==
          doctest::Approx(std::sqrt(3.0) * (2 * rho * rho - 1)).epsilon(1e-14));
    CHECK(single_term(5).sag(x, y) ==
          doctest::Approx(std::sqrt(6.0) * rho * rho * std::sin(2 * phi)).epsilon(1e-14));
    CHECK(single_term(6).sag(x, y) ==
          doctest::Approx(std::sqrt(6.0) * rho * rho * std::cos(2 * phi)).epsilon(1e-14));
    CHECK(single_term(231).sag(x, y) ==
          doctest::Approx(std::sqrt(42.0) * std::pow(rho, 20) * std::sin(20 * phi)).epsilon(1e-12));
  }

  TEST_CASE("the Cartesian form equals the polar definition for all 231 terms") {
    // Both forms sum alternating radial coefficients of up to 1.8e5 (n = 20), so they
    // agree to rounding of that size, not to 1e-16.
    double worst = 0;
    for (int j = 1; j <= 231; ++j) {
      const Zernike z = single_term(j);
      for (double rho : {0.0, 0.3, 0.77, 1.0})
        for (double phi : {0.0, 1.1, 2.9, 5.5}) {
          const double expected = zernike_polar(j, rho, phi);
          worst =
              std::max(worst, std::abs(z.sag(rho * std::cos(phi), rho * std::sin(phi)) - expected));
        }
    }
    MESSAGE("largest difference between the Cartesian and polar forms: " << worst);
    CHECK(worst <= 1e-10);
  }

  TEST_CASE("Zernike terms are orthonormal over the unit disk to 1e-10") {
    // (1/π) ∫∫ Z_i Z_j ρ dρ dφ by Gauss–Legendre in ρ (exact: degree ≤ 41 with 22 points)
    // and the trapezoid rule in φ (exact for frequencies below the point count).
    const auto rule = freeturn::nurbs::gauss_legendre(22);
    const int nphi = 64;
    const int terms = 231;
    std::vector<std::vector<double>> values(terms);
    std::vector<double> weights;
    for (int a = 0; a < 22; ++a)
      for (int b = 0; b < nphi; ++b) {
        const double rho = 0.5 * (rule.nodes[a] + 1), phi = 2 * std::numbers::pi * b / nphi;
        weights.push_back(0.5 * rule.weights[a] * rho * (2 * std::numbers::pi / nphi) /
                          std::numbers::pi);
        for (int j = 0; j < terms; ++j)
          values[j].push_back(single_term(j + 1).sag(rho * std::cos(phi), rho * std::sin(phi)));
      }
    double worst = 0;
    for (int i = 0; i < terms; ++i)
      for (int j = i; j < terms; ++j) {
        double sum = 0;
        for (std::size_t k = 0; k < weights.size(); ++k)
          sum += weights[k] * values[i][k] * values[j][k];
        worst = std::max(worst, std::abs(sum - (i == j ? 1.0 : 0.0)));
      }
    MESSAGE("largest deviation from orthonormality over 231 terms: " << worst);
    CHECK(worst <= 1e-10);
  }

  TEST_CASE("a 66-term Zernike surface on a conic base: derivatives") {
    std::vector<double> a(66);
    for (int j = 0; j < 66; ++j) a[j] = 1e-3 * std::sin(1.0 + j);
    const Zernike z(1 / 80.0, -0.6, {1e-6}, 10.0, a);
    freeturn::test::check_derivatives(z, 7.0);
  }
}
