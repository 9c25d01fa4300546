// A wavy edge is compensated at each contact's own angle, so the edge at another angle
// reaches δ(φ) − δ(ψ) past the round nose the planner measured: at a held nose's far
// flank that is the far touch's angle. The chord band keeps the round nose the waviness's
// span above the design (stand_off_for). The check here shares nothing with the planner:
// the compensated centres moved linearly, the edge at every angle at R + δ(φ) from them,
// against the design's sag.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/tool/compensation.hpp"
#include "path/fixtures.hpp"

using namespace freeturn;

namespace {

constexpr double kDegree = std::numbers::pi / 180;

// δ: 60 nm at −45°, 0 at 0°, −40 nm at 20°, 30 nm at 45°, all times `scale`.
ToolGeometry wavy_tool(double included_deg, double scale = 1) {
  ToolGeometry t;
  t.nose_radius = 0.2;
  t.included_angle = included_deg * kDegree;
  t.waviness = {{-45 * kDegree, 6e-5 * scale},
                {0, 0},
                {20 * kDegree, -4e-5 * scale},
                {45 * kDegree, 3e-5 * scale}};
  return t;
}

// The deepest the wavy edge goes below the design (mm, vertical; < 0: above it
// everywhere), the centres moved linearly in (C, radial, z) between blocks, `samples` a
// segment, the edge every 0.05° over ±half the included angle.
double wavy_edge_depth(const Surface& s, const std::vector<CutterLocation>& path,
                       const ToolGeometry& tool, int samples) {
  double deepest = -1e300;
  const double half = 0.5 * tool.included_angle;
  const int angles = static_cast<int>(std::ceil(2 * half / (0.05 * kDegree)));
  const auto radial = [](const CutterLocation& cl) {
    return cl.nose_centre.x() * std::cos(cl.contact.theta) +
           cl.nose_centre.y() * std::sin(cl.contact.theta);
  };
  for (std::size_t k = 1; k < path.size(); ++k) {
    const CutterLocation &a = path[k - 1], &b = path[k];
    for (int j = 0; j < samples; ++j) {
      const double t = static_cast<double>(j) / samples;
      const double c = a.contact.theta + t * (b.contact.theta - a.contact.theta);
      const double cr = radial(a) + t * (radial(b) - radial(a));
      const double cz = a.nose_centre.z() + t * (b.nose_centre.z() - a.nose_centre.z());
      for (int i = 0; i <= angles; ++i) {
        const double phi = -half + 2 * half * i / angles;
        const double r = tool.nose_radius + tool.waviness_at(phi);
        const double rho = cr - r * std::sin(phi), z = cz - r * std::cos(phi);
        deepest = std::max(deepest, s.sag(rho * std::cos(c), rho * std::sin(c)) - z);
      }
    }
  }
  return deepest;
}

}  // namespace

TEST_SUITE("tool") {
  TEST_CASE("a waviness's span over the edge, in closed form") {
    // Over ±45°: the table's own extremes, 60 nm at −45° and −40 nm at 20°.
    CHECK(wavy_tool(90).waviness_span() == doctest::Approx(1e-4).epsilon(1e-12));
    // Over ±30°: δ(−30°) = 60·30/45 = 40 nm at the end, −40 nm at 20° inside.
    CHECK(wavy_tool(60).waviness_span() == doctest::Approx(8e-5).epsilon(1e-12));
    // Over ±10°: the ends alone, δ(−10°) = 60/4.5 nm and δ(10°) = −20 nm.
    CHECK(wavy_tool(20).waviness_span() == doctest::Approx(6e-5 / 4.5 + 2e-5).epsilon(1e-12));
    CHECK(ToolGeometry{}.waviness_span() == 0);
    CutterPointOptions chord;
    chord.rule = CutterPointRule::kChordError;
    chord.tolerance = 2e-4;
    CompensationOptions c;
    c.tool = wavy_tool(90);
    // On a creased design the band is [w, ε]: stand-off (ε + w)/2. On a smooth one the
    // nose touches at one angle, and the band stays [0, ε].
    LensletArrayOptions lo;
    lo.lens_radius = 0.6;
    lo.lens_diameter = 0.2;
    lo.pitch = 0.25;
    lo.extent = 1.0;
    CHECK(stand_off_for(chord, tool_motion(c), LensletArray(lo)) ==
          doctest::Approx(1.5e-4).epsilon(1e-12));
    CHECK(stand_off_for(chord, tool_motion(c), EvenAsphere(1 / 200.0, -1)) ==
          doctest::Approx(1e-4).epsilon(1e-12));
  }

  TEST_CASE("a wavy edge's steepest slope over the edge, in closed form") {
    // The table's segments: 60 nm over 45°, 40 nm over 20°, 70 nm over 25°.
    const double rad = 1 / kDegree;
    CHECK(wavy_tool(90).waviness_slope() == doctest::Approx(7e-5 / 25 * rad).epsilon(1e-12));
    // Over ±10° only the two segments about 0° overlap the edge: 40 nm over 20°.
    CHECK(wavy_tool(20).waviness_slope() == doctest::Approx(4e-5 / 20 * rad).epsilon(1e-12));
    CHECK(ToolGeometry{}.waviness_slope() == 0);
  }

  TEST_CASE("on a smooth design the edge reaches L²/(2R(1 − κR)) past the round nose") {
    // A circle of radius R inside a section circle of radius ρ = 1/κ, touching it: the nose
    // at Δφ from the touch clears the section by R(1 − κR)Δφ²/2, the edge rises by at most
    // L|Δφ|, so it reaches past by at most L²/(2R(1 − κR)) (and never more than the span).
    CompensationOptions c;
    c.tool = wavy_tool(90);
    ToolMotion tool = tool_motion(c);
    const double L = tool.waviness_slope, R = 0.2;
    // A plane, and a convex dome: κ ≤ 0 leaves at least the room of a plane.
    CHECK(smooth_wavy_edge_reach(tool, EvenAsphere(0, 0), 0, 2) ==
          doctest::Approx(L * L / (2 * R)).epsilon(1e-12));
    CHECK(smooth_wavy_edge_reach(tool, EvenAsphere(-1 / 5.0, 0), 0, 2) ==
          doctest::Approx(L * L / (2 * R)).epsilon(1e-12));
    // A centred bowl of radius 0.201: every radial section is a great circle, κ = 1/0.201.
    const double room = R * (1 - R / 0.201);
    CHECK(smooth_wavy_edge_reach(tool, EvenAsphere(1 / 0.201, 0), 0, 0.1) ==
          doctest::Approx(L * L / (2 * room)).epsilon(1e-9));
    // Decentred by d = 0.005: the radial plane at θ passes d|sin θ| from the centre, and
    // cuts a circle of radius √(ρ² − d² sin² θ): κ is largest at θ = 90°.
    const TransformedSurface decentred(std::make_unique<EvenAsphere>(1 / 0.201, 0), 0.005, 0,
                                       Eigen::Matrix3d::Identity());
    const double tightest = R * (1 - R / std::sqrt(0.201 * 0.201 - 0.005 * 0.005));
    const double reach = smooth_wavy_edge_reach(tool, decentred, 0, 0.1);
    CHECK(reach >= L * L / (2 * tightest));
    CHECK(reach <= 1.05 * L * L / (2 * tightest));  // the samples' margin, a few percent
    // A nose that fits the bowl: the whole span.
    CHECK(smooth_wavy_edge_reach(tool, EvenAsphere(1 / 0.2, 0), 0, 0.1) ==
          doctest::Approx(tool.waviness_span).epsilon(1e-12));
    // The chord band follows it: stand-off (ε + reach)/2.
    CutterPointOptions chord;
    chord.rule = CutterPointRule::kChordError;
    chord.tolerance = 2e-4;
    tool.smooth_waviness_reach = reach;
    CHECK(stand_off_for(chord, tool, decentred) ==
          doctest::Approx(0.5 * (2e-4 + reach)).epsilon(1e-12));
  }

  TEST_CASE(
      "a compound eye cut with a wavy edge: the edge stays above the design at the held rims") {
    // The demo's lenslets (R_b 20 mm, lenslets −5 mm, 0.9 mm across at a 1 mm pitch) to
    // r = 1.6 mm, a 0.2 mm nose whose waviness spans 0.18 µm (0.9 ε), ε = 0.2 µm. The
    // nose is held at every rim, touching the far flank about 6° from its own touch.
    const LensletArray eye(test::compound_eye_options(1.6));
    CompensationOptions c;
    c.tool = wavy_tool(90, 1.8);
    SpiralOptions o;
    o.outer_radius = 1.6;
    o.pitch = 0.02;
    o.points.rule = CutterPointRule::kChordError;
    o.points.tolerance = 2e-4;
    o.points.max_angle_step = 4 * kDegree;
    const auto cut = [&](const ToolMotion& motion) {
      o.tool = motion;
      ContactCollector out;
      plan_spiral(eye, BaseSurface::plane(o.outer_radius), o, out);
      std::vector<CutterLocation> path;
      for (const ContactPoint& p : out.points) path.push_back(compensate(p, c));
      return wavy_edge_depth(eye, path, c.tool, 16);
    };
    const double depth = cut(tool_motion(c));
    // The band as it was, [0, ε] for the round nose whatever the edge.
    ToolMotion round = tool_motion(c);
    round.waviness_span = 0;
    const double before = cut(round);
    MESSAGE("the wavy edge's deepest: ", depth * 1e6,
            " nm; with the band as it was: ", before * 1e6, " nm");
    CHECK(depth <= 0);
    CHECK(before > 2e-6);  // 4.3 nm into the design
  }
}

// centre_height_reach over 0.01 ≤ ρ ≤ 0.45 mm of a lenslet array with a nose of radius R,
// for h = 10 nm and h = −20 nm: the second twice the first where the reach is in proportion
// to |h|.
struct ReachAtTwoHeights {
  double once = 0, twice = 0;
};
ReachAtTwoHeights reach_at_10_and_minus_20_nm(const LensletArray& lenslets, double R) {
  ToolMotion motion;
  motion.nose_radius = R;
  motion.centre_height = 0.00001;
  const double once = centre_height_reach(motion, lenslets, 0.01, 0.45);
  motion.centre_height = -0.00002;
  return {once, centre_height_reach(motion, lenslets, 0.01, 0.45)};
}

TEST_SUITE("tool") {
  TEST_CASE(
      "a centre height's reach at a held nose: none on a smooth design or on the spindle "
      "line, and in proportion to h while h ≪ ρ") {
    const LensletArray eye(test::compound_eye_options(1.6));
    ToolMotion motion;
    motion.nose_radius = 0.2;
    CHECK(centre_height_reach(motion, eye, 0.05, 1.6) == 0);
    motion.centre_height = 0.002;
    CHECK(centre_height_reach(motion, EvenAsphere(1 / 20.0, 0), 0.05, 1.6) == 0);
    // (s_t(ρ₂) + s_t(ρ₁))·β·R·Δψ with β = asin(h/ρ₁): h/ρ₁ ≤ 0.002/0.1 here, so doubling h
    // doubles it to within asin's curvature, (h/ρ)²/2 = 2·10⁻⁴ at most.
    const double once = centre_height_reach(motion, eye, 0.05, 1.6);
    motion.centre_height = -0.004;
    const double twice = centre_height_reach(motion, eye, 0.05, 1.6);
    CHECK(once > 0);
    CHECK(twice == doctest::Approx(2 * once).epsilon(2e-4));
  }

  TEST_CASE(
      "a centre height's reach by domes with one on the axis: in proportion to h, not a "
      "window's quarter turn") {
    // Domes 0.29 mm in radius and 0.22 mm across at a 0.2357 mm pitch, one on the axis:
    // valleys 16 µm wide between the central dome and the first ring, where a 0.2 mm nose is
    // held touching both domes, its nearer touch about 0.07 mm from the axis. The window
    // about such a rim took in the next domes' slopes until it reached the axis and took
    // β = π/2 whatever h: a reach of 0.26 mm for h = 10 nm. β = asin(h/ρ) at the held
    // nose's own touches doubles with h to within (h/ρ)²/2 < 10⁻⁷ here.
    LensletArrayOptions o;
    o.lens_radius = -0.2908;
    o.lens_diameter = 0.2198;
    o.pitch = 0.2357;
    o.pattern = LensletArrayOptions::Pattern::kSquare;
    o.extent = 0.45;
    const auto [once, twice] = reach_at_10_and_minus_20_nm(LensletArray(o), 0.2);
    MESSAGE("reach for h = 10 nm: ", once * 1e6, " nm");
    CHECK(once > 0);
    // 2·s_t·(h/ρ)·Δ with the domes' steepest s_t = tan(asin(0.1099/0.2908)) = 0.408, the
    // touches Δ ≤ 2R·0.378 = 0.151 mm apart, the nearer ρ ≳ 0.07 mm: about 1.8 h at most.
    CHECK(once < 2 * 0.00001);
    CHECK(twice == doctest::Approx(2 * once).epsilon(1e-4));
  }

  TEST_CASE(
      "a centre height's reach by bowls with one on the axis: in proportion to h, β at the "
      "ridge the nose rolls over") {
    // Bowls 0.148 mm in radius, 0.1371 mm across, in a hexagonal array 0.1965 mm apart: each
    // rim a ridge that a 0.1 mm nose rolls over, touching once. The window about the central
    // bowl's rim (ρ = 0.0686 mm) took in the next bowls' slopes and reached the axis, and
    // took β = π/2 whatever h: 0.2 mm for h = 10 nm. With β at the ridge, asin(h/ρ) ≈ h/ρ
    // doubles with h to within (h/ρ)²/2 < 10⁻⁷.
    LensletArrayOptions o;
    o.lens_radius = 0.148;
    o.lens_diameter = 0.1371;
    o.pitch = 0.1965;
    o.pattern = LensletArrayOptions::Pattern::kHexagonal;
    o.extent = 0.45;
    const auto [once, twice] = reach_at_10_and_minus_20_nm(LensletArray(o), 0.1);
    MESSAGE("reach for h = 10 nm: ", once * 1e6, " nm");
    CHECK(once > 0);
    // 2·(s_t + its change between samples)·(h/ρ)·R·Δψ: the steepest s_t alone,
    // tan(asin(0.06855/0.148)) = 0.52, with Δψ ≤ 2·0.482 rad, R = 0.1 and ρ = 0.0686 at the
    // central rim gives 1.47 h; the change adds to it. Under 4 h (0.2 mm before).
    CHECK(once < 4 * 0.00001);
    CHECK(twice == doctest::Approx(2 * once).epsilon(1e-4));
  }
}
