#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "freeturn/core/error.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/xy_polynomial.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "path/fixtures.hpp"

using namespace freeturn;

namespace {

ToolCheckOptions warn_all(double outer) {
  ToolCheckOptions o;
  o.policy.fill(CheckPolicy::kWarning);
  o.outer_radius = outer;
  return o;
}

// Plans a spiral (equal angles) through a compensator and returns its report.
ToolCheckReport spiral_report(const Surface& s, double outer, const CompensationOptions& c,
                              const ToolCheckOptions& checks, std::vector<CutterLocation>* out = nullptr,
                              int per_revolution = 180) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = 0.05;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = per_revolution;
  CutterCollector sink;
  ToolCompensator compensator(s, c, checks, sink);
  plan_spiral(s, BaseSurface::plane(outer), o, compensator);
  if (out) *out = sink.locations;
  return compensator.report();
}

}  // namespace

TEST_SUITE("tool") {
  TEST_CASE("gouge: a concave section radius below the nose radius fails where it is tightest") {
    // z = A sin(ωr): concave where sin(ωr) < 0, radius 1/(Aω²) = 0.507 mm at r = 0.75 + k.
    const SinusoidalRing ring(0.05, 2 * std::numbers::pi, 0);
    ProfileOptions o;
    o.outer_radius = 2.5;
    o.points.tolerance = 1e-5;
    CompensationOptions c;
    c.tool.nose_radius = 0.6;
    c.tool.included_angle = 2.5;
    CutterCollector out;
    ToolCheckOptions checks = warn_all(2.5);
    checks.policy[static_cast<int>(ToolCheck::kCentre)] = CheckPolicy::kOff;
    ToolCompensator compensator(ring, c, checks, out);
    plan_profile(ring, o, compensator);
    const CheckFinding& f = compensator.report()[ToolCheck::kLocalGouge];
    CHECK(f.count > 0);
    CHECK(1 / f.worst == doctest::Approx(1 / (0.05 * 4 * std::numbers::pi * std::numbers::pi)).epsilon(1e-3));
    CHECK(std::abs(std::remainder(f.r - 0.75, 1.0)) < 0.01);
    // As an error it stops at the first tight place, naming it.
    checks.policy[static_cast<int>(ToolCheck::kLocalGouge)] = CheckPolicy::kError;
    CutterCollector none;
    ToolCompensator strict(ring, c, checks, none);
    CHECK_THROWS_WITH_AS(plan_profile(ring, o, strict),
                         doctest::Contains("gouge check: concave radius 0.5"), InputError);
  }

  TEST_CASE("clearance: a steep tangential slope fails at θ = 90°; ψ = slope with B at 0, 0 with B following") {
    // A tilted flat z = 0.3x: tangential slope atan(0.3 |sin θ|), radial slope 0.3 cos θ.
    const Alvarez flat(0, 0.3);
    CompensationOptions c;
    c.tool.clearance_angle = 10 * std::numbers::pi / 180;
    std::vector<CutterLocation> cls;
    const ToolCheckReport report = spiral_report(flat, 3, c, warn_all(3), &cls);
    const CheckFinding& f = report[ToolCheck::kClearance];
    CHECK(f.count > 0);
    CHECK(f.worst == doctest::Approx(std::atan(0.3)).epsilon(1e-4));
    CHECK(std::abs(std::sin(f.theta)) == doctest::Approx(1.0).epsilon(1e-3));
    for (const CutterLocation& cl : cls) {
      CHECK(cl.b == 0);
      CHECK(cl.psi == doctest::Approx(std::atan(-0.3 * std::cos(cl.contact.theta))).epsilon(1e-12).scale(1));
    }
    c.b_mode = BMode::kFollow;
    spiral_report(flat, 3, c, warn_all(3), &cls);
    for (const CutterLocation& cl : cls) CHECK(cl.psi - cl.b == 0);
  }

  TEST_CASE(
      "clearance with the edge above centre: the flank faces machine y, where a "
      "paraboloid's radial slope shows as c·h everywhere") {
    // z = c r²/2: ∇z = c (x, y). Machine y at spindle angle C is (−sin C, cos C), and the
    // contact at radius ρ stands at C = θ − asin(h/ρ): ∇z · e_y = −cρ sin(asin(h/ρ)) = −ch.
    const EvenAsphere paraboloid(2.0, -1);
    CompensationOptions c;
    c.tool.clearance_angle = 10 * std::numbers::pi / 180;
    ToolCheckOptions checks = warn_all(1);
    checks.policy[static_cast<int>(ToolCheck::kCentre)] = CheckPolicy::kOff;
    CHECK(spiral_report(paraboloid, 1, c, checks)[ToolCheck::kClearance].count == 0);
    c.tool.centre_height = 0.1;  // atan(0.2) = 11.3°
    const ToolCheckReport report = spiral_report(paraboloid, 1, c, checks);
    const CheckFinding& f = report[ToolCheck::kClearance];
    CHECK(f.count > 0);
    CHECK(f.worst == doctest::Approx(std::atan(0.2)).epsilon(1e-9));
  }

  TEST_CASE("global gouge: the nose reaches into a lenslet beside the contact; the local check sees nothing") {
    LensletArrayOptions lo;
    lo.lens_radius = -1.0;  // convex bumps of D 0.8 on a plane
    lo.lens_diameter = 0.8;
    lo.pitch = 1.2;
    lo.pattern = LensletArrayOptions::Pattern::kSquare;
    lo.extent = 3.5;
    const LensletArray array(lo);
    CompensationOptions c;
    c.tool.nose_radius = 0.5;
    c.tool.included_angle = 2.0;
    ToolCheckOptions checks = warn_all(3);
    checks.policy[static_cast<int>(ToolCheck::kContactAngle)] = CheckPolicy::kOff;
    checks.policy[static_cast<int>(ToolCheck::kClearance)] = CheckPolicy::kOff;
    const ToolCheckReport report = spiral_report(array, 3, c, checks, nullptr, 360);
    CHECK(report[ToolCheck::kLocalGouge].count == 0);
    const CheckFinding& g = report[ToolCheck::kGlobalGouge];
    REQUIRE(g.count > 0);
    // The worst place is at a rim (a concave crease: the nose, tangent on one side,
    // overhangs the other) or on the flat within a nose radius of it.
    const double cx = 1.2 * std::round(g.x / 1.2), cy = 1.2 * std::round(g.y / 1.2);
    CHECK(std::hypot(g.x - cx, g.y - cy) > 0.4 - 0.01);
    CHECK(std::hypot(g.x - cx, g.y - cy) < 0.4 + 0.5);
    // A real gouge (over a micrometre deep), not rounding.
    CHECK(g.worst > 1e-3);
  }

  TEST_CASE("global gouge: the depth is a dense walk's along the edge, at rims and clear of them") {
    // A compound eye (lenslets R −5 mm, D 0.9 mm on a sphere of R 20 mm) and a 0.2 mm nose,
    // its edge ±45° about the tip, placed δ below its tangent position at a contact: clear
    // of the rims (where the depth is the contact's alone, from one search) and within 40
    // µm of a rim (where the nose overhangs the next flank, or rolls over it). The depth
    // the check reports is compared with the largest height of the section over the edge
    // arc, walked in 20 000 steps: never below it by more than the searches' Newton
    // shortfall (6 pm at worst here, with the nose 3 µm deep), and above it only by the
    // walk's miss at a crease's peak (its spacing, 14 nm, times the flanks' slopes).
    const LensletArray eye(test::compound_eye_options(3.0));
    const double R = 0.2, half = std::numbers::pi / 4;
    CompensationOptions c;
    c.tool.nose_radius = R;
    c.tool.included_angle = 2 * half;
    ToolCheckOptions checks;
    checks.policy.fill(CheckPolicy::kOff);
    checks.policy[static_cast<int>(ToolCheck::kGlobalGouge)] = CheckPolicy::kWarning;
    checks.gouge_tolerance = -1;  // every depth is a finding: its value is read back
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), unit(0, 1);
    int near_rim = 0, elsewhere = 0, deepest_off_contact = 0;
    for (int k = 0; k < 300; ++k) {
      const RadialLine line(angle(rng));
      double rho = 0.1 + 2.3 * unit(rng);
      if (k % 2 == 0) {
        // Beside a rim on this line.
        double creases[16];
        const int n = eye.section_creases(line, 0.1, 2.4, creases);
        if (n == 0) continue;
        rho = creases[static_cast<int>(unit(rng) * n) % n] + 0.04 * (2 * unit(rng) - 1);
      }
      double g, gx, gy;
      eye.sag_gradient(rho * line.cos, rho * line.sin, g, gx, gy);
      const double slope = gx * line.cos + gy * line.sin, length = std::sqrt(1 + slope * slope);
      const double delta = 1e-3 * (-0.5 + 3.5 * unit(rng));  // mm below the tangent place
      CutterLocation cl;
      cl.contact.theta = line.theta;
      cl.contact.r = rho;
      cl.contact.point = {rho * line.cos, rho * line.sin, g};
      const double c_r = rho - (R - delta) * slope / length, c_z = g + (R - delta) / length;
      cl.nose_centre = {c_r * line.cos, c_r * line.sin, c_z};
      ToolChecker checker(eye, c, checks);
      checker.check(cl);
      const CheckFinding& f = checker.report()[ToolCheck::kGlobalGouge];
      REQUIRE(f.count == 1);
      double walked = -1e300, at = rho;
      for (int j = 0; j <= 20000; ++j) {
        const double phi = -half + 2 * half * j / 20000;
        const double r = c_r - R * std::sin(phi);
        const double h = eye.sag(r * line.cos, r * line.sin) - (c_z - R * std::cos(phi));
        if (h > walked) walked = h, at = r;
      }
      CHECK(f.worst >= walked - 1e-8);
      CHECK(f.worst <= walked + 2e-6);
      if (std::abs(at - rho) > 1e-3) ++deepest_off_contact;
      (k % 2 == 0 ? near_rim : elsewhere)++;
    }
    // Both kinds were met, and the nose reached deepest away from its contact at some.
    CHECK(near_rim > 100);
    CHECK(elsewhere == 150);
    CHECK(deepest_off_contact >= 10);
  }

  TEST_CASE("centre: the nose centre may cross the axis; the global gouge check judges the other side") {
    CompensationOptions c;
    c.tool.nose_radius = 0.5;
    c.tool.included_angle = 2.5;
    ToolCheckOptions checks = warn_all(2);
    checks.policy[static_cast<int>(ToolCheck::kCentre)] = CheckPolicy::kError;
    checks.policy[static_cast<int>(ToolCheck::kLocalGouge)] = CheckPolicy::kOff;
    {
      // A sphere tilted by a linear term (a slope of 0.1 through the axis, as coma or an
      // off-axis segment has): smooth, so the offset of its section crosses the axis
      // without the nose reaching below the design on the other side.
      const XyPolynomial tilted(1 / 50.0, 0, 1.0, {0.1});
      std::vector<CutterLocation> cls;
      const ToolCheckReport r = spiral_report(tilted, 2, c, checks, &cls);
      CHECK(r[ToolCheck::kCentre].count == 0);
      CHECK(r[ToolCheck::kGlobalGouge].count == 0);
      double least = 1e300;
      for (const CutterLocation& cl : cls) least = std::min(least, cl.x);
      CHECK(least < -0.04);  // X passes through zero by about R·0.1
    }
    {
      // A cone at the vertex (slope s = Aω = 0.314): the plain offset of a contact at the
      // axis puts the nose over the other flank, R(1 − cos 2ψ)·√(1 + s²) deep along the
      // vertical for a straight cone, ψ = atan s (less for the sine, which bends down).
      const SinusoidalRing ring(0.05, 2 * std::numbers::pi, 0);
      const ToolCheckReport r = spiral_report(ring, 2, c, checks);
      const CheckFinding& g = r[ToolCheck::kGlobalGouge];
      REQUIRE(g.count > 0);
      const double s = 0.05 * 2 * std::numbers::pi, psi = std::atan(s);
      CHECK(g.r < 0.01);
      CHECK(g.worst <= 0.5 * (1 - std::cos(2 * psi)) * std::sqrt(1 + s * s));
      CHECK(g.worst > 0.6 * 0.5 * (1 - std::cos(2 * psi)) * std::sqrt(1 + s * s));
      CHECK(r[ToolCheck::kCentre].count == 0);
    }
  }

  TEST_CASE("B limits: a B that would leave its range is refused, never clamped") {
    const Alvarez flat(0, 0.3);  // ψ up to atan 0.3 = 0.29 rad
    CompensationOptions c;
    c.b_mode = BMode::kFollow;
    c.pivot_distance = 30;
    ToolCheckOptions checks = warn_all(3);
    checks.b_min = -0.2;
    checks.b_max = 0.2;
    checks.policy[static_cast<int>(ToolCheck::kBLimits)] = CheckPolicy::kWarning;  // ignored
    CHECK_THROWS_WITH_AS(spiral_report(flat, 3, c, checks), doctest::Contains("B limits check"),
                         InputError);
  }
}
