#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "freeturn/surface/polynomial_height.hpp"
#include "freeturn/surface/zernike.hpp"

using namespace freeturn;

TEST_SUITE("surface") {
  TEST_CASE("a Zernike sum expanded into powers equals its Jacobi form, value and derivatives") {
    // Every term to n = 8 (45 terms) with coefficients of a few hundred nanometres.
    std::mt19937 random(11);
    std::uniform_real_distribution<double> coefficient(-3e-4, 3e-4), place(-4.5, 4.5);
    std::vector<double> a(45);
    for (double& v : a) v = coefficient(random);
    const Zernike jacobi(0, 0, {}, 4.0, a);
    const PolynomialHeight powers = PolynomialHeight::from_zernike(4.0, a);
    for (int k = 0; k < 200; ++k) {
      const double x = place(random), y = place(random);
      const HeightDerivatives p = powers.height_derivatives(x, y), z = jacobi.height_derivatives(x, y);
      CHECK(p.z == doctest::Approx(z.z).epsilon(1e-11).scale(1e-3));
      CHECK(p.zx == doctest::Approx(z.zx).epsilon(1e-11).scale(1e-3));
      CHECK(p.zy == doctest::Approx(z.zy).epsilon(1e-11).scale(1e-3));
      CHECK(p.zxx == doctest::Approx(z.zxx).epsilon(1e-11).scale(1e-3));
      CHECK(p.zxy == doctest::Approx(z.zxy).epsilon(1e-11).scale(1e-3));
      CHECK(p.zyy == doctest::Approx(z.zyy).epsilon(1e-11).scale(1e-3));
      double s, sx, sy;
      powers.sag_gradient(x, y, s, sx, sy);
      CHECK(s == p.z);
      CHECK(sx == p.zx);
      CHECK(sy == p.zy);
    }
  }

  TEST_CASE("single terms against their closed forms: Z4 = √3 (2ρ² − 1), Z9 = √8 ρ³ sin 3φ") {
    std::vector<double> z4(4, 0.0), z9(9, 0.0);
    z4[3] = 1;
    z9[8] = 1;
    const PolynomialHeight defocus = PolynomialHeight::from_zernike(2.0, z4);
    const PolynomialHeight trefoil = PolynomialHeight::from_zernike(2.0, z9);
    const double x = 0.7, y = -1.3, rho = std::hypot(x, y) / 2, phi = std::atan2(y, x);
    CHECK(defocus.sag(x, y) == doctest::Approx(std::sqrt(3.0) * (2 * rho * rho - 1)).epsilon(1e-14));
    CHECK(trefoil.sag(x, y) == doctest::Approx(std::sqrt(8.0) * std::pow(rho, 3) * std::sin(3 * phi)).epsilon(1e-13));
  }
}
