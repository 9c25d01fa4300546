// Troughs tighter than the nose (path/tight_troughs.hpp): the stretches listed as creases
// against the section's curvature in closed form, and the nose held across a trough
// against its placement by brute force, no point of it below the design.
#include "freeturn/path/tight_troughs.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "dense_check.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/tool/compensation.hpp"
#include "nose_brute_force.hpp"

namespace freeturn {
namespace {

// The ring z = A sin(ωr), A = 0.05 mm, period 0.8 mm: its troughs (r = 0.6 + 0.8k) bend to
// 1/(Aω²) = 0.3242 mm, tighter than a 0.5 mm nose.
constexpr double kA = 0.05, kPeriod = 0.8, kR = 0.5, kStandOff = 5e-5;
const double kOmega = 2 * std::numbers::pi / kPeriod;
const double kAngleCap = 4 * std::numbers::pi / 180;  // the spirals' angle cap (rad)

// The section's curvature in closed form, g''/(1 + g'²)^{3/2}, > 0 concave.
double curvature(double r) {
  const double slope = kA * kOmega * std::cos(kOmega * r);
  const double bend = -kA * kOmega * kOmega * std::sin(kOmega * r);
  return bend / std::pow(1 + slope * slope, 1.5);
}

// The chord rule's spiral over [0, outer] at `pitch` (mm/rev), angle cap 4°, planned on
// `view` as the run plans it, with a nose of radius `nose` (mm).
std::vector<ContactPoint> chord_spiral(const Surface& view, double outer, double pitch,
                                       double tolerance, double nose,
                                       PathSummary* summary = nullptr) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = pitch;
  o.points.tolerance = tolerance;
  o.points.max_angle_step = kAngleCap;
  o.tool.nose_radius = nose;
  ContactCollector out;
  const PathSummary s = plan_spiral(view, BaseSurface::plane(outer), o, out);
  if (summary) *summary = s;
  return out.points;
}

// The cutter locations of a nose of radius `nose` (mm) at the contacts.
std::vector<CutterLocation> compensated(const std::vector<ContactPoint>& points, double nose) {
  CompensationOptions c;
  c.tool.nose_radius = nose;
  std::vector<CutterLocation> cls;
  for (const ContactPoint& p : points) cls.push_back(compensate(p, c));
  return cls;
}

TEST_SUITE("path") {
  TEST_CASE("tight troughs: each tight stretch bracketed, its bottom between") {
    const SinusoidalRing ring(kA, kOmega, 0.0);
    const double placed = kR + kStandOff;
    const TightTroughs view(ring, placed, 3.0);
    REQUIRE(view.any());
    // The trough at 2.2 mm: the stretch where κ·R' > 1, its ends by bisection on the
    // closed form.
    const auto tight = [&](double r) { return curvature(r) * placed > 1; };
    const auto edge = [&](double in, double out) {
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (in + out);
        (tight(mid) ? in : out) = mid;
      }
      return in;
    };
    const double lo = edge(2.2, 2.0), hi = edge(2.2, 2.4);
    std::array<double, 32> creases;
    const int n = view.section_creases(RadialLine(0.0), 2.0, 2.4, creases);
    REQUIRE(n == 3);
    const double step = placed / 16;
    CHECK(creases[0] < lo);
    CHECK(creases[0] > lo - step);
    CHECK(creases[2] > hi);
    CHECK(creases[2] < hi + step);
    CHECK(creases[1] == doctest::Approx(2.2).epsilon(1e-4));  // the bottom, sin(ωr) = −1
    // The same creases from a query that holds only part of the stretch.
    std::array<double, 32> part;
    const int m = view.section_creases(RadialLine(0.0), creases[1] - 1e-9, 2.4, part);
    REQUIRE(m == 2);
    CHECK(part[0] == creases[1]);
    CHECK(part[1] == creases[2]);
    // Nothing on a ring whose troughs the nose follows (A = 0.005: 3.24 mm).
    const SinusoidalRing gentle(0.005, kOmega, 0.0);
    CHECK_FALSE(TightTroughs(gentle, placed, 3.0).any());
  }

  TEST_CASE("tight troughs: the nose rests on both sides, as high as brute force places it") {
    const SinusoidalRing ring(kA, kOmega, 0.0);
    const double placed = kR + kStandOff;
    const TightTroughs view(ring, placed, 3.0);
    // Over the trough at 2.2 the centre stands on its axis (the section is symmetric about
    // it) at the least height that clears the section: max over ρ of g(ρ) + √(R'² − (ρ −
    // 2.2)²), by brute force; the material left is that less R less g(2.2) = −A.
    const double centre_z = test::brute_overlap(ring, 2.2, 0.0, placed);
    const double uncut = centre_z - kR + kA;
    int held = 0;
    for (double rho = 2.03; rho <= 2.37; rho += 0.02) {
      double z, zx, zy;
      ring.sag_gradient(rho, 0, z, zx, zy);
      const NoseTouch t = nose_touch(view, RadialLine(0.0), kR, rho, z, zx, kStandOff);
      REQUIRE(t.held);
      ++held;
      CHECK(t.centre_x == doctest::Approx(2.2).epsilon(1e-9));
      CHECK(std::abs(t.centre_z - centre_z) < 1e-9);
      CHECK(std::abs(t.uncut - uncut) < 1e-9);
      // The placed nose touches the section and overhangs it nowhere (R' about the centre).
      CHECK(std::abs(test::brute_overlap(ring, t.centre_x, t.centre_z, placed)) < 1e-9);
      // Its touch lies on the contact's side of the bottom, on a stretch it can follow.
      CHECK((t.rho < 2.2) == (rho < 2.2));
      CHECK(curvature(t.rho) * placed < 1);
    }
    CHECK(held == 18);
    // Without the view the nose at the bottom's contact sinks into both sides.
    double z, zx, zy;
    ring.sag_gradient(2.2, 0, z, zx, zy);
    const NoseTouch free = nose_touch(ring, RadialLine(0.0), kR, 2.2, z, zx, kStandOff);
    CHECK_FALSE(free.held);
    CHECK(test::brute_overlap(ring, free.centre_x, free.centre_z, placed) > 1e-3);
  }

  // Bowls of radius 0.15 mm, 0.2 mm across on a square 0.25 mm lattice under a 0.2 mm nose:
  // every radial section of a bowl is a circle of radius at most 0.15 mm, tighter than the
  // nose, so the nose never reaches into a bowl; it rests on its two rims (ridges).
  LensletArrayOptions tight_bowls() {
    return {.lens_radius = 0.15,
            .lens_diameter = 0.2,
            .pitch = 0.25,
            .pattern = LensletArrayOptions::Pattern::kSquare,
            .extent = 1.0};
  }

  TEST_CASE("tight troughs: a bowl tighter than the nose, between two rims: it rests on both") {
    // On θ = 0 the bowl centred at 0.25 has its rims at 0.15 and 0.35 on the plane z = 0.
    // The nose across it rests on both rims: its centre at x = 0.25, √(R'² − 0.1²) above
    // them, and the real nose leaves the bowl's bottom, 0.15 − √(0.15² − 0.1²) deep, that
    // less the nose's sag over the rims. The library before placed contacts inside the bowl
    // 22.4 µm into its far wall, and its centre jumped back 33 µm at each rim: the job
    // stopped at the chord tolerance ("the design's section bends to a concave radius of
    // 0.15 mm").
    const LensletArray bowls(tight_bowls());
    const double nose = 0.2, placed = nose + kStandOff;
    const TightTroughs view(bowls, placed, 1.0);
    REQUIRE(view.any());
    const double centre_z = std::sqrt(placed * placed - 0.01);
    const double bottom = -(0.15 - std::sqrt(0.15 * 0.15 - 0.01));
    const double uncut = centre_z - nose - bottom;
    const double step = 2.5e-4;
    double last_x = -1, last_z = 0, widest = 0;
    int held = 0, on_rims = 0;
    for (double rho = 0.105; rho <= 0.395; rho += step) {
      CAPTURE(rho);
      double z, zx, zy;
      bowls.sag_gradient(rho, 0, z, zx, zy);
      const NoseTouch t = nose_touch(view, RadialLine(0.0), nose, rho, z, zx, kStandOff);
      // Touching the section and overhanging it nowhere (R' about the centre), by brute force.
      CHECK(std::abs(test::brute_overlap(bowls, t.centre_x, t.centre_z, placed)) < 1e-9);
      // The centre moves on along the section with the contact, never back, and never by
      // more than a few steps of it (the rims' windows: their roll over 0.45 R either side).
      if (last_x >= 0) {
        CHECK(t.centre_x >= last_x - 1e-12);
        widest = std::max(widest, std::hypot(t.centre_x - last_x, t.centre_z - last_z) / step);
      }
      last_x = t.centre_x;
      last_z = t.centre_z;
      on_rims += t.at_ridge;
      if (rho > 0.241 && rho < 0.259) {
        // Inside the bowl, past both rims' windows (0.45 R = 0.09 mm from each): held on
        // both rims.
        REQUIRE(t.held);
        ++held;
        CHECK(std::abs(t.centre_x - 0.25) < 1e-9);
        CHECK(std::abs(t.centre_z - centre_z) < 1e-9);
        CHECK(std::abs(t.uncut - uncut) < 1e-9);
        CHECK(t.at_ridge);
        CHECK(std::abs(std::abs(t.rho - 0.25) - 0.1) < 1e-12);  // its touch is a rim
      }
    }
    MESSAGE("held ", held, ", touching a rim ", on_rims, ", the centre's widest move ", widest,
            " times the contact's");
    CHECK(held == 73);
    // Across the land between the axis's bowl and this one both rims' windows overlap: the
    // centre moves 1 + 0.1/0.135 + 0.1/0.18 = 2.30 times as fast as the contact along the
    // section, and the drop moves it up and down besides.
    CHECK(widest < 3);
  }

  TEST_CASE("tight troughs: bowls finer than the nose, more creases about it than a list held") {
    // Bowls of radius 0.2563 mm, 0.0896 mm across at a 0.1296 mm pitch, under a 0.2711 mm
    // nose: the section at θ = 4.608373 crosses a sliver of a bowl between rims at
    // 0.367271 and 0.406126, and the hold's drops reach 3R = 0.81 mm either side of the
    // contact, where the view lists more creases than the 32 a list held. The lenslets'
    // creases were kept in the order found, not the lowest: the far rim was left out, the
    // drops there touched the bowl just inside it, and the hold beside the rim moved 9 µm.
    // The job (a mold a shop could order) stopped at the chord tolerance.
    const LensletArray bowls({.lens_radius = 0.2563,
                              .lens_diameter = 0.0896,
                              .pitch = 0.1296,
                              .pattern = LensletArrayOptions::Pattern::kSquare,
                              .extent = 0.52});
    const double nose = 0.2711, stand_off = 1e-4, placed = nose + stand_off;
    const TightTroughs view(bowls, placed, 0.52);
    REQUIRE(view.any());
    const RadialLine line(4.608373);
    std::array<double, 256> all;
    const int about = view.section_creases(line, 0.406 - 3 * placed, 0.406 + 3 * placed, all);
    REQUIRE(about > 32);
    // A list shorter than that holds the lowest of them, and says how many there are.
    std::array<double, 16> some;
    REQUIRE(view.section_creases(line, 0.406 - 3 * placed, 0.406 + 3 * placed, some) == about);
    for (int k = 0; k < 16; ++k)
      CHECK(some[static_cast<std::size_t>(k)] == all[static_cast<std::size_t>(k)]);
    const double step = 5e-5;
    double last_x = -1, last_z = 0, widest = 0;
    for (double rho = 0.36; rho <= 0.42; rho += step) {
      CAPTURE(rho);
      double z, zx, zy;
      bowls.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const double slope = zx * line.cos + zy * line.sin;
      const NoseTouch t = nose_touch(view, line, nose, rho, z, slope, stand_off);
      CHECK(std::abs(test::brute_overlap(bowls, t.centre_x, t.centre_z, placed, line.theta)) <
            1e-9);
      if (last_x >= 0) {
        CHECK(t.centre_x >= last_x - 1e-12);
        widest = std::max(widest, std::hypot(t.centre_x - last_x, t.centre_z - last_z) / step);
      }
      last_x = t.centre_x;
      last_z = t.centre_z;
    }
    MESSAGE("creases within 3R: ", about, ", the centre's widest move ", widest,
            " times the contact's");
    // The rims' windows and the drop move the centre a few times as fast as the contact
    // (1.27 on the far rim's window); the jump had been 9 µm in one step of 0.05 µm.
    CHECK(widest < 3);
  }

  TEST_CASE("tight troughs: a spiral over bowls tighter than the nose, sampled densely") {
    // The chord rule's spiral over the bowls to 0.4 mm, planned on the view as the run
    // plans it (the nose's radius plus the stand-off, half the tolerance), compensated, and
    // sampled along the interpolated motion by the tests' own nose sampler against the
    // bowls themselves: no jump, the nose nowhere below the design, the chord within ε.
    // It stopped at the chord tolerance before.
    const LensletArray bowls(tight_bowls());
    const double nose = 0.2, tolerance = 2e-4;
    const TightTroughs view(bowls, nose + 0.5 * tolerance, 0.4);
    REQUIRE(view.any());
    PathSummary summary;
    const std::vector<ContactPoint> points =
        chord_spiral(view, 0.4, 0.005, tolerance, nose, &summary);
    const std::vector<CutterLocation> cls = compensated(points, nose);
    long held = 0;
    double uncut = 0;
    for (const ContactPoint& p : points) {
      held += p.uncut_residual > 0;
      uncut = std::max(uncut, p.uncut_residual);
    }
    // 2 000 values across the nose: a rim's peak is sharp, and the default grid's 1.6 µm
    // spacing put the search beside it (391 nm read where the nose passed 192 nm above).
    const test::DenseNoseFigures f = test::dense_nose_figures(bowls, cls, nose, 12, 2000);
    MESSAGE("points ", cls.size(), ", held ", held, ", uncut at most ", uncut * 1e6,
            " nm, deepest ", f.gouge * 1e6, " nm, chord ", f.worst * 1e6, " nm");
    CHECK(summary.jumps == 0);
    CHECK(f.gouge <= 1e-6);
    CHECK(f.worst <= tolerance * 1.02);
    CHECK(held > 0);
    // The most left: a bowl's bottom under the nose resting on rims 0.1 mm either side of
    // its centre (the previous case's closed form), on no section more.
    const double placed = nose + 0.5 * tolerance;
    const double most =
        (std::sqrt(placed * placed - 0.01) - nose) + 0.15 - std::sqrt(0.15 * 0.15 - 0.01);
    CHECK(uncut <= most + 1e-9);
    CHECK(uncut > 0.9 * most);
  }

  TEST_CASE("tight troughs: a section that grazes a tight bowl: the centre continuous in θ") {
    // The section at θ ≈ 0.923 rad crosses the bowl centred at (0.25, 0.25) near its edge,
    // leaving it at r ≈ 0.4377 onto the plane. The view samples each section at whole steps
    // of ρ, so the stretch's end listed beside the rim came and went with θ; while it bounded
    // the rim's window, the centre of one contact jumped with θ and the chord rule stopped
    // there (the centre moved up to 10.9 µm in a step of 2e-5 rad). Now for a contact in the
    // rim's window the centre moves with θ as the rim does.
    const LensletArray bowls(tight_bowls());
    const double nose = 0.2, placed = nose + kStandOff;
    const TightTroughs view(bowls, placed, 1.0);
    for (const double rho : {0.43, 0.4374, 0.4380}) {
      CAPTURE(rho);
      double last_x = 0, last_z = 0, widest = 0;
      const double turn = 2e-5;
      for (double theta = 0.915; theta <= 0.93; theta += turn) {
        const RadialLine line(theta);
        double z, zx, zy;
        bowls.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
        const NoseTouch t =
            nose_touch(view, line, nose, rho, z, zx * line.cos + zy * line.sin, kStandOff);
        CHECK(std::abs(test::brute_overlap(bowls, t.centre_x, t.centre_z, placed, theta)) < 1e-9);
        if (theta > 0.915)
          widest = std::max(widest, std::hypot(t.centre_x - last_x, t.centre_z - last_z) / turn);
        last_x = t.centre_x;
        last_z = t.centre_z;
      }
      MESSAGE("the centre's widest move ", widest, " mm per radian of θ");
      CHECK(widest < 2.0);
    }
  }

  // The grid z = A sin(2πx/λx) sin(2πy/λy), A = 5 µm, λ = 0.3 × 0.4 mm: at its troughs the
  // sections bend to 1/(A (kx² cos²θ + ky² sin²θ)), 0.456 mm along x, barely tighter than a
  // 0.5 mm nose; their tight stretches are mostly narrower than the view's samples (R'/16).
  struct GridSection {
    double a = 0.005, kx = 2 * std::numbers::pi / 0.3, ky = 2 * std::numbers::pi / 0.4;
    double cos, sin;
    // g''/(1 + g'²)^{3/2} of g(ρ) = A sin(kx ρ cosθ) sin(ky ρ sinθ), in closed form.
    double curvature(double rho) const {
      const double p = kx * cos, q = ky * sin, u = p * rho, v = q * rho;
      const double slope = a * (p * std::cos(u) * std::sin(v) + q * std::sin(u) * std::cos(v));
      const double bend = a * (-(p * p + q * q) * std::sin(u) * std::sin(v) +
                               2 * p * q * std::cos(u) * std::cos(v));
      return bend / std::pow(1 + slope * slope, 1.5);
    }
  };

  TEST_CASE("tight troughs: stretches narrower than a sample, found between the samples") {
    const SinusoidalGrid grid(0.005, 0.3, 0.4);
    const double placed = 0.5 + kStandOff, step = placed / 16;
    const TightTroughs view(grid, placed, 1.5);
    // The library before saw no stretch on most sections (every sample under 1/R') and left
    // the view unused: the job failed the local gouge check at once (concave radius 0.4956
    // mm under the 0.5 mm nose).
    REQUIRE(view.any());
    int stretches = 0, between = 0;
    std::array<double, 256> creases;
    for (int j = 0; j < 96; ++j) {
      const double theta = 2 * std::numbers::pi * (j + 0.37) / 96;
      CAPTURE(theta);
      const GridSection section{.cos = std::cos(theta), .sin = std::sin(theta)};
      const int n = view.section_creases(RadialLine(theta), 0.0, 1.5, creases);
      REQUIRE(n >= 0);
      REQUIRE(n <= static_cast<int>(creases.size()));
      const auto listed = [&](double from, double to) {
        return std::any_of(creases.begin(), creases.begin() + n,
                           [&](double c) { return c >= from && c <= to; });
      };
      // The tight stretches on a 0.1 µm grid, each bracketed by a crease within two samples
      // before it and after it, with one inside.
      const double fine = 1e-4;
      for (double rho = 2 * step; rho < 1.5 - 2 * step; rho += fine) {
        if (!(section.curvature(rho) * placed > 1) || section.curvature(rho - fine) * placed > 1)
          continue;
        double end = rho;
        while (section.curvature(end + fine) * placed > 1) end += fine;
        CAPTURE(rho);
        CAPTURE(end);
        ++stretches;
        CHECK(listed(rho - 2 * step, rho - fine));
        CHECK(listed(rho - fine, end + fine));
        CHECK(listed(end + fine, end + 2 * step));
        if (std::floor(rho / step) == std::floor(end / step)) ++between;
        rho = end;
      }
    }
    MESSAGE(stretches, " tight stretches, ", between, " of them between two samples");
    CHECK(between > 0);
  }

  TEST_CASE("tight troughs: a nose across a stretch narrower than a sample rests on both sides") {
    // Along θ = 0.1484 the section crosses a trough whose tight stretch (0.8191 to 0.8380
    // mm, 1.02/R' at most) lies between two samples: every contact about it places a nose that
    // touches the section and overhangs it nowhere (R' about its centre), by brute force; without
    // the view the nose at the trough's tightest point sinks into it.
    const SinusoidalGrid grid(0.005, 0.3, 0.4);
    const double placed = 0.5 + kStandOff, step = placed / 16, theta = 0.1484;
    const TightTroughs view(grid, placed, 1.5);
    const GridSection section{.cos = std::cos(theta), .sin = std::sin(theta)};
    // The tightest point of the section between 0.79 and 0.87 mm, on a 0.1 µm grid.
    double tightest = 0.79;
    for (double rho = 0.79; rho < 0.87; rho += 1e-4)
      if (section.curvature(rho) > section.curvature(tightest)) tightest = rho;
    REQUIRE(section.curvature(tightest) * placed > 1);
    const double below = step * std::floor(tightest / step);
    REQUIRE(section.curvature(below) * placed < 1);
    REQUIRE(section.curvature(below + step) * placed < 1);
    const RadialLine line(theta);
    int held = 0;
    for (double rho = tightest - 2 * step; rho <= tightest + 2 * step; rho += step / 8) {
      CAPTURE(rho);
      double z, zx, zy;
      grid.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const double slope = zx * line.cos + zy * line.sin;
      const NoseTouch t = nose_touch(view, line, 0.5, rho, z, slope, kStandOff);
      CHECK(std::abs(test::brute_overlap(grid, t.centre_x, t.centre_z, placed, theta)) < 1e-9);
      held += t.held;
    }
    CHECK(held > 0);
    double z, zx, zy;
    grid.sag_gradient(tightest * line.cos, tightest * line.sin, z, zx, zy);
    const NoseTouch free =
        nose_touch(grid, line, 0.5, tightest, z, zx * line.cos + zy * line.sin, kStandOff);
    CHECK(test::brute_overlap(grid, free.centre_x, free.centre_z, placed, theta) > 1e-9);
  }

  TEST_CASE("tight troughs: a contact on a stretch whose overhang is under the tolerance is held") {
    // A grid (A 3.98 µm, λ 0.5477 × 0.3970 mm) under a 1.5 mm nose: along θ = 146.64° the
    // section bends to 1.49987 mm about ρ = 0.1718, tighter than the nose by 0.02 % over
    // 3 µm, and the nose at a contact there overhangs the far side by far less than the
    // envelope's tolerance (1e-10 mm). It was placed at the contact, and the local gouge
    // check refused the job. Every contact on that stretch now holds the nose at the
    // stretch's crease: touching the section and overhanging it nowhere (brute force),
    // its touches where the section bends less than the nose.
    const SinusoidalGrid grid(0.00398, 0.5477, 0.3970);
    const double nose = 1.5, placed = nose + 1e-4;
    const TightTroughs view(grid, placed, 0.979);
    REQUIRE(view.any());
    const double theta = std::atan2(0.093951, -0.142703);
    const GridSection section{.a = 0.00398,
                              .kx = 2 * std::numbers::pi / 0.5477,
                              .ky = 2 * std::numbers::pi / 0.3970,
                              .cos = std::cos(theta),
                              .sin = std::sin(theta)};
    const RadialLine line(theta);
    int tight = 0;
    for (double rho = 0.165; rho <= 0.178; rho += 2e-5) {
      if (!(section.curvature(rho) * placed > 1)) continue;
      CAPTURE(rho);
      ++tight;
      double z, zx, zy;
      grid.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const NoseTouch t = nose_touch(view, line, nose, rho, z, zx * line.cos + zy * line.sin, 1e-4);
      CHECK(t.held);
      CHECK(std::abs(test::brute_overlap(grid, t.centre_x, t.centre_z, placed, theta)) < 1e-9);
      CHECK(section.curvature(t.rho) * placed <= 1);
    }
    MESSAGE(tight, " contacts on the tight stretch");
    CHECK(tight > 10);
  }

  TEST_CASE("tight troughs: a nose held on the axis while C turns: every block kept") {
    // A sinusoidal grid (A 15.33 µm, λ 0.7042 × 0.5232 mm) under a 1.5 mm nose: about the
    // axis, where the grid is a saddle tighter than the nose along the first quadrant, the
    // nose is held with its centre on the axis (X = 0) for several blocks while C turns.
    // Such a block moves Z by under the program's resolution and was dropped as a block of
    // no move, which left a segment of twice the angle cap whose middle went 7 nm into the
    // design (read from the NC). Every step now stays within the cap, and the motion,
    // sampled densely by the tests' own nose sampler, stays above the design.
    const SinusoidalGrid grid(0.01533, 0.7042, 0.5232);
    const double nose = 1.5, tolerance = 2e-4, outer = 0.2;
    const TightTroughs view(grid, nose + 0.5 * tolerance, outer);
    REQUIRE(view.any());
    const std::vector<CutterLocation> cls =
        compensated(chord_spiral(view, outer, 0.02, tolerance, nose), nose);
    int on_axis = 0;
    double widest = 0;
    for (std::size_t k = 0; k < cls.size(); ++k) {
      on_axis += std::hypot(cls[k].nose_centre.x(), cls[k].nose_centre.y()) < 1e-9;
      if (k > 0) widest = std::max(widest, cls[k].c - cls[k - 1].c);
    }
    const test::DenseNoseFigures f = test::dense_nose_figures(grid, cls, nose, 24, 2000);
    MESSAGE("points ", cls.size(), ", on the axis ", on_axis, ", deepest ", f.gouge * 1e6,
            " nm, widest step ", widest * 180 / std::numbers::pi, "°");
    CHECK(on_axis > 2);
    CHECK(widest <= kAngleCap * (1 + 1e-9));
    CHECK(f.gouge <= 1e-6);
  }

  TEST_CASE("tight troughs: a period the samples alias into a slow wave leaves the view unused") {
    // z = 0.5 sin(2πr/0.017) under a 0.5 mm nose: the samples, 31.25 µm apart, see a wave 8
    // samples long, whose one-sample stretches look like bumps; the curvature between them
    // peaks at A ω² = 6.8e4 /mm, far above them. A 10 µm period likewise.
    for (const double period : {0.017, 0.01}) {
      CAPTURE(period);
      const SinusoidalRing ring(0.5, 2 * std::numbers::pi / period, 0.0);
      CHECK_FALSE(TightTroughs(ring, 0.5 + 5e-4, 1.5).any());
    }
  }

  TEST_CASE("tight troughs: wide tight stretches and a nose wider than the period, touching") {
    // Every contact's nose, held or not, touches the section and overhangs it nowhere: the
    // largest height of the section over its lower arc (R') is 0, by brute force. Before
    // the whole section's overhang placed it (section_envelope.cpp, hold_by_overhang),
    // contacts inside a wide tight stretch were held on its own pieces, 92 µm into the
    // trough.
    struct Case {
      double amplitude, period, nose;
    };
    for (const Case c : {Case{0.1, 1.0, 0.8}, Case{0.01, 0.3, 0.5}}) {
      CAPTURE(c.period);
      const double w = 2 * std::numbers::pi / c.period;
      const SinusoidalRing ring(c.amplitude, w, 0.0);
      const double placed = c.nose + kStandOff;
      const TightTroughs view(ring, placed, 3.0);
      REQUIRE(view.any());
      int held = 0, count = 0;
      for (double rho = 1.0; rho <= 2.0; rho += 0.0125) {
        CAPTURE(rho);
        double z, zx, zy;
        ring.sag_gradient(rho, 0, z, zx, zy);
        const NoseTouch t = nose_touch(view, RadialLine(0.0), c.nose, rho, z, zx, kStandOff);
        CHECK(std::abs(test::brute_overlap(ring, t.centre_x, t.centre_z, placed)) < 1e-9);
        ++count;
        if (t.held) ++held;
      }
      // Held somewhere in every period (the troughs are tighter than the nose).
      CHECK(held > count / 4);
    }
    // The wide stretch's trough at 0.75 + 1: the nose centred over its bottom by symmetry, as
    // high as the section demands, the same for every contact under it.
    const SinusoidalRing ring(0.1, 2 * std::numbers::pi, 0.0);
    const double placed = 0.8 + kStandOff;
    const TightTroughs view(ring, placed, 3.0);
    const double centre_z = test::brute_overlap(ring, 1.75, 0.0, placed);
    for (double rho = 1.6; rho <= 1.9; rho += 0.01) {
      double z, zx, zy;
      ring.sag_gradient(rho, 0, z, zx, zy);
      const NoseTouch t = nose_touch(view, RadialLine(0.0), 0.8, rho, z, zx, kStandOff);
      REQUIRE(t.held);
      CHECK(t.centre_x == doctest::Approx(1.75).epsilon(1e-9));
      CHECK(std::abs(t.centre_z - centre_z) < 1e-9);
      CHECK(std::abs(t.uncut - (centre_z - 0.8 + 0.1)) < 1e-9);
    }
  }
}

}  // namespace
}  // namespace freeturn
