#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "derivatives_check.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/surface/biconic.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/toroidal.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/surface/xy_polynomial.hpp"
#include "freeturn/surface/zernike.hpp"

using namespace freeturn;
using freeturn::test::check_derivatives;

TEST_SUITE("surface") {
  TEST_CASE("biconic: equal directions give the conic; derivatives") {
    const Biconic b(1 / 40.0, 1 / 40.0, -0.5, -0.5);
    const EvenAsphere conic(1 / 40.0, -0.5);
    for (double x : {-7.0, 0.0, 3.5})
      for (double y : {-2.0, 5.0})
        CHECK(b.sag(x, y) == doctest::Approx(conic.sag(x, y)).epsilon(1e-15));
    const Biconic anamorphic(1 / 30.0, -1 / 55.0, 0.3, -2.0);
    check_derivatives(anamorphic, 8.0);
    // Flat in y (c_y = 0): a cylinder along y, sag from x alone.
    const Biconic cylinder(1 / 20.0, 0.0, 0.0, 0.0);
    CHECK(cylinder.sag(3.0, 9.0) == doctest::Approx(20 - std::sqrt(400 - 9.0)).epsilon(1e-15));
    CHECK(anamorphic.defined_radius() == doctest::Approx(30 / std::sqrt(1.3)).epsilon(1e-15));
  }

  TEST_CASE("toroidal: a torus with equal radii is a sphere; a cylinder; derivatives") {
    const double R = 25.0;
    const Toroidal sphere_like(1 / R, 0.0, R, {});
    const EvenAsphere sphere(1 / R, 0.0);
    for (double x : {-6.0, 0.0, 4.0})
      for (double y : {-3.0, 7.0})
        CHECK(sphere_like.sag(x, y) == doctest::Approx(sphere.sag(x, y)).epsilon(1e-14));
    const Toroidal cylinder(1 / R, 0.0, 0.0, {});
    CHECK(cylinder.sag(5.0, 3.0) == doctest::Approx(R - std::sqrt(R * R - 9)).epsilon(1e-15));
    const Toroidal torus(1 / 30.0, -0.4, -80.0, {1e-4, -2e-7});
    check_derivatives(torus, 8.0);
  }

  TEST_CASE("xy polynomial: term numbering and sag") {
    CHECK(xy_polynomial_term(1).a == 1);
    CHECK(xy_polynomial_term(2).b == 1);
    const Monomial m12 = xy_polynomial_term(12);
    CHECK((m12.a == 2 && m12.b == 2));  // x²y² is term 12
    const Monomial m230 = xy_polynomial_term(230);
    CHECK((m230.a == 0 && m230.b == 20));
    CHECK_THROWS_AS(xy_polynomial_term(231), InputError);
    std::vector<double> a(12, 0.0);
    a[11] = 3e-3;  // x²y²
    a[3] = -2e-2;  // term 4: xy
    const XyPolynomial p(0.0, 0.0, 5.0, a);
    const double x = 1.7, y = -2.4;
    CHECK(p.sag(x, y) ==
          doctest::Approx(3e-3 * x * x * y * y / 625 - 2e-2 * x * y / 25).epsilon(1e-15));
    std::vector<double> many(65);
    for (std::size_t i = 0; i < many.size(); ++i) many[i] = 1e-3 * std::cos(double(i));
    check_derivatives(XyPolynomial(1 / 50.0, -1.0, 10.0, many), 9.0);
  }

  TEST_CASE("sinusoidal ring, sinusoidal grid and Alvarez plate: closed forms and derivatives") {
    const SinusoidalRing ring(0.005, 2 * std::numbers::pi / 2.5, 0.01);
    CHECK(ring.sag(3.0, 4.0) ==
          doctest::Approx(0.005 * std::sin(2 * std::numbers::pi / 2.5 * 5) + 0.01).epsilon(1e-15));
    CHECK(ring.sag(0.0, 0.0) == 0.01);
    check_derivatives(ring, 10.0, 100, 0.05, 1e-5);
    const SinusoidalGrid grid(0.002, 4.0, 6.0);
    CHECK(grid.sag(1.0, 1.5) == doctest::Approx(0.002).epsilon(1e-15));  // both sines at 1
    check_derivatives(grid, 10.0);
    const Alvarez alvarez(1e-3, 0.02);
    CHECK(alvarez.sag(2.0, 3.0) == doctest::Approx(1e-3 * (18 + 8.0 / 3) + 0.04).epsilon(1e-15));
    check_derivatives(alvarez, 10.0);
  }

  TEST_CASE(
      "jet surfaces: the first-order jet's value and gradient are the second-order jet's, bit for "
      "bit") {
    // A jet formula is evaluated on Jet<1> for the planner (sag_gradient) and on Jet<2> for
    // curvatures (height_derivatives). Jet<1> holds no Hessian and starts uninitialised like a
    // double, so an array of them costs nothing to declare; its value and gradient follow the
    // same operations as Jet<2>'s and must agree to the last bit, signs of zero included.
    std::vector<double> xy_terms(65), zernike_terms(37);
    for (std::size_t i = 0; i < xy_terms.size(); ++i) xy_terms[i] = 1e-3 * std::cos(double(i));
    for (std::size_t i = 0; i < zernike_terms.size(); ++i)
      zernike_terms[i] = 1e-4 * std::sin(1.0 + double(i));
    const Biconic biconic(1 / 30.0, -1 / 55.0, 0.3, -2.0);
    const Toroidal toroidal(1 / 40.0, -0.4, 30.0, {1e-5, -2e-8});
    const XyPolynomial xy(1 / 50.0, -1.0, 10.0, xy_terms);
    const Zernike zernike(1 / 80.0, 0.2, {1e-6, -2e-8, 0, 0, 0, 0, 0, 0, 0}, 6.0, zernike_terms);
    const SinusoidalRing ring(0.005, 2 * std::numbers::pi / 2.5, 0.01);
    const SinusoidalGrid grid(0.002, 4.0, 6.0);
    const Alvarez alvarez(1e-3, 0.02);
    const Surface* surfaces[] = {&biconic, &toroidal, &xy, &zernike, &ring, &grid, &alvarez};
    const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> u(-5.5, 5.5);
    for (const Surface* s : surfaces)
      for (int k = 0; k < 500; ++k) {
        const double x = k == 0 ? 0.0 : u(rng), y = k == 0 ? -0.0 : u(rng);
        double z, zx, zy;
        s->sag_gradient(x, y, z, zx, zy);
        const HeightDerivatives h = s->height_derivatives(x, y);
        CAPTURE(s->type());
        CAPTURE(x);
        CAPTURE(y);
        CHECK(bits(z) == bits(h.z));
        CHECK(bits(zx) == bits(h.zx));
        CHECK(bits(zy) == bits(h.zy));
      }
  }

  TEST_CASE("off-axis parabola: decentred sag matches its parent frame; tilted one lies on it") {
    const double f = 100.0, x0 = 40.0;  // parent z = r²/(4f)
    auto parent = [&] { return std::make_unique<EvenAsphere>(1 / (2 * f), -1.0); };
    const TransformedSurface decentred(parent(), x0, 0.0, Eigen::Matrix3d::Identity());
    for (double x : {-10.0, 0.0, 6.0})
      for (double y : {-8.0, 0.0, 3.0}) {
        const double expected = ((x + x0) * (x + x0) + y * y - x0 * x0) / (4 * f);
        CHECK(decentred.sag(x, y) == doctest::Approx(expected).epsilon(1e-14).scale(1e-12));
      }
    check_derivatives(decentred, 10.0);

    const EvenAsphere reference = *parent();
    const Eigen::Matrix3d tilt = TransformedSurface::rotation_aligning_normal(reference, x0, 0.0);
    const TransformedSurface segment(parent(), x0, 0.0, tilt);
    CHECK(segment.sag(0.0, 0.0) == doctest::Approx(0.0).scale(1e-12));
    CHECK((segment.normal(0.0, 0.0) - Eigen::Vector3d::UnitZ()).norm() <= 1e-12);
    for (double x : {-10.0, -3.0, 0.0, 8.0})
      for (double y : {-9.0, 0.0, 4.0}) {
        const Eigen::Vector3d X = segment.to_parent(segment.point(x, y));
        CHECK(std::abs(X.z() - reference.sag(X.x(), X.y())) <= 1e-12);
      }
    check_derivatives(segment, 10.0);
  }
}
