// A creased surface decentred without a tilt keeps its creases: a radial section of the
// world is the parent's line through the decentred point (Surface::line_creases). The
// rims of a decentred microlens array against their closed form, |p₀ + ρe − c| = D/2 for
// every lenslet centre c, computed here from the lattice alone.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/odd_asphere.hpp"
#include "freeturn/surface/transformed_surface.hpp"

using namespace freeturn;

namespace {

constexpr double kPitch = 0.25, kDiameter = 0.2;

LensletArrayOptions bowls() {
  LensletArrayOptions o;
  o.lens_radius = 0.6;
  o.lens_diameter = kDiameter;
  o.pitch = kPitch;
  o.pattern = LensletArrayOptions::Pattern::kSquare;
  o.extent = 2.0;
  return o;
}

// The rims' crossings of the line p₀ + ρe, ρ ∈ [lo, hi], ascending: every lattice point
// whose footprint lies inside the extent (the array's rule), by the quadratic's roots.
std::vector<double> rim_crossings(double x0, double y0, double theta, double lo, double hi) {
  const double ct = std::cos(theta), st = std::sin(theta), half = 0.5 * kDiameter;
  std::vector<double> out;
  for (int i = -8; i <= 8; ++i)
    for (int j = -8; j <= 8; ++j) {
      const double cx = i * kPitch, cy = j * kPitch;
      if (std::hypot(cx, cy) > 2.0 - half + 1e-12) continue;
      const double along = (cx - x0) * ct + (cy - y0) * st;
      const double off = (cy - y0) * ct - (cx - x0) * st;
      const double disc = half * half - off * off;
      if (disc < 0) continue;
      for (const double rho : {along - std::sqrt(disc), along + std::sqrt(disc)})
        if (rho >= lo && rho <= hi) out.push_back(rho);
    }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("a decentred microlens array's radial sections cross its rims where they lie") {
    const double dx = 0.1, dy = 0.05;
    const TransformedSurface moved(std::make_unique<LensletArray>(bowls()), dx, dy,
                                   Eigen::Matrix3d::Identity());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), start(-1.4, 0.8),
        length(0.05, 0.6);
    long crossings = 0;
    for (int line = 0; line < 200; ++line) {
      const double theta = angle(rng), lo = start(rng), hi = lo + length(rng);
      std::array<double, 32> found{};
      const int n = moved.section_creases(theta, lo, hi, found);
      const std::vector<double> expected = rim_crossings(dx, dy, theta, lo, hi);
      CAPTURE(theta);
      REQUIRE(n == static_cast<int>(expected.size()));
      for (int k = 0; k < n; ++k)
        CHECK(found[k] == doctest::Approx(expected[k]).epsilon(1e-12).scale(1));
      crossings += n;
    }
    CHECK(crossings > 200);
    // The creases near a point and the bend are the parent's at the moved point.
    const LensletArray parent(bowls());
    std::array<NearbyCrease, 16> a{}, b{};
    const int na = moved.creases_near(0.3, -0.2, 0.15, a);
    const int nb = parent.creases_near(0.3 + dx, -0.2 + dy, 0.15, b);
    REQUIRE(na == nb);
    REQUIRE(na > 0);
    for (int k = 0; k < na; ++k) CHECK(a[k].distance == b[k].distance);
    // The slope's bend on the array is its bowls' (1/0.6 over their footprint, steepest
    // at the rim): the parent's bound, asked as far out as the moved aperture reaches.
    CHECK(moved.max_bend(1.0) == parent.max_bend(1.0 + std::hypot(dx, dy)));
  }

  TEST_CASE("a tilted creased surface reports no crease it cannot place; a smooth one none") {
    const TransformedSurface tilted(std::make_unique<LensletArray>(bowls()), 0.1, 0.0,
                                    TransformedSurface::rotation_from_tilts(0.01, 0));
    std::array<double, 32> found{};
    CHECK(tilted.section_creases(0.3, -1.0, 1.0, found) == 0);
    std::array<NearbyCrease, 16> near{};
    CHECK(tilted.creases_near(0.3, 0.0, 0.2, near) == -1);  // not known
    // An axicon's apex decentred: the default knows creases only on lines through its axis.
    const TransformedSurface apex(std::make_unique<OddAsphere>(0, 0, std::vector<double>{-0.2}),
                                  0.5, 0.0, Eigen::Matrix3d::Identity());
    CHECK(apex.section_creases(0.0, -1.0, 1.0, found) == 0);
    const OddAsphere centred(0, 0, {-0.2});
    CHECK(centred.line_creases(0, 0, RadialLine(0.7), -1.0, 1.0, found) == 1);
    CHECK(found[0] == 0.0);
    CHECK(centred.line_creases(0.5, 0, RadialLine(0.7), -1.0, 1.0, found) == -1);
  }
}
