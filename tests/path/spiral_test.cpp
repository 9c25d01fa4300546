#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/zernike.hpp"
#include "path/dense_check.hpp"
#include "path/fixtures.hpp"

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

// One plan on each thread count, in order; with `replanned`, each plan's PVT seams planned
// again.
std::vector<std::vector<ContactPoint>> plan_on_threads(const Surface& s, const BaseSurface& base,
                                                       SpiralOptions o, std::initializer_list<int> threads,
                                                       std::vector<long>* replanned = nullptr) {
  std::vector<std::vector<ContactPoint>> runs;
  for (const int n : threads) {
    o.threads = n;
    ContactCollector out;
    const PathSummary summary = plan_spiral(s, base, o, out);
    if (replanned) replanned->push_back(summary.replanned_seams);
    runs.push_back(out.points);
  }
  return runs;
}

// Whether two plans place the same points, to the bit: angle, point and chord error.
bool same_points(const std::vector<ContactPoint>& a, const std::vector<ContactPoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].theta != b[k].theta || a[k].point != b[k].point || a[k].chord_error != b[k].chord_error)
      return false;
  return true;
}

// Points that lie exactly on a seam every `steps` caps (the chord rule's band bounds),
// strictly inside the path.
long points_on_cap_seams(const std::vector<ContactPoint>& p, double cap, long steps) {
  const double width = static_cast<double>(steps) * cap, end = p.back().theta;
  long seams = 0;
  for (const ContactPoint& q : p) {
    const long k = std::lround(q.theta / width);
    if (q.theta > 0 && q.theta < end && q.theta == static_cast<double>(k * steps) * cap) ++seams;
  }
  return seams;
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
    // The two points share θ, so the arc between them is exactly R (asin(r₁/R) − asin(r₂/R));
    // the 1/cos law is its first-order form, about the pair's midpoint.
    CHECK(spacing == doctest::Approx(radius * (std::asin(path[k60].r / radius) -
                                               std::asin(path[k60 + n].r / radius)))
                         .epsilon(1e-9)
                         .scale(0));
    CHECK(spacing ==
          doctest::Approx(pitch / std::cos(std::asin(mid / radius))).epsilon(1e-4).scale(0));
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

#include "freeturn/path/profile.hpp"
#include "freeturn/surface/lenslet_array.hpp"

namespace {

// The largest distance of the PVT motion from the profile, as a controller given positions
// only runs it: each block's velocity the central difference of its neighbours over their
// times (the X-Z chord at one feed), one-sided at the ends, and a cubic Hermite in time
// through each block; the distance of (X(u), Z(u)) from z = f(x), sampled densely.
double densest_cubic_error(const Surface& s, const std::vector<ContactPoint>& path) {
  const std::size_t n = path.size();
  std::vector<double> x(n), z(n), t(n, 0.0), vx(n), vz(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = path[k].r;
    z[k] = path[k].point.z();
    if (k > 0) t[k] = t[k - 1] + std::hypot(x[k] - x[k - 1], z[k] - z[k - 1]);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k > 0 ? k - 1 : 0, hi = k + 1 < n ? k + 1 : n - 1;
    vx[k] = (x[hi] - x[lo]) / (t[hi] - t[lo]);
    vz[k] = (z[hi] - z[lo]) / (t[hi] - t[lo]);
  }
  double worst = 0;
  for (std::size_t k = 1; k < n; ++k) {
    const double h = t[k] - t[k - 1];
    for (int j = 1; j < 400; ++j) {
      const double u = j / 400.0, u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      const double px = h00 * x[k - 1] + h10 * h * vx[k - 1] + h01 * x[k] + h11 * h * vx[k];
      const double pz = h00 * z[k - 1] + h10 * h * vz[k - 1] + h01 * z[k] + h11 * h * vz[k];
      double f, fx, fy;
      s.sag_gradient(px, 0, f, fx, fy);
      worst = std::max(worst, std::abs(pz - f) / std::sqrt(1 + fx * fx + fy * fy));
    }
  }
  return worst;
}

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("PVT (cubic) interpolation: ε holds on the controller's cubics, with fewer points than linear") {
    const SinusoidalRing ring(0.05, std::numbers::pi, 0.0);
    ProfileOptions o;
    o.outer_radius = 10;
    o.points.tolerance = 1e-4;
    o.points.max_radial_step = 1.0;
    ContactCollector linear;
    plan_profile(ring, o, linear);
    o.points.interpolation = Interpolation::kCubic;
    ContactCollector cubic;
    plan_profile(ring, o, cubic);
    CHECK(densest_cubic_error(ring, cubic.points) <= 1e-4);
    MESSAGE("0.1 µm: linear " << linear.points.size() << " points, cubic " << cubic.points.size());
    // Velocities from the neighbours are a second-order guess, and each segment must hold
    // whatever step follows it (path_stepper.hpp): fewer points than linear, not many fewer.
    CHECK(cubic.points.size() < linear.points.size());
  }

  TEST_CASE("scallop prediction: R − √(R² − f²/4) on a plane, the circles' cusp in a concave sphere") {
    const double pitch = 0.02, nose = 0.5;
    SpiralOptions o;
    o.outer_radius = 3;
    o.pitch = pitch;
    o.tool.nose_radius = nose;
    o.points = equal_angle(36);
    ContactCollector flat;
    plan_spiral(EvenAsphere(0, 0), BaseSurface::plane(3), o, flat);
    const double flat_scallop = nose - std::sqrt(nose * nose - pitch * pitch / 4);
    for (const auto& p : flat.points) CHECK(p.scallop == doctest::Approx(flat_scallop).epsilon(1e-12));
    // A concave sphere (R = 2 mm, seen from the tool) on its own base: f = p, κ = 1/2.
    const EvenAsphere bowl(0.5, 0);
    ContactCollector cut;
    BaseFitOptions fo;
    fo.spans = 32;
    plan_spiral(bowl, fit_base_least_squares(sample_aperture(bowl, 0, 1.5), fo),
                [&] { SpiralOptions s = o; s.outer_radius = 1.5; return s; }(), cut);
    // The cusp of two nose circles whose centres lie ρ − R from the sphere's centre, f/ρ
    // apart in angle: h = ρ − [(ρ − R) cos(φ/2) + √(R² − (ρ − R)² sin²(φ/2))].
    const double rho = 2, phi = pitch / rho;
    const double cusp = rho - ((rho - nose) * std::cos(phi / 2) +
                               std::sqrt(nose * nose - std::pow((rho - nose) * std::sin(phi / 2), 2)));
    for (const auto& p : cut.points) {
      CHECK(p.section_curvature == doctest::Approx(0.5).epsilon(1e-9));
      CHECK(p.scallop == doctest::Approx(cusp).epsilon(1e-4).scale(0));
      CHECK(p.scallop >= cusp * (1 - 1e-9));  // an upper bound, where f²/8 (1/R − κ) falls short
    }
  }

  TEST_CASE("centre-to-edge spirals and chunked streaming") {
    struct ChunkCounter final : ContactSink {
      void write(std::span<const ContactPoint> chunk) override {
        sizes.push_back(chunk.size());
        if (!chunk.empty()) last = chunk.back();
      }
      std::vector<std::size_t> sizes;
      ContactPoint last;
    } sink;
    SpiralOptions o;
    o.outer_radius = 4;
    o.inner_radius = 1;
    o.pitch = 0.01;
    o.centre_to_edge = true;
    o.points = equal_angle(100);
    const auto summary = plan_spiral(EvenAsphere(1 / 30.0, 0), BaseSurface::plane(4), o, sink);
    // 300 revolutions × 100 points + the first.
    CHECK(summary.points == 30001);
    REQUIRE(sink.sizes.size() == 8);
    for (std::size_t k = 0; k + 1 < sink.sizes.size(); ++k) CHECK(sink.sizes[k] == ContactChunker::kChunkSize);
    CHECK(sink.sizes.back() == 30001 - 7 * ContactChunker::kChunkSize);
    CHECK(sink.last.r == 4.0);
  }

  TEST_CASE("space spiral on a compound eye: every point on the design, in order, exact ends") {
    const LensletArray eye(test::compound_eye_options(5.5));
    SpiralOptions o;
    o.outer_radius = 5;
    o.pitch = 0.05;
    o.points.tolerance = 2e-4;
    ContactCollector out;
    plan_spiral(eye, fit_base_least_squares(sample_aperture(eye, 0, 5)), o, out);
    const auto& p = out.points;
    REQUIRE(p.size() > 100);
    CHECK(p.front().theta == 0);
    CHECK(p.back().r == 0);
    CHECK(p.back().theta == doctest::Approx(2 * std::numbers::pi * 5 / 0.05).epsilon(0.05));
    for (std::size_t k = 0; k < p.size(); ++k) {
      CHECK(p[k].point.z() == doctest::Approx(eye.sag(p[k].point.x(), p[k].point.y())).epsilon(1e-12).scale(1));
      if (k > 0) CHECK(p[k].theta > p[k - 1].theta);
    }
    CHECK(test::densest_chord_error(eye, p) <= 2e-4);
  }

  TEST_CASE("space spiral on a hexagonal compound eye: the first contact on the outer radius to 1e-9 mm") {
    LensletArrayOptions lo = test::compound_eye_options(3.5);
    lo.pattern = LensletArrayOptions::Pattern::kHexagonal;
    const LensletArray eye(lo);
    for (const bool centre_to_edge : {false, true}) {
      CAPTURE(centre_to_edge);
      SpiralOptions o;
      o.outer_radius = 3;
      o.pitch = 0.05;
      o.points.tolerance = 2e-4;
      o.centre_to_edge = centre_to_edge;
      ContactCollector out;
      plan_spiral(eye, fit_base_least_squares(sample_aperture(eye, 0, 3)), o, out);
      const ContactPoint& outer = centre_to_edge ? out.points.back() : out.points.front();
      const ContactPoint& inner = centre_to_edge ? out.points.front() : out.points.back();
      CHECK(std::abs(std::hypot(outer.point.x(), outer.point.y()) - 3.0) < 1e-9);
      CHECK(std::abs(outer.r - 3.0) < 1e-9);
      CHECK(inner.r < 1e-9);
      // Around the first turn the projection wanders with the design: past the outer radius
      // by a small part of the pitch at most.
      double beyond = 0;
      for (const ContactPoint& p : out.points) beyond = std::max(beyond, p.r - 3.0);
      CHECK(beyond < 0.1 * o.pitch);
    }
  }
}

TEST_SUITE("path") {
  TEST_CASE("bands: the same points, to the bit, on 1, 2 and 8 threads; ε holds across seams") {
    const NurbsHeightField surface = test::wavy_nurbs(12, 0.2);
    const BaseSurface base = fit_base_least_squares(sample_aperture(surface, 0, 4.0));
    SpiralOptions o;
    o.outer_radius = 4.0;
    o.pitch = 0.02;  // about 200 turns: bands of 4 turns and a radian (docs/path.md, "Bands")
    o.points.tolerance = 2e-4;
    const std::vector<std::vector<ContactPoint>> runs = plan_on_threads(surface, base, o, {1, 2, 8});
    REQUIRE(runs[0].size() > 1000);
    for (std::size_t r = 1; r < runs.size(); ++r) {
      CHECK(same_points(runs[r], runs[0]));
    }
    // The seams are points: every k·299 steps of the 5° cap, exactly (four turns and a
    // radian, 8π + 1 = 26.13, is 299.5 caps; 299 = 13·23 is prime to the 72 caps a turn).
    // The base's arc length is a little over the radius: a little over 200 turns.
    const double cap = 5 * std::numbers::pi / 180, width = 299 * cap, end = runs[0].back().theta;
    const long seams = points_on_cap_seams(runs[0], cap, 299);
    CHECK(seams == static_cast<long>(std::ceil(end / width - 1e-9)) - 1);
    CHECK(seams >= 47);
    CHECK(test::densest_chord_error(surface, runs[0]) <= 2e-4);
  }

  TEST_CASE("PVT in bands: the same points and seams planned again on 1, 2 and 8 threads; ε holds") {
    const NurbsHeightField surface = test::wavy_nurbs(12, 0.2);
    const BaseSurface base = fit_base_least_squares(sample_aperture(surface, 0, 4.0));
    SpiralOptions o;
    o.outer_radius = 4.0;
    o.pitch = 0.02;  // about 200 turns: bands of 4 turns and a radian
    o.points.tolerance = 2e-4;
    o.points.interpolation = Interpolation::kCubic;
    std::vector<long> replanned;
    const std::vector<std::vector<ContactPoint>> runs =
        plan_on_threads(surface, base, o, {1, 2, 8}, &replanned);
    REQUIRE(runs[0].size() > 1000);
    for (std::size_t r = 1; r < runs.size(); ++r) {
      CHECK(same_points(runs[r], runs[0]));
      CHECK(replanned[r] == replanned[0]);
    }
    // Seams every 299 steps of the 5° cap, as for linear motion: each is a point.
    const double cap = 5 * std::numbers::pi / 180, width = 299 * cap, end = runs[0].back().theta;
    const long seams = points_on_cap_seams(runs[0], cap, 299);
    CHECK(seams == static_cast<long>(std::ceil(end / width - 1e-9)) - 1);
    MESSAGE(seams << " seams, " << replanned[0] << " planned again, " << runs[0].size() << " points");
    double planned = 0;
    for (const ContactPoint& p : runs[0]) planned = std::max(planned, p.chord_error);
    CHECK(planned <= 2e-4);
  }

  TEST_CASE(
      "equal angles where the chords' errors are rounding: no more evaluations a point than where "
      "they are not") {
    // On a sphere the space spiral turns as a surface of revolution: an equal-angle chord
    // departs from the design only by the radial step's square, about z''·Δr²/8. At a pitch
    // of 0.05 mm and 1000 points a turn that is about 1e-11 mm, a smooth peak the parabola's
    // check settles; at 1e-4 mm it is about 1e-16 mm, rounding, where the check never agreed
    // and each segment was searched again by golden section: 21 evaluations a point, not 10.
    // The same 10 turns, once at each pitch: the evaluations per point stay alike.
    const EvenAsphere sphere(1 / 20.0, 0);
    BaseFitOptions fo;
    fo.spans = 32;
    const BaseSurface base = fit_base_least_squares(sample_aperture(sphere, 0, 1.0), fo);
    const auto per_point = [&](double inner, double pitch, double& worst) {
      const test::CountingSurface counting(sphere);
      SpiralOptions o;
      o.inner_radius = inner;
      o.outer_radius = 1.0;
      o.pitch = pitch;
      o.points = equal_angle(1000);
      ContactCollector out;
      plan_spiral(counting, base, o, out);
      worst = 0;
      for (const ContactPoint& p : out.points) worst = std::max(worst, p.chord_error);
      return static_cast<double>(counting.evaluations) / static_cast<double>(out.points.size());
    };
    double coarse_worst, fine_worst;
    const double coarse = per_point(0.5, 0.05, coarse_worst);
    const double fine = per_point(0.999, 1e-4, fine_worst);
    // z''·Δr²/8 with z'' = 1/20 mm⁻¹ and Δr = 5e-5 mm: 1.6e-11 mm; and rounding.
    CHECK(coarse_worst == doctest::Approx(1.6e-11).epsilon(0.2));
    CHECK(fine_worst <= 1e-14);
    CHECK(fine <= 1.1 * coarse);
  }

  TEST_CASE("chord control where the cap binds: every step is the cap, across the seams too") {
    // A gentle sphere at a coarse tolerance: the 3° cap binds everywhere, so a one-time
    // dialect (block_times: constant) can take the program; seams at multiples of the cap
    // keep it so (a seam at any other angle would cut one step a band short).
    const EvenAsphere sphere(1 / 200.0, 0);
    for (const Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
      SpiralOptions o;
      o.outer_radius = 4.0;
      o.pitch = 0.05;  // 80 turns: bands of a turn and about a radian
      o.points.tolerance = 1e-2;
      o.points.max_angle_step = 3 * std::numbers::pi / 180;
      o.points.interpolation = mode;
      o.threads = 2;
      ContactCollector out;
      plan_spiral(sphere, BaseSurface::plane(4.0), o, out);
      const std::vector<ContactPoint>& p = out.points;
      REQUIRE(p.size() > 80 * 120);
      double worst = 0;
      for (std::size_t k = 1; k + 1 < p.size(); ++k)
        worst = std::max(worst, std::abs((p[k].theta - p[k - 1].theta) / o.points.max_angle_step - 1));
      CHECK(worst <= 1e-9);
    }
  }

  TEST_CASE(
      "the path's last steps leave no sliver, and the last is a whole step: chords and equal "
      "angles") {
    // The program stops after its last block, over that block's time: at one spindle speed
    // a last block of f caps asks C for ω²/(f·cap), 1/f times what the start from rest
    // asks. The cap binds everywhere here (as above), and the path ends f caps past a whole
    // number of them; equal angles of 120 a turn step as the cap does. Under linear motion,
    // where the end lies within 2.5 caps the steps left are laid out as
    // [(L − c)/2, (L − c)/2, c] (L = 2 + f caps) or [L − c, c] (L = 1 + f, f ≥ 1/2), the last
    // a whole cap; under PVT the last two are evened, [L/2, L/2] for L = 1 + f
    // (path_stepper.hpp, last_step_laid_out, says why). Before, the last step was f caps:
    // 0.02 of the others (equal angles: a tilted sphere at one speed then ran at 2.14 rpm
    // where its blocks allow 14.57, tests/jobs/constant_speed_stop_test.sh).
    const EvenAsphere sphere(1 / 200.0, 0);
    const double cap = 3 * std::numbers::pi / 180;
    struct Case {
      Interpolation mode;
      double f;
      std::vector<double> last_steps;  // in caps
    };
    const Interpolation linear = Interpolation::kLinear, cubic = Interpolation::kCubic;
    for (const CutterPointRule rule : {CutterPointRule::kChordError, CutterPointRule::kEqualAngle})
      for (const Case& c : {Case{linear, 0.02, {0.51, 0.51, 1}}, Case{linear, 0.3, {0.65, 0.65, 1}},
                            Case{linear, 0.7, {0.7, 1}}, Case{cubic, 0.02, {0.51, 0.51}},
                            Case{cubic, 0.3, {0.65, 0.65}}, Case{cubic, 0.7, {0.85, 0.85}}}) {
        CAPTURE(static_cast<int>(rule));
        CAPTURE(c.f);
        CAPTURE(static_cast<int>(c.mode));
        SpiralOptions o;
        o.pitch = 0.05;
        o.outer_radius = o.pitch * (20 + c.f / 120);  // 20 turns of 120 caps, and f more
        o.points.rule = rule;
        o.points.points_per_revolution = 120;
        o.points.tolerance = 1e-2;
        o.points.max_angle_step = cap;
        o.points.interpolation = c.mode;
        o.threads = 2;
        ContactCollector out;
        plan_spiral(sphere, BaseSurface::plane(o.outer_radius), o, out);
        const std::vector<ContactPoint>& p = out.points;
        const std::size_t n = c.last_steps.size();
        REQUIRE(p.size() == 20 * 120 + 2);  // 2 400 caps and f: one step more, one point more
        CHECK(p.back().theta ==
              doctest::Approx(2 * std::numbers::pi * o.outer_radius / o.pitch).epsilon(1e-12));
        for (std::size_t k = 1; k < p.size(); ++k) {
          CAPTURE(k);
          const std::size_t from_end = p.size() - k;  // 1 for the last step
          const double expected = from_end <= n ? c.last_steps[n - from_end] : 1.0;
          CHECK((p[k].theta - p[k - 1].theta) / cap == doctest::Approx(expected).epsilon(1e-9));
        }
      }
  }

  TEST_CASE(
      "equal arc lengths: the path's last steps leave no sliver, none longer than the length") {
    // Centre to edge on a gentle sphere, 0.05 mm chords: at the edge (r about 1 mm) a step
    // is about 0.05/1 rad = 2.9°, and the outer radius moves the path's end by f such steps
    // (f·0.05 mm of spiral, 0.05·f·pitch/2π mm of radius), so that it ends at several parts
    // of a step past a whole number of them. The last steps are laid out as the chord rule's in
    // 0.98 of the arc's own step in τ (path_stepper.hpp: the step the length gives drifts along the
    // path): under linear motion the last is at least 0.97 of the steps before the end and
    // none of the last three under 0.48 of them; under PVT none of the last two under
    // 0.48. Every chord stays within the length. Before, the last step was what was left.
    const EvenAsphere sphere(1 / 200.0, 0);
    for (const Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic})
      for (const double f : {0.0, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9}) {
        CAPTURE(f);
        CAPTURE(static_cast<int>(mode));
        SpiralOptions o;
        o.pitch = 0.01;
        o.outer_radius = 1 + f * 0.05 * o.pitch / (2 * std::numbers::pi);
        o.centre_to_edge = true;
        o.points.rule = CutterPointRule::kEqualArcLength;
        o.points.arc_length = 0.05;
        o.points.interpolation = mode;
        o.threads = 2;
        ContactCollector out;
        plan_spiral(sphere, BaseSurface::plane(o.outer_radius), o, out);
        const std::vector<ContactPoint>& p = out.points;
        REQUIRE(p.size() > 10);
        const std::size_t m = p.size() - 1;                     // the last step ends at p[m]
        const double before = p[m - 3].theta - p[m - 4].theta;  // a whole step, before the end's
        CHECK(p[m].r == doctest::Approx(o.outer_radius).epsilon(1e-12));
        for (std::size_t k = m - 2; k <= m; ++k) {
          CAPTURE(k);
          CHECK((p[k].theta - p[k - 1].theta) >= 0.48 * before);
          CHECK((p[k].point - p[k - 1].point).norm() <= 0.05 * (1 + 1e-8));
        }
        if (mode == Interpolation::kLinear) CHECK((p[m].theta - p[m - 1].theta) >= 0.97 * before);
      }
  }

  TEST_CASE("equal angles in bands of whole turns: the same points on 1 and 2 threads, equal steps") {
    const NurbsHeightField surface = test::wavy_nurbs(12, 0.2);
    const BaseSurface base = fit_base_least_squares(sample_aperture(surface, 0, 4.0));
    SpiralOptions o;
    o.outer_radius = 4.0;
    o.pitch = 0.02;  // about 200 turns: bands of 4 whole turns
    o.points.rule = CutterPointRule::kEqualAngle;
    o.points.points_per_revolution = 90;
    const std::vector<std::vector<ContactPoint>> runs = plan_on_threads(surface, base, o, {1, 2});
    REQUIRE(same_points(runs[1], runs[0]));
    // Every step is 2π/90, across the seams too: the k-th point at k·2π/90 to rounding. The
    // path's last three steps excepted: the base's fit ends the path part of a step past
    // the lattice, and those are laid out (the test above), none under half a step.
    const double step = 2 * std::numbers::pi / 90;
    double worst = 0;
    const std::size_t n = runs[0].size();
    for (std::size_t k = 1; k + 3 < n; ++k)
      worst = std::max(worst, std::abs(runs[0][k].theta - runs[0][k - 1].theta - step));
    CHECK(worst <= 1e-12);
    for (std::size_t k = n - 3; k < n; ++k) {
      CHECK(runs[0][k].theta - runs[0][k - 1].theta >= 0.5 * step * (1 - 1e-12));
      CHECK(runs[0][k].theta - runs[0][k - 1].theta <= step * (1 + 1e-12));
    }
    CHECK(std::abs(runs[0][360].theta - 360 * step) <= 1e-12);
    CHECK(runs[0].size() > 200 * 90);
  }

  TEST_CASE("equal arc lengths in bands: the same points on 1, 2 and 8 threads, equal chords across seams") {
    const NurbsHeightField surface = test::wavy_nurbs(12, 0.2);
    const BaseSurface base = fit_base_least_squares(sample_aperture(surface, 0, 4.0));
    SpiralOptions o;
    o.outer_radius = 4.0;
    o.pitch = 0.02;  // about 200 turns: 50 bands or so, each seam a point of the rule's walk
    o.points.rule = CutterPointRule::kEqualArcLength;
    o.points.arc_length = 0.05;
    const std::vector<std::vector<ContactPoint>> runs = plan_on_threads(surface, base, o, {1, 2, 8});
    for (std::size_t r = 1; r < runs.size(); ++r) {
      CHECK(same_points(runs[r], runs[0]));
    }
    // The path is about π·4²/0.02 = 2513 mm long (its turns a pitch apart): some 50 000
    // chords of 0.05 mm. Where the angle cap (5°) binds, inside r = 0.05 mm / 5° = 0.573 mm,
    // a chord is shorter: 0.573 / 0.02 = 28.6 turns of 72 steps, 2 063. Elsewhere every
    // chord is 0.05 mm to the rule's 1e-8, the last three excepted (laid out: "equal arc
    // lengths: the path's last steps", above), and none is shorter (a seam that cut a step
    // short would show here).
    const std::vector<ContactPoint>& p = runs[0];
    REQUIRE(p.size() > 40000);
    double worst = 0;
    long capped = 0;
    for (std::size_t k = 1; k + 3 < p.size(); ++k) {
      const double chord = (p[k].point - p[k - 1].point).norm();
      if (p[k].theta - p[k - 1].theta >= 5 * std::numbers::pi / 180 * (1 - 1e-9)) {
        ++capped;
        continue;
      }
      worst = std::max(worst, std::abs(chord / 0.05 - 1));
    }
    CHECK(worst <= 1e-6);
    CHECK(capped >= 1950);
    CHECK(capped <= 2150);
  }

  TEST_CASE("equal arc lengths on a compound eye: bands land on their seams, chords off the length only at holds") {
    const LensletArray eye(test::compound_eye_options(3));
    SpiralOptions o;
    o.outer_radius = 2;
    o.pitch = 0.05;  // 40 turns: bands of a turn and a radian
    o.points.rule = CutterPointRule::kEqualArcLength;
    o.points.arc_length = 0.01;
    o.tool.nose_radius = 0.2;
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, 2));
    const std::vector<std::vector<ContactPoint>> runs = plan_on_threads(eye, base, o, {1, 2});
    CHECK(same_points(runs[1], runs[0]));
    // About π·2²/0.05 = 251 mm of path: 25 000 chords of 0.01 mm. Where the nose is held at
    // a lenslet's rim its contact stays on one flank, then jumps to the other: a chord there
    // is short of the length (the step ends before the jump) or longer (it counts from
    // where the contact lands). Every other chord has the length, the cap's (inside
    // r = 0.01 mm / 5°; a band's points follow its seams' walk to 1e-8 of a step, so a
    // capped step that ends on a seam can fall short of the cap by that) and the last three
    // excepted (laid out).
    const std::vector<ContactPoint>& p = runs[0];
    REQUIRE(p.size() > 20000);
    long off = 0, off_unheld = 0;
    for (std::size_t k = 1; k + 3 < p.size(); ++k) {
      const double chord = (p[k].point - p[k - 1].point).norm();
      if (p[k].theta - p[k - 1].theta >= 5 * std::numbers::pi / 180 * (1 - 1e-6)) continue;
      if (std::abs(chord / 0.01 - 1) <= 1e-6) continue;
      ++off;
      if (p[k].uncut_residual == 0 && p[k - 1].uncut_residual == 0) ++off_unheld;
    }
    CHECK(off_unheld == 0);
    CHECK(off < p.size() / 10);
  }
}
