// Surface::max_bend against the Hessian's largest eigenvalue sampled at random points within
// the radius (each from the surface's own second derivatives): never below it, and for the
// sinusoidal grid and the bare conic, reached.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "freeturn/surface/biconic.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/odd_asphere.hpp"
#include "freeturn/surface/qbfs.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/toroidal.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/surface/xy_polynomial.hpp"
#include "freeturn/surface/zernike.hpp"

using namespace freeturn;

namespace {

// Conic bases (c, k) of each kind: a sphere, a prolate ellipsoid, hyperboloids of either
// sign, an oblate ellipsoid.
constexpr std::array<std::array<double, 2>, 5> kConics{
    {{0.05, 0.0}, {-0.05, -0.5}, {0.1, -3.0}, {-0.1, -2.0}, {0.08, 2.0}}};

// The largest second derivative along a unit direction at (x, y): the Hessian's largest
// eigenvalue, in closed form for a symmetric 2 × 2.
double largest_bend(const Surface& s, double x, double y) {
  const HeightDerivatives d = s.height_derivatives(x, y);
  const double mean = 0.5 * (d.zxx + d.zyy), half = 0.5 * (d.zxx - d.zyy);
  return mean + std::hypot(half, d.zxy);
}

// The largest |∇z| over n random points within `radius` of the axis.
double sampled_max_slope(const Surface& s, double radius, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  double most = 0;
  for (int k = 0; k < n; ++k) {
    const double r = radius * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
    double z, zx, zy;
    s.sag_gradient(r * std::cos(phi), r * std::sin(phi), z, zx, zy);
    most = std::max(most, std::hypot(zx, zy));
  }
  return most;
}

// The largest of largest_bend over n random points within `radius` of the axis.
double sampled_max_bend(const Surface& s, double radius, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  double most = -1e300;
  for (int k = 0; k < n; ++k) {
    const double r = radius * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
    most = std::max(most, largest_bend(s, r * std::cos(phi), r * std::sin(phi)));
  }
  return most;
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("max_bend of a sinusoidal grid: |A| max(kx, ky)², never exceeded and reached") {
    for (const auto& [a, lx, ly] :
         {std::array{0.005, 0.3, 0.4}, std::array{-0.02, 0.9, 0.25}, std::array{0.001, 0.5, 0.5}}) {
      const SinusoidalGrid grid(a, lx, ly);
      const double k = 2 * std::numbers::pi / std::min(lx, ly);
      CHECK(grid.max_bend(1.0) == doctest::Approx(std::abs(a) * k * k).epsilon(1e-15));
      const double sampled = sampled_max_bend(grid, 2.0, 200000, 3);
      CHECK(sampled <= grid.max_bend(2.0) * (1 + 1e-12));
      CHECK(sampled >= 0.99 * grid.max_bend(2.0));  // at a crest or a trough
    }
  }

  TEST_CASE("max_bend of an XY polynomial: never below the bend anywhere within the radius") {
    // A conic base of each kind (a bowl, a dome, a hyperboloid, an oblate ellipsoid) with
    // terms to order 6, coefficients of a few micrometres over a 2 mm normalization.
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> coefficient(-4e-3, 4e-3);
    std::vector<double> terms(27);
    for (double& v : terms) v = coefficient(rng);
    for (const auto& [c, kappa] : kConics) {
      CAPTURE(c);
      CAPTURE(kappa);
      const XyPolynomial s(c, kappa, 2.0, terms);
      for (const double radius : {0.5, 1.5, 2.5}) {
        CAPTURE(radius);
        CHECK(std::isfinite(s.max_bend(radius)));
        CHECK(sampled_max_bend(s, radius, 20000, 5) <= s.max_bend(radius));
      }
      // The conic alone: its bound is the largest eigenvalue, reached at the axis or the rim.
      const XyPolynomial conic(c, kappa, 2.0, {});
      const double bound = conic.max_bend(1.5);
      const double reached = std::max(
          {largest_bend(conic, 0, 0), largest_bend(conic, 1.5, 0), largest_bend(conic, 0, -1.5)});
      CHECK(reached == doctest::Approx(bound).epsilon(1e-12));
    }
    // Past the conic's defined radius: no bound.
    CHECK(std::isinf(XyPolynomial(0.1, 0.0, 2.0, terms).max_bend(10.5)));
  }

  TEST_CASE("max_bend of an even asphere: never below the bend, the bare conic's reached") {
    // Terms A4 … A10 of either sign, sized to move the sag by micrometres at 5 mm.
    const std::array<double, 9> terms{2e-6, -4e-8, 3e-10, -1e-12};
    for (const auto& [c, kappa] : kConics) {
      CAPTURE(c);
      CAPTURE(kappa);
      const EvenAsphere s(c, kappa, terms);
      for (const double radius : {1.0, 3.0, 5.0}) {
        CAPTURE(radius);
        CHECK(std::isfinite(s.max_bend(radius)));
        CHECK(sampled_max_bend(s, radius, 20000, 9) <= s.max_bend(radius));
      }
      const EvenAsphere conic(c, kappa);
      const double bound = conic.max_bend(3.0);
      const double reached = std::max(
          {largest_bend(conic, 0, 0), largest_bend(conic, 3.0, 0), largest_bend(conic, 0, -3.0)});
      CHECK(reached == doctest::Approx(bound).epsilon(1e-12));
    }
  }
  TEST_CASE("max_bend of a Zernike sag: never below the bend anywhere within the radius") {
    // Noll terms 1 to 45 (to n = 8) of a few micrometres over a 2.5 mm normalization, with
    // asphere terms, on each kind of conic.
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> coefficient(-2e-3, 2e-3);
    std::vector<double> terms(45);
    for (double& v : terms) v = coefficient(rng);
    const std::array<double, 9> asphere{1e-5, -2e-7};
    for (const auto& [c, kappa] : {std::array{0.05, 0.0}, std::array{-0.05, -0.5},
                                   std::array{0.1, -3.0}, std::array{0.0, 0.0}}) {
      CAPTURE(c);
      const Zernike s(c, kappa, asphere, 2.5, terms);
      for (const double radius : {0.5, 1.5, 2.5}) {
        CAPTURE(radius);
        CHECK(std::isfinite(s.max_bend(radius)));
        CHECK(sampled_max_bend(s, radius, 20000, 13) <= s.max_bend(radius));
      }
    }
    // A single astigmatism term, Z6 = √6 ρ² cos 2φ = √6 (X² − Y²): it bends 2√6 A/R_n² along
    // x, and the bound, 2·(√6 + √6)·A/R_n², counts both powers' coefficients.
    std::vector<double> z6(6, 0.0);
    z6[5] = 1e-3;
    const Zernike astigmatism(0, 0, {}, 2.0, z6);
    CHECK(largest_bend(astigmatism, 0.3, -0.7) == doctest::Approx(2 * std::sqrt(6.0) * 1e-3 / 4));
    CHECK(astigmatism.max_bend(1.0) == doctest::Approx(4 * std::sqrt(6.0) * 1e-3 / 4));
  }

  TEST_CASE(
      "max_bend of an odd asphere: never below the bend, reached for one term, none for a cone") {
    // β₂ … β₇ of either sign, sized to move the sag by micrometres at 5 mm, on each kind of
    // conic; with β₁ < 0 (the tip of a cone pointing up, which bends no way but down).
    const std::vector<double> terms{0.0, 3e-4, -2e-5, 1.5e-5, -4e-7, 2e-8, -1e-9};
    std::vector<double> coned = terms;
    coned[0] = -2e-3;
    for (const auto& [c, kappa] : kConics) {
      CAPTURE(c);
      CAPTURE(kappa);
      for (const auto& beta : {terms, coned}) {
        const OddAsphere s(c, kappa, beta);
        for (const double radius : {1.0, 3.0, 5.0}) {
          CAPTURE(radius);
          CHECK(std::isfinite(s.max_bend(radius)));
          CHECK(sampled_max_bend(s, radius, 20000, 11) <= s.max_bend(radius));
        }
      }
    }
    // β₃ r³ alone bends 6β₃r along the radius: reached at the rim.
    const OddAsphere cubic(0.0, 0.0, {0.0, 0.0, 2e-4});
    CHECK(cubic.max_bend(4.0) == doctest::Approx(6 * 2e-4 * 4.0).epsilon(1e-15));
    CHECK(largest_bend(cubic, 0.0, 4.0) == doctest::Approx(cubic.max_bend(4.0)).epsilon(1e-12));
    // A cone pointing down (β₁ > 0) bends β₁/r along the circle: no bound near the vertex.
    CHECK(largest_bend(OddAsphere(0.0, 0.0, {1e-3}), 1e-6, 0.0) == doctest::Approx(1e3));
    CHECK(std::isinf(OddAsphere(0.0, 0.0, {1e-3}).max_bend(1.0)));
  }

  TEST_CASE("max_bend of a Q-bfs asphere: never below the bend, within and past r_max") {
    // a_0 … a_10 of a few micrometres over r_max 5 mm, on best-fit spheres of either sign
    // and on a plane, out to 1.3 r_max (the nose's reach past a part cut to r_max).
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> coefficient(-3e-3, 3e-3);
    std::vector<double> terms(11);
    for (double& v : terms) v = coefficient(rng);
    for (const double c : {0.05, -0.05, 0.0, 0.12}) {
      CAPTURE(c);
      for (const std::size_t count : {std::size_t{1}, std::size_t{4}, terms.size()}) {
        CAPTURE(count);
        const Qbfs s(c, 5.0, std::vector<double>(terms.begin(), terms.begin() + count));
        for (const double radius : {1.0, 3.0, 5.0, 6.5}) {
          CAPTURE(radius);
          const double bound = s.max_bend(radius);
          CHECK(std::isfinite(bound));
          CHECK(sampled_max_bend(s, radius, 20000, 17) <= bound);
        }
      }
      // The best-fit sphere alone: c/(1 − c²r²)^{3/2} at the rim for a bowl, c for a dome.
      const Qbfs sphere(c, 5.0, {});
      const double reached = std::max(largest_bend(sphere, 0, 0), largest_bend(sphere, 0, 4.0));
      CHECK(sphere.max_bend(4.0) == doctest::Approx(reached).epsilon(1e-12));
    }
    // A design of a few micrometres on a 20 mm sphere bends far less than a 0.5 mm nose, and
    // the bound says so (the planner's searches and checks use it only under 1/R): within
    // r_max it is under twice the sampled bend (0.104 against 0.054 /mm); 0.5 mm past r_max,
    // where the Q_m grow fast, under a quarter of 1/R (0.30 against 0.075).
    const Qbfs design(0.05, 5.0, {0.002, -0.001, 0.0005, 0.0003, -0.0002});
    CHECK(design.max_bend(5.0) < 2 * sampled_max_bend(design, 5.0, 20000, 19));
    CHECK(design.max_bend(5.5) < 0.5);
    CHECK(design.max_bend(5.5) >= sampled_max_bend(design, 5.5, 20000, 19));
    // Past the sphere's radius: no bound.
    CHECK(std::isinf(Qbfs(0.1, 5.0, terms).max_bend(10.5)));
  }

  TEST_CASE("max_bend of a biconic: never below the bend, near it on a gentle part") {
    // Each pairing of bowl, dome and plane across the two sections, with conics of each kind.
    for (const auto& [cx, cy, kx, ky] :
         {std::array{0.05, 0.02, 0.0, -1.5}, std::array{-0.08, 0.03, -0.5, 2.0},
          std::array{-0.05, -0.1, 1.0, -3.0}, std::array{0.0, 0.12, 0.0, -0.8},
          std::array{0.1, 0.1, -0.6, -0.6}}) {
      CAPTURE(cx);
      CAPTURE(cy);
      const Biconic s(cx, cy, kx, ky);
      for (const double radius : {1.0, 3.0, 5.0}) {
        CAPTURE(radius);
        const double bound = s.max_bend(radius);
        CHECK(std::isfinite(bound));
        CHECK(sampled_max_bend(s, radius, 20000, 23) <= bound);
      }
    }
    // At the vertex a biconic bends c_x along x and c_y along y: the bound at radius 0.
    CHECK(Biconic(0.05, 0.02, 0.0, -1.5).max_bend(0.0) == doctest::Approx(0.05).epsilon(1e-15));
    // An anamorphic part of R 20 and 50 mm over 5 mm: within 15 % of its sampled bend.
    const Biconic part(0.05, 0.02, -0.5, 0.0);
    CHECK(part.max_bend(5.0) < 1.15 * sampled_max_bend(part, 5.0, 20000, 29));
    // Past the defined radius: no bound.
    CHECK(std::isinf(Biconic(0.1, 0.05, 0.0, 0.0).max_bend(10.5)));
  }

  TEST_CASE("max_bend of a toroidal surface: never below the bend, near it on a gentle part") {
    // Profiles of each kind (bowl, dome, with and without α terms) turned about axes on
    // either side, and a cylinder (R_rot = 0).
    const std::array<double, 8> alpha{2e-4, -3e-6, 4e-8};
    for (const auto& [c, k, r_rot] :
         {std::array{0.05, 0.0, 30.0}, std::array{-0.05, -0.5, -25.0}, std::array{0.1, -3.0, -12.0},
          std::array{-0.02, 1.0, 15.0}, std::array{0.08, 0.0, 0.0}}) {
      CAPTURE(c);
      CAPTURE(r_rot);
      for (const auto& terms : {std::array<double, 8>{}, alpha}) {
        const Toroidal s(c, k, r_rot, terms);
        for (const double radius : {1.0, 3.0, 5.0}) {
          CAPTURE(radius);
          const double bound = s.max_bend(radius);
          CHECK(std::isfinite(bound));
          CHECK(sampled_max_bend(s, radius, 20000, 31) <= bound);
        }
      }
    }
    // A cylinder's profile bends c at its vertex line: the bound at radius 0.
    CHECK(Toroidal(0.08, 0.0, 0.0, {}).max_bend(0.0) == doctest::Approx(0.08).epsilon(1e-11));
    // A toric lens, profile R 40 mm turned at 25 mm, over 5 mm: within 25 % of its sampled bend.
    const Toroidal part(0.025, 0.0, 25.0, {});
    CHECK(part.max_bend(5.0) < 1.25 * sampled_max_bend(part, 5.0, 20000, 37));
    // The axis inside the reach of the radius (|R_rot| − max|z| ≤ r): no bound.
    CHECK(std::isinf(Toroidal(0.05, 0.0, 4.0, {}).max_bend(5.0)));
  }

  TEST_CASE("max_bend of an Alvarez surface: 2√2|A|r, never exceeded and reached") {
    for (const auto& [a, d] : {std::array{0.002, 0.0}, std::array{-0.01, 0.3}}) {
      CAPTURE(a);
      const Alvarez s(a, d);
      for (const double radius : {1.0, 4.0}) {
        const double bound = s.max_bend(radius);
        CHECK(sampled_max_bend(s, radius, 20000, 41) <= bound * (1 + 1e-12));
        // On the rim at 45°, x of A's sign: 2A x + 2|A y| = 2√2|A| r.
        const double x = (a > 0 ? 1 : -1) * radius / std::sqrt(2.0), y = radius / std::sqrt(2.0);
        CHECK(largest_bend(s, x, y) == doctest::Approx(bound).epsilon(1e-12));
      }
    }
  }

  TEST_CASE("max_slope of an even asphere: never below the slope, the bare conic's reached") {
    const std::array<double, 9> terms{2e-6, -4e-8, 3e-10, -1e-12};
    for (const auto& [c, kappa] : kConics) {
      CAPTURE(c);
      CAPTURE(kappa);
      const EvenAsphere s(c, kappa, terms);
      for (const double radius : {1.0, 3.0, 5.0})
        CHECK(sampled_max_slope(s, radius, 20000, 43) <= s.max_slope(radius));
      // The conic's slope c·r/q grows with r: at the rim it is the bound.
      const EvenAsphere conic(c, kappa);
      double z, zx, zy;
      conic.sag_gradient(0.0, 3.0, z, zx, zy);
      CHECK(std::hypot(zx, zy) == doctest::Approx(conic.max_slope(3.0)).epsilon(1e-12));
    }
  }

  TEST_CASE("max_bend of a tilted segment: never below the bend, near it on an off-axis parabola") {
    // Off-axis parabolas (R 200 mm and 60 mm, decentred 40 and 20 mm, each on its own axis)
    // and two aspheres tilted by explicit angles, over 5 mm. The 20 mm bowl tilted 0.22 rad
    // bends 0.07 mm⁻¹ where the world sees it steepest, more than the parent's own bound
    // there (0.053): the tilt's 1/cos³θ is needed.
    struct Segment {
      double c, k, decentre;
      bool align;
    };
    for (const Segment& g : {Segment{1 / 200.0, -1, 40, true}, Segment{1 / 60.0, -1, 20, true},
                             Segment{-1 / 80.0, -0.5, 10, false}, Segment{0.05, 0.0, 0, false}}) {
      CAPTURE(g.c);
      auto parent = std::make_unique<EvenAsphere>(g.c, g.k, std::array<double, 9>{1e-7});
      const Eigen::Matrix3d r =
          g.align ? TransformedSurface::rotation_aligning_normal(*parent, g.decentre, 0)
                  : TransformedSurface::rotation_from_tilts(0.1, -0.2);
      const TransformedSurface s(std::move(parent), g.decentre, 0, r);
      for (const double radius : {1.0, 5.0}) {
        CAPTURE(radius);
        const double bound = s.max_bend(radius);
        CHECK(std::isfinite(bound));
        const double sampled = sampled_max_bend(s, radius, 20000, 47);
        CHECK(sampled <= bound);
        // The 200 mm parabola with its A4 bends about 0.0067 mm⁻¹ on its 5 mm segment; the
        // bound takes the parent's bend 45 mm out and its normal's angle there plus the
        // tilt, 24° where the segment's own normal turns by a few, and is within twice that
        // (0.0108), far under any nose's 1/R.
        if (g.c == 1 / 200.0) CHECK(bound < 2 * sampled);
      }
    }
    // A tilt that turns the parent's normal past 90° somewhere: no bound.
    auto steep = std::make_unique<EvenAsphere>(0.1, 0.0);
    const TransformedSurface tilted(std::move(steep), 0, 0,
                                    TransformedSurface::rotation_from_tilts(1.2, 0.0));
    CHECK(std::isinf(tilted.max_bend(5.0)));
  }

  TEST_CASE("max_slope of the polynomial surfaces: never below the slope within the radius") {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> coefficient(-3e-3, 3e-3);
    std::vector<double> xy(27), zernike(45), q(11);
    for (auto* terms : {&xy, &zernike, &q})
      for (double& v : *terms) v = coefficient(rng);
    const std::vector<double> odd{-2e-3, 3e-4, -2e-5, 1.5e-5, -4e-7, 2e-8, -1e-9};
    for (const auto& [c, kappa] : {std::array{0.05, 0.0}, std::array{-0.05, -0.5},
                                   std::array{0.1, -3.0}, std::array{0.0, 0.0}}) {
      CAPTURE(c);
      const XyPolynomial s_xy(c, kappa, 2.0, xy);
      const Zernike s_zernike(c, kappa, {1e-5, -2e-7}, 2.5, zernike);
      const OddAsphere s_odd(c, kappa, odd);
      const Qbfs s_q(c, 5.0, q);
      for (const double radius : {0.5, 2.0, 4.0}) {
        CAPTURE(radius);
        for (const Surface* s : std::array<const Surface*, 4>{&s_xy, &s_zernike, &s_odd, &s_q}) {
          CAPTURE(s->type());
          const double bound = s->max_slope(radius);
          CHECK(std::isfinite(bound));
          CHECK(sampled_max_slope(*s, radius, 20000, 59) <= bound);
        }
      }
    }
    // X³ alone over R_n = 2 (coefficient 1e-3): slope 3·1e-3·x²/8, reached on the x axis.
    std::vector<double> cubic(6, 0.0);
    cubic[5] = 1e-3;  // term 6, x³ (x, y, x², xy, y², x³, …)
    const XyPolynomial x3(0, 0, 2.0, cubic);
    double z, zx, zy;
    x3.sag_gradient(1.5, 0.0, z, zx, zy);
    CHECK(std::hypot(zx, zy) == doctest::Approx(x3.max_slope(1.5)).epsilon(1e-12));
  }

  TEST_CASE("max_section_bend: the radial sections' bound where lines off the axis have none") {
    // The sinusoidal ring along its radial sections bends −Aω² sin(ω|ρ|): |A|ω², reached at
    // a trough; just off its cone point a line bends without bound, so max_bend has none.
    const double a = 0.05, w = 2 * std::numbers::pi / 0.8;
    const SinusoidalRing ring(a, w, 0.0);
    CHECK(std::isinf(ring.max_bend(2.0)));
    CHECK(largest_bend(ring, 1e-4, 1e-3) > 100);
    double most = -1e300;
    for (int k = 1; k <= 20000; ++k) {
      const double rho = 2.0 * k / 20000, phi = 0.37 * k;
      const HeightDerivatives d = ring.height_derivatives(rho * std::cos(phi), rho * std::sin(phi));
      const double c = std::cos(phi), s = std::sin(phi);
      most = std::max(most, (d.zxx * c + 2 * d.zxy * s) * c + d.zyy * s * s);
    }
    CHECK(most <= ring.max_section_bend(2.0) * (1 + 1e-12));
    CHECK(most >= 0.999 * ring.max_section_bend(2.0));
    // An odd asphere with a cone pointing down (β₁ > 0): none off the axis, its other terms'
    // along the radial sections; a surface without its own keeps max_bend's.
    const OddAsphere coned(0.05, 0.0, {2e-3, 3e-4, -2e-5, 1.5e-5});
    CHECK(std::isinf(coned.max_bend(3.0)));
    CHECK(coned.max_section_bend(3.0) ==
          doctest::Approx(OddAsphere(0.05, 0.0, {0.0, 3e-4, -2e-5, 1.5e-5}).max_bend(3.0)));
    const EvenAsphere plain(0.05, -0.5);
    CHECK(plain.max_section_bend(3.0) == plain.max_bend(3.0));
  }

  TEST_CASE("max_bend and max_slope of a NURBS height field on affine parameters: from its net") {
    // Bicubic nets over [−3, 3]² on uniform clamped knots, x and y at the Greville abscissae
    // (affine parameters), z a smooth bump of 20 µm plus random ripples of 2 µm.
    const int n = 9, p = 3;
    const nurbs::KnotVector knots = nurbs::KnotVector::uniform_clamped(p, n);
    std::vector<double> k(knots.knots().begin(), knots.knots().end());
    std::mt19937 rng(61);
    std::uniform_real_distribution<double> ripple(-2e-3, 2e-3);
    for (const double bump : {0.02, -0.02, 0.0}) {
      CAPTURE(bump);
      std::vector<Eigen::Vector3d> points;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double x = -3 + 6 * knots.greville(i), y = -3 + 6 * knots.greville(j);
          points.emplace_back(x, y, bump * std::exp(-(x * x + y * y) / 4) + ripple(rng));
        }
      const NurbsHeightField s(nurbs::NurbsSurface(p, p, k, k, points));
      REQUIRE(s.affine_parameters());
      const double bend = sampled_max_bend(s, 2.9, 20000, 67);
      const double slope = sampled_max_slope(s, 2.9, 20000, 67);
      CHECK(bend <= s.max_bend(2.9));
      CHECK(slope <= s.max_slope(2.9));
      // The net's differences exceed the surface's on random ripples (0.012 to 0.020 /mm
      // sampled, bounds 0.044 to 0.065), yet stay within a few times and far under 1/R.
      CHECK(s.max_bend(2.9) < 4 * bend);
      CHECK(s.max_slope(2.9) < 2.5 * slope);
    }
    // A plane z = 0.01x + 0.02y: no bend, and its slope exactly.
    std::vector<Eigen::Vector3d> plane;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = -3 + 6 * knots.greville(i), y = -3 + 6 * knots.greville(j);
        plane.emplace_back(x, y, 0.01 * x + 0.02 * y);
      }
    const NurbsHeightField flat(nurbs::NurbsSurface(p, p, k, k, plane));
    CHECK(std::abs(flat.max_bend(1.0)) <= 1e-12);
    CHECK(flat.max_slope(1.0) == doctest::Approx(std::hypot(0.01, 0.02)).epsilon(1e-12));
    // A paraboloid z = x²/40 (a net that reproduces it: the quadratic's blossom at the knots)
    // bends 1/20 along x: the net's second differences give it exactly.
    const nurbs::KnotVector quad = nurbs::KnotVector::uniform_clamped(2, n);
    std::vector<double> kq(quad.knots().begin(), quad.knots().end());
    std::vector<Eigen::Vector3d> bowl;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        // The blossom of x² (x = −3 + 6u) at (u_{i+1}, u_{i+2}): x(u_{i+1})·x(u_{i+2}).
        const double x1 = -3 + 6 * kq[static_cast<std::size_t>(i + 1)];
        const double x2 = -3 + 6 * kq[static_cast<std::size_t>(i + 2)];
        bowl.emplace_back(-3 + 6 * quad.greville(i), -3 + 6 * quad.greville(j), x1 * x2 / 40);
      }
    const NurbsHeightField parabolic(nurbs::NurbsSurface(2, 2, kq, kq, bowl));
    REQUIRE(parabolic.affine_parameters());
    CHECK(parabolic.sag(1.3, 0.4) == doctest::Approx(1.3 * 1.3 / 40).epsilon(1e-12));
    CHECK(parabolic.max_bend(1.0) == doctest::Approx(1.0 / 20).epsilon(1e-12));
    // A net that is not on affine parameters gives none.
    std::vector<Eigen::Vector3d> skewed = plane;
    for (Eigen::Vector3d& q : skewed) q.x() += 0.05 * q.y();
    CHECK(std::isinf(NurbsHeightField(nurbs::NurbsSurface(p, p, k, k, skewed)).max_bend(1.0)));
  }
}
