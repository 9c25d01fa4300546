#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/zernike.hpp"
#include "path/dense_check.hpp"

using namespace freeturn;

namespace {

std::vector<ContactPoint> spiral(const Surface& s, const BaseSurface& base, double outer,
                                 double pitch, CutterPointOptions points) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = pitch;
  o.points = points;
  ContactCollector out;
  plan_spiral(s, base, o, out);
  return out.points;
}

CutterPointOptions equal_angle(int n) {
  CutterPointOptions o;
  o.rule = CutterPointRule::kEqualAngle;
  o.points_per_revolution = n;
  return o;
}

// Angle between two points of a sphere about c, seen from c.
double arc_on_sphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     double radius) {
  const Eigen::Vector3d u = a - c, v = b - c;
  return radius * std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("space spiral on a sphere: passes exactly a pitch apart along the surface, α = 0") {
    const double radius = 20.0, pitch = 0.2;
    const EvenAsphere sphere(1 / radius, 0);
    BaseFitOptions fo;
    fo.spans = 32;  // the cubic fit of the circle's arc has slope errors ~ spans⁻³
    const auto samples = sample_aperture(sphere, 0, 10.0);
    const BaseSurface base = fit_base_least_squares(samples, fo);
    CHECK(measure_quasi_revolution(samples, base).max_angle < 1e-6);
    const int n = 90;
    const auto path = spiral(sphere, base, 10.0, pitch, equal_angle(n));
    const Eigen::Vector3d centre(0, 0, radius);
    double worst = 0;
    for (std::size_t k = 0; k + n < path.size(); ++k) {
      // Only the pairs a whole turn apart (the last step is shorter).
      if (std::abs(path[k + n].theta - path[k].theta - 2 * std::numbers::pi) > 1e-9) continue;
      const double spacing = arc_on_sphere(path[k].point, path[k + n].point, centre, radius);
      worst = std::max(worst, std::abs(spacing / pitch - 1));
      CHECK(path[k].pass_spacing == doctest::Approx(pitch).epsilon(1e-6));
    }
    CHECK(worst < 1e-6);
  }

  TEST_CASE("traditional spiral on a sphere: pass spacing grows as 1/cos(slope), 2p at 60°") {
    const double radius = 20.0, pitch = 0.05;
    const EvenAsphere sphere(1 / radius, 0);
    const int n = 72;
    const auto path = spiral(sphere, BaseSurface::plane(18.0), 18.0, pitch, equal_angle(n));
    const Eigen::Vector3d centre(0, 0, radius);
    // The pass whose midpoint is nearest r = R sin 60°.
    const double r60 = radius * std::sin(std::numbers::pi / 3);
    std::size_t k60 = 0;
    for (std::size_t k = 0; k + n < path.size(); ++k)
      if (std::abs(0.5 * (path[k].r + path[k + n].r) - r60) <
          std::abs(0.5 * (path[k60].r + path[k60 + n].r) - r60))
        k60 = k;
    const double spacing = arc_on_sphere(path[k60].point, path[k60 + n].point, centre, radius);
    const double mid = 0.5 * (path[k60].r + path[k60 + n].r);
    CHECK(path[k60].r - path[k60 + n].r == doctest::Approx(pitch).epsilon(1e-12));
    CHECK(spacing == doctest::Approx(pitch / std::cos(std::asin(mid / radius))).epsilon(1e-5));
    CHECK(spacing == doctest::Approx(2 * pitch).epsilon(2e-3));
    CHECK(path[k60].pass_spacing == doctest::Approx(pitch / std::cos(std::asin(path[k60].r / radius)))
                                        .epsilon(1e-12));
  }

  TEST_CASE("a plane base reproduces the traditional spiral exactly; ends are exact") {
    const Zernike z(1 / 60.0, 0, {}, 6.0, {0, 0, 0, 0, 0, 2e-3, 1e-3, 0, 5e-4});
    // A flat base that is not flagged as a plane takes the projection path.
    const BaseSurface flat(3, {0, 0, 0, 0, 3, 6, 6, 6, 6}, {0, 0, 0, 0, 0});
    CutterPointOptions o;
    o.tolerance = 2e-4;
    const auto a = spiral(z, BaseSurface::plane(6.0), 6.0, 0.3, o);
    const auto b = spiral(z, flat, 6.0, 0.3, o);
    REQUIRE(a.size() == b.size());
    double worst = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      worst = std::max(worst, (a[k].point - b[k].point).norm());
      // r = r_e − bθ, the contact straight above (x, y).
      CHECK(a[k].r == doctest::Approx(6.0 - 0.3 * a[k].theta / (2 * std::numbers::pi)).epsilon(1e-13).scale(1));
      CHECK(a[k].point.z() == doctest::Approx(z.sag(a[k].point.x(), a[k].point.y())).epsilon(1e-15).scale(1));
    }
    CHECK(worst < 1e-12);
    CHECK(a.front().r == 6.0);
    CHECK(a.front().theta == 0.0);
    CHECK(a.back().r == 0.0);
    CHECK(a.back().theta == doctest::Approx(2 * std::numbers::pi * 6.0 / 0.3).epsilon(1e-14));
    for (std::size_t k = 1; k < a.size(); ++k) {
      CHECK(a[k].theta > a[k - 1].theta);
      CHECK(a[k].point.allFinite());
    }
  }

  TEST_CASE("freeform spiral: ε holds on every segment with ≥ 30% fewer points than equal angles") {
    const SinusoidalGrid grid(0.01, 4.0, 5.0);
    const double outer = 5.0, pitch = 0.1, eps = 5e-4;
    CutterPointOptions o;
    o.tolerance = eps;
    o.max_angle_step = 0.5;
    const auto path = spiral(grid, BaseSurface::plane(outer), outer, pitch, o);
    const double worst = test::densest_chord_error(grid, path);
    CHECK(worst <= eps);
    // The fewest equal angles per revolution with the same worst error (bisection).
    int lo = 8, hi = 4096;
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      (test::densest_chord_error(grid, spiral(grid, BaseSurface::plane(outer), outer, pitch,
                                              equal_angle(mid)), 40) <= eps
           ? hi
           : lo) = mid;
    }
    const auto equal = spiral(grid, BaseSurface::plane(outer), outer, pitch, equal_angle(hi));
    MESSAGE("chord-controlled " << path.size() << " points, equal angles " << equal.size() << " ("
                                << hi << " per revolution)");
    CHECK(static_cast<double>(path.size()) <= 0.7 * static_cast<double>(equal.size()));
  }

  TEST_CASE("a projection that misses the design surface names θ and r") {
    // The asphere is undefined beyond r = 9.13 mm; the base reaches 12.
    const EvenAsphere steep(1 / 10.0, 0.2);
    CHECK_THROWS_WITH_AS(spiral(steep, BaseSurface::plane(12.0), 12.0, 0.5, equal_angle(36)),
                         doctest::Contains("θ = 0.000000 rad (0.000000°), r = 12.000000 mm"),
                         InputError);
  }
}
