// A creased surface decentred without a tilt keeps its creases: a radial section of the
// world is the parent's line through the decentred point (Surface::line_creases). The
// rims of a decentred microlens array against their closed form, |p₀ + ρe − c| = D/2 for
// every lenslet centre c, computed here from the lattice alone. Tilted, or a compound eye
// off its axis, the rims' ellipses (ProjectedRims) against a walk of each circle and
// against the section's own slope.
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
#include "path/fixtures.hpp"

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

  TEST_CASE("a tilted microlens array's sections cross its rims where the tilted rims lie") {
    // A rim is the circle |X − c| = D/2 in the parent's plane z = 0; the world sees
    // W = R(X − o). Found here by a second method: walk each circle in φ, bisect where it
    // changes sides of the line, and read t = W·d there.
    // Decentred off the rims (the walk below cannot see a crossing at φ = 0 exactly).
    const double dx = 0.13, dy = 0.02;
    const Eigen::Matrix3d rotation = TransformedSurface::rotation_from_tilts(0.01, -0.006);
    const TransformedSurface tilted(std::make_unique<LensletArray>(bowls()), dx, dy, rotation);
    const LensletArray parent(bowls());
    const Eigen::Vector3d origin(dx, dy, parent.sag(dx, dy));
    const auto crossings_by_walk = [&](double theta, double lo, double hi) {
      const Eigen::Vector2d d(std::cos(theta), std::sin(theta));
      std::vector<double> out;
      for (int i = -8; i <= 8; ++i)
        for (int j = -8; j <= 8; ++j) {
          const double cx = i * kPitch, cy = j * kPitch;
          if (std::hypot(cx, cy) > 2.0 - 0.5 * kDiameter + 1e-12) continue;
          const auto world = [&](double phi) {
            const Eigen::Vector3d x(cx + 0.5 * kDiameter * std::cos(phi),
                                    cy + 0.5 * kDiameter * std::sin(phi), 0);
            const Eigen::Vector3d w = rotation * (x - origin);
            return Eigen::Vector2d(w.x(), w.y());
          };
          const auto side = [&](double phi) {
            const Eigen::Vector2d w = world(phi);
            return d.x() * w.y() - d.y() * w.x();
          };
          constexpr int kSteps = 720;
          for (int k = 0; k < kSteps; ++k) {
            double a = 2 * std::numbers::pi * k / kSteps,
                   b = 2 * std::numbers::pi * (k + 1) / kSteps;
            if ((side(a) > 0) == (side(b) > 0)) continue;
            for (int it = 0; it < 80; ++it) {
              const double m = 0.5 * (a + b);
              ((side(m) > 0) == (side(a) > 0) ? a : b) = m;
            }
            const double t = world(0.5 * (a + b)).dot(d);
            if (t >= lo && t <= hi) out.push_back(t);
          }
        }
      std::sort(out.begin(), out.end());
      return out;
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), start(-1.4, 0.8),
        length(0.05, 0.6);
    long crossings = 0;
    for (int line = 0; line < 200; ++line) {
      const double theta = angle(rng), lo = start(rng), hi = lo + length(rng);
      std::array<double, 32> found{};
      const int n = tilted.section_creases(theta, lo, hi, found);
      const std::vector<double> expected = crossings_by_walk(theta, lo, hi);
      CAPTURE(theta);
      REQUIRE(n == static_cast<int>(expected.size()));
      for (int k = 0; k < n; ++k) {
        CHECK(found[k] == doctest::Approx(expected[k]).epsilon(1e-11).scale(1));
        // And the world's section does fold there. On the parent the slope jumps by the
        // bowl's rim slope (D/2)/√(R² − (D/2)²) along the rim's normal ν, so by that times
        // ν·d along the line; the 0.01 rad tilt moves it by about 1 % of that.
        const RadialLine l(theta);
        const auto slope = [&](double rho) {
          double z, zx, zy;
          tilted.sag_gradient(rho * l.cos, rho * l.sin, z, zx, zy);
          return zx * l.cos + zy * l.sin;
        };
        const double rho = found[k];
        double z, zx, zy;
        tilted.sag_gradient(rho * l.cos, rho * l.sin, z, zx, zy);
        const Eigen::Vector3d q = tilted.to_parent({rho * l.cos, rho * l.sin, z});
        const Eigen::Vector2d nu = Eigen::Vector2d(q.x() - kPitch * std::round(q.x() / kPitch),
                                                   q.y() - kPitch * std::round(q.y() / kPitch))
                                       .normalized();
        const double rim_slope = 0.1 / std::sqrt(0.36 - 0.01);
        const double jump = std::abs(slope(rho + 1e-7) - slope(rho - 1e-7));
        CHECK(std::abs(jump - rim_slope * std::abs(nu.x() * l.cos + nu.y() * l.sin)) <= 0.003);
      }
      crossings += n;
    }
    CHECK(crossings > 200);
    // Tilted, the creases near a point and the bend are not known.
    std::array<NearbyCrease, 16> near{};
    CHECK(tilted.creases_near(0.3, 0.0, 0.2, near) == -1);
  }

  TEST_CASE("a decentred compound eye's sections cross a crease exactly where the slope jumps") {
    // The parent knows no line off its axis on a sphere: the rims' ellipses serve. The
    // witness is the section itself: sampled every 0.1 µm, its slope changes by at most
    // 0.1 µm × its bend (under 1/4 mm), 2.5e-5, between samples on one flank, and by the
    // rim's jump (about 0.11 along its normal) times the cosine of the crossing's angle
    // across a rim.
    const TransformedSurface moved(std::make_unique<LensletArray>(test::compound_eye_options(4.4)),
                                   0.3, 0.2, Eigen::Matrix3d::Identity());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
    long crossings = 0;
    for (int line = 0; line < 12; ++line) {
      const RadialLine l(angle(rng));
      const auto slope = [&](double rho) {
        double z, zx, zy;
        moved.sag_gradient(rho * l.cos, rho * l.sin, z, zx, zy);
        return zx * l.cos + zy * l.sin;
      };
      std::array<double, 32> found{};
      const int n = moved.section_creases(l, -3.5, 3.5, found);
      CAPTURE(l.theta);
      // Every jump of the sampled slope holds a crease reported; every crease reported
      // makes one, unless it is half of a pair that grazes a rim (their jumps cancel).
      constexpr double kStep = 1e-4;
      std::vector<double> jumps;  // the sample intervals' midpoints where the slope jumps
      double previous = slope(-3.5);
      for (double rho = -3.5 + kStep; rho <= 3.5; rho += kStep) {
        const double next = slope(rho);
        if (std::abs(next - previous) > 1e-3) jumps.push_back(rho - 0.5 * kStep);
        previous = next;
      }
      const auto near = [](const auto& list, int count, double rho, double reach) {
        for (int k = 0; k < count; ++k)
          if (std::abs(list[static_cast<std::size_t>(k)] - rho) <= reach) return true;
        return false;
      };
      for (const double rho : jumps) CHECK(near(found, n, rho, 0.5 * kStep + 1e-12));
      for (int k = 0; k < n; ++k) {
        const bool grazing = (k > 0 && found[k] - found[k - 1] < 2 * kStep) ||
                             (k + 1 < n && found[k + 1] - found[k] < 2 * kStep);
        if (!grazing)
          CHECK(near(jumps, static_cast<int>(jumps.size()), found[k], 0.5 * kStep + 1e-12));
      }
      crossings += n;
    }
    CHECK(crossings > 50);
  }

  TEST_CASE("a surface whose creases are not circles reports none it cannot place") {
    // An axicon's apex decentred: the default knows creases only on lines through its axis.
    std::array<double, 32> found{};
    const TransformedSurface apex(std::make_unique<OddAsphere>(0, 0, std::vector<double>{-0.2}),
                                  0.5, 0.0, Eigen::Matrix3d::Identity());
    CHECK(apex.section_creases(0.0, -1.0, 1.0, found) == 0);
    const TransformedSurface tilted_apex(
        std::make_unique<OddAsphere>(0, 0, std::vector<double>{-0.2}), 0.0, 0.0,
        TransformedSurface::rotation_from_tilts(0.01, 0));
    CHECK(tilted_apex.section_creases(0.0, -1.0, 1.0, found) == 0);
    const OddAsphere centred(0, 0, {-0.2});
    CHECK(centred.line_creases(0, 0, RadialLine(0.7), -1.0, 1.0, found) == 1);
    CHECK(found[0] == 0.0);
    CHECK(centred.line_creases(0.5, 0, RadialLine(0.7), -1.0, 1.0, found) == -1);
    std::vector<CreaseCircle> circles;
    CHECK_FALSE(centred.crease_circles(circles));
  }
}
