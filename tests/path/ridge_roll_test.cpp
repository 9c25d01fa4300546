// The nose rolling over a ridge, a convex crease (path/section_envelope.hpp, docs/tool.md,
// "Ridges"): the placement against its closed form on a roof of two planes, every rolled
// nose touching the design by brute force, and spirals over a roof and over a concave
// microlens array checked by the tests' dense nose sampler.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include "dense_check.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/odd_asphere.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/tool/compensation.hpp"
#include "nose_brute_force.hpp"
#include "nurbs/fixtures.hpp"

namespace freeturn {
namespace {

// Two planes meeting at the line x = kRidge, z = 0: slope kIn before it, kOut beyond. A
// ridge where kIn > kOut (the slope falls across it), a valley otherwise.
class Roof final : public Surface {
 public:
  Roof(double in, double out) : in_(in), out_(out) {}
  static constexpr double kRidge = 2.0;
  const char* type() const override { return "roof"; }
  bool has_creases() const override { return true; }
  int section_creases(const RadialLine& line, double lo, double hi,
                      std::span<double> out) const override {
    if (std::abs(line.cos) < 1e-12 || out.empty()) return 0;
    const double rho = kRidge / line.cos;
    if (!(rho >= lo && rho <= hi)) return 0;
    out[0] = rho;
    return 1;
  }
  void sag_gradient(double x, double, double& z, double& zx, double& zy) const override {
    zx = x < kRidge ? in_ : out_;
    zy = 0;
    z = zx * (x - kRidge);
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    HeightDerivatives h;
    sag_gradient(x, y, h.z, h.zx, h.zy);
    return h;
  }

 private:
  double in_, out_;
};

using test::brute_overlap;
using test::touch_at;

TEST_SUITE("path") {
  TEST_CASE("a ridge of two planes: the nose rolls over it as the closed form places it") {
    const double s_in = 0.3, s_out = -0.2, R = 0.2, k = Roof::kRidge;
    const Roof roof(s_in, s_out);
    // The two flanks' offsets at the ridge, and the window either side: the roll, or 0.45 R.
    const double l_in = std::sqrt(1 + s_in * s_in), l_out = std::sqrt(1 + s_out * s_out);
    const double x_in = k - R * s_in / l_in, x_out = k - R * s_out / l_out;
    const double w = std::min(x_out - x_in, 0.45 * R);
    REQUIRE(w == doctest::Approx(0.45 * R));  // roll 0.0966 mm > 0.09
    const double x_start = x_in - w,
                 x_end = x_out + w;  // planes: the offsets move with the contact
    double on_arc = 0, on_flanks = 0, last_x = -1e300, last_z = 0, largest_move = 0;
    for (int i = 0; i <= 4000; ++i) {
      const double rho = k - 2 * w + 4 * w * i / 4000.0;
      const NoseTouch t = touch_at(roof, rho, R);
      double x, z;
      if (rho <= k - w || rho >= k + w) {
        // Outside the window: the contact's own offset.
        const double s = rho < k ? s_in : s_out, l = std::sqrt(1 + s * s);
        x = rho - R * s / l;
        z = s * (rho - k) + R / l;
        CHECK(!t.rolling);
      } else {
        // A contact on the ridge itself (its slope either flank's) is placed as the one
        // 2e-10 mm inside it.
        const double placed_rho = rho == k ? k - 2e-10 : rho;
        x = x_start + (placed_rho - (k - w)) / (2 * w) * (x_end - x_start);
        if (x <= x_in) {
          z = s_in * (x + R * s_in / l_in - k) + R / l_in;  // the foot's offset on the inner plane
        } else if (x >= x_out) {
          z = s_out * (x + R * s_out / l_out - k) + R / l_out;
        } else {
          z = std::sqrt(R * R - (x - k) * (x - k));  // on the arc about the ridge
          on_arc += 1;
          CHECK(t.rho == doctest::Approx(k).epsilon(1e-12));  // touching the ridge
          // The slope handed on is the nose's tangent at the ridge: its offset is the centre.
          CHECK(t.rho - R * t.slope / std::sqrt(1 + t.slope * t.slope) ==
                doctest::Approx(x).epsilon(1e-12));
        }
        on_flanks += std::abs(t.rho - k) > 1e-9;
        CHECK(t.rolling);
        CHECK(!t.held);
      }
      CHECK(t.centre_x == doctest::Approx(x).epsilon(1e-12));
      CHECK(t.centre_z == doctest::Approx(z).epsilon(1e-12));
      // Touching the design, never below it: brute force over the whole nose.
      CHECK(std::abs(brute_overlap(roof, t.centre_x, t.centre_z, R)) <= 1e-12);
      if (i > 0)
        largest_move = std::max(largest_move, std::hypot(t.centre_x - last_x, t.centre_z - last_z));
      last_x = t.centre_x;
      last_z = t.centre_z;
    }
    // The centre never jumps: each 0.09 µm step of the contact moves its abscissa
    // (x_end − x_start)/2w times as far (1.54 here), and the centre √(1 + 0.3²) times that
    // at most (along the steeper flank), where it jumped 96.6 µm at the ridge.
    const double step = 4 * w / 4000;
    CHECK(largest_move <= step * (x_end - x_start) / (2 * w) * std::sqrt(1 + s_in * s_in) * 1.001);
    // The arc takes (x_out − x_in)/(x_end − x_start) = 35 % of the window's 2000 samples.
    CHECK(on_arc == doctest::Approx(2000 * (x_out - x_in) / (x_end - x_start)).epsilon(0.01));
    CHECK(on_flanks > 1200);
  }

  TEST_CASE("a cone's apex pointing at the tool: the nose rolls over it and ends over the apex") {
    // z = −β r (an axicon). The axis is the section's ridge: its flanks' offsets end at
    // ±R sin ψ (tan ψ = β), a roll of J = 2R sin ψ across a window of ±0.45 R. The contacts
    // come from ρ > 0 alone, so the centre's abscissa ramps from the offset's ρ + R sin ψ at
    // ρ = w to 0 at the axis: x = ρ (1 + R sin ψ / w). Where x < R sin ψ the dropped nose
    // touches the apex, z = √(R² − x²); beyond, the flank, z = −β (x − R sin ψ) + R cos ψ.
    const double beta = 0.3, R = 0.2, w = 0.45 * R;
    const OddAsphere cone(0, 0, {-beta});
    const double sin_psi = beta / std::sqrt(1 + beta * beta),
                 cos_psi = 1 / std::sqrt(1 + beta * beta);
    const double rate = 1 + R * sin_psi / w;
    double on_apex = 0, last_x = 0, last_z = 0, largest_move = 0;
    const int n = 3000;
    for (int i = 0; i <= n; ++i) {
      const double rho = 1.5 * w * i / n;
      const NoseTouch t = touch_at(cone, rho, R);
      double x, z;
      if (rho >= w) {
        x = rho + R * sin_psi;  // the contact's own offset
        z = -beta * rho + R * cos_psi;
        CHECK(!t.rolling);
      } else {
        // A contact on the apex itself is placed as the one 2e-10 mm past it (on the far
        // flank, whose offset the ramp moves the same way).
        x = (rho == 0 ? -2e-10 : rho) * rate;
        if (x >= R * sin_psi) {
          z = -beta * (x - R * sin_psi) + R * cos_psi;
        } else {
          z = std::sqrt(R * R - x * x);
          on_apex += 1;
          CHECK(std::abs(t.rho) <= 1e-12);  // touching the apex
        }
        CHECK(t.rolling);
        CHECK(!t.held);
      }
      CHECK(t.centre_x == doctest::Approx(x).epsilon(1e-12));
      CHECK(t.centre_z == doctest::Approx(z).epsilon(1e-12));
      CHECK(std::abs(brute_overlap(cone, t.centre_x, t.centre_z, R)) <= 1e-12);
      if (i > 0)
        largest_move = std::max(largest_move, std::hypot(t.centre_x - last_x, t.centre_z - last_z));
      last_x = t.centre_x;
      last_z = t.centre_z;
    }
    // At the axis the centre stands over the apex, R above it.
    const NoseTouch end = touch_at(cone, 0.0, R);
    CHECK(std::abs(end.centre_x) <= 1e-9);
    CHECK(end.centre_z == doctest::Approx(R).epsilon(1e-12));
    // No jump: a step of the contact moves the centre at most rate·√(1 + β²) times as far
    // (it had jumped R sin ψ = 57.5 µm onto the axis at the spiral's last block).
    CHECK(largest_move <= 1.5 * w / n * rate * std::sqrt(1 + beta * beta) * 1.001);
    // The apex holds the touch for x < R sin ψ: ρ < R sin ψ / rate, of the n / 1.5 samples.
    CHECK(on_apex == doctest::Approx(n / 1.5 * R * sin_psi / rate / w).epsilon(0.01));
  }

  TEST_CASE("a valley of the same planes is held, not rolled") {
    const Roof valley(-0.2, 0.3);
    for (const double rho : {1.99, 1.999, 2.001, 2.01}) {
      const NoseTouch t = touch_at(valley, rho, 0.2);
      CHECK(!t.rolling);
      CHECK(t.held);
    }
  }

  TEST_CASE("domes have no ridge: skipping the search for one changes no placement") {
    // LensletArray::may_have_ridges is false for domes; a view that does not say so makes
    // the planner look for ridges, and it must find none: every placement the same bits.
    struct Looking final : Surface {
      const Surface& s;
      explicit Looking(const Surface& surface) : s(surface) {}
      const char* type() const override { return s.type(); }
      void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
        s.sag_gradient(x, y, z, zx, zy);
      }
      HeightDerivatives height_derivatives(double x, double y) const override {
        return s.height_derivatives(x, y);
      }
      bool has_creases() const override { return true; }
      int section_creases(const RadialLine& line, double lo, double hi,
                          std::span<double> out) const override {
        return s.section_creases(line, lo, hi, out);
      }
      double max_bend(double radius) const override { return s.max_bend(radius); }
    };
    for (const double lens_radius : {-0.3, -0.6}) {
      LensletArrayOptions lo;
      lo.lens_radius = lens_radius;
      lo.lens_diameter = 0.2;
      lo.pitch = 0.25;
      lo.pattern = LensletArrayOptions::Pattern::kHexagonal;
      lo.extent = 1.0;
      const LensletArray domes(lo);
      REQUIRE(!domes.may_have_ridges());
      const Looking looking(domes);
      long compared = 0;
      for (int line = 0; line < 24; ++line) {
        const RadialLine c(0.37 + line * 2 * std::numbers::pi / 24);
        for (int i = 0; i <= 2000; ++i) {
          const double rho = 0.9 * i / 2000;
          double z, zx, zy;
          domes.sag_gradient(rho * c.cos, rho * c.sin, z, zx, zy);
          const double slope = zx * c.cos + zy * c.sin;
          const NoseTouch a = nose_touch(domes, c, 0.2, rho, z, slope, 1e-4);
          const NoseTouch b = nose_touch(looking, c, 0.2, rho, z, slope, 1e-4);
          CHECK(!b.rolling);
          CHECK(a.centre_x == b.centre_x);
          CHECK(a.centre_z == b.centre_z);
          CHECK(a.held == b.held);
          ++compared;
        }
      }
      CHECK(compared == 24 * 2001);
    }
  }

  // Bowls of radius 0.6 mm, 0.2 mm across on a square 0.25 mm lattice (the microlens_mold
  // example), out to `extent`.
  LensletArrayOptions mold_bowls(double extent) {
    LensletArrayOptions lo;
    lo.lens_radius = 0.6;
    lo.lens_diameter = 0.2;
    lo.pitch = 0.25;
    lo.pattern = LensletArrayOptions::Pattern::kSquare;
    lo.extent = extent;
    return lo;
  }

  SpiralOptions ridge_spiral(double outer, double pitch, double tolerance, double R) {
    SpiralOptions o;
    o.outer_radius = outer;
    o.pitch = pitch;
    o.points.tolerance = tolerance;
    o.points.max_angle_step = 4 * std::numbers::pi / 180;
    o.tool.nose_radius = R;
    return o;
  }

  // Plans the spiral and checks it with the dense sampler: no jump, the nose nowhere below
  // the design by more than 1 nm, the chord within ε (2% for the sampler's own margin).
  void check_rolling_spiral(const Surface& s, const SpiralOptions& o, long min_rolled) {
    ContactCollector out;
    const PathSummary summary = plan_spiral(s, BaseSurface::plane(o.outer_radius), o, out);
    CompensationOptions c;
    c.tool.nose_radius = o.tool.nose_radius;
    std::vector<CutterLocation> cls;
    long at_ridge = 0;
    for (const ContactPoint& p : out.points) {
      cls.push_back(compensate(p, c));
      // A touch at the ridge carries the nose's direction, not either flank's normal.
      double z, zx, zy;
      s.sag_gradient(p.point.x(), p.point.y(), z, zx, zy);
      at_ridge += std::abs(p.normal.x() * std::sqrt(1 + zx * zx + zy * zy) + zx) > 1e-6;
    }
    const test::DenseNoseFigures f = test::dense_nose_figures(s, cls, o.tool.nose_radius, 12, 240);
    MESSAGE("points ", cls.size(), ", at a ridge ", at_ridge, ", deepest ", f.gouge * 1e6,
            " nm, chord ", f.worst * 1e6, " nm");
    CHECK(summary.jumps == 0);
    CHECK(f.gouge <= 1e-6);
    CHECK(f.worst <= o.points.tolerance * 1.02);
    CHECK(at_ridge >= min_rolled);
  }

  TEST_CASE("a spiral over a roof's ridge: no jump, no gouge") {
    // The ridge line crosses the turns at every angle, tangent to them at θ = 0. Before the
    // nose rolled (the library before, run with this test): 25 jumps, the nose 5.74 µm into
    // the ridge.
    const Roof roof(0.3, -0.2);
    check_rolling_spiral(roof, ridge_spiral(2.6, 0.05, 2e-4, 0.2), 50);
  }

  TEST_CASE("a roof's ridge with B following about a pivot: the nose rolls, B turns, no gouge") {
    // B follows the nose's tangent at the touch, so the edge point that touches stays the
    // same point of the tool; the pivot 60 mm behind the centre swings with B, and the
    // sampler finds the centre from the interpolated X, Z and B.
    const Roof roof(0.3, -0.2);
    const double R = 0.2, L = 60;
    SpiralOptions o = ridge_spiral(2.6, 0.05, 2e-4, R);
    o.tool.axis_offset = L;
    o.tool.b_follows = true;
    CompensationOptions c;
    c.tool.nose_radius = R;
    c.b_mode = BMode::kFollow;
    c.pivot_distance = L;
    ContactCollector out;
    const PathSummary summary = plan_spiral(roof, BaseSurface::plane(2.6), o, out);
    std::vector<CutterLocation> cls;
    for (const ContactPoint& p : out.points) cls.push_back(compensate(p, c));
    const test::DenseNoseFigures f = test::dense_nose_figures(roof, cls, R, 12, 240, &c);
    double b_lo = 1e300, b_hi = -1e300;
    for (const CutterLocation& cl : cls) b_lo = std::min(b_lo, cl.b), b_hi = std::max(b_hi, cl.b);
    MESSAGE("points ", cls.size(), ", B from ", b_lo * 180 / std::numbers::pi, "° to ",
            b_hi * 180 / std::numbers::pi, "°, deepest ", f.gouge * 1e6, " nm, chord ",
            f.worst * 1e6, " nm");
    CHECK(summary.jumps == 0);
    CHECK(f.gouge <= 1e-6);
    CHECK(f.worst <= o.points.tolerance * 1.02);
    // B turns through the whole roll: from the inner plane's normal to the outer one's.
    CHECK(b_lo <= -std::atan(0.3) + 1e-9);
    CHECK(b_hi >= std::atan(0.2) - 1e-9);
  }

  TEST_CASE("a spiral to an axicon's apex: the nose rolls over it, no jump, no gouge") {
    // The cone z = −0.3 r under a 0.2 mm nose. Before the axis's ridge was rolled (the
    // library before, run with this test): the last block jumped the centre 57.5 µm onto
    // the axis, and its chord cut 1.96 µm into the apex.
    const OddAsphere cone(0, 0, {-0.3});
    check_rolling_spiral(cone, ridge_spiral(1.0, 0.01, 2e-4, 0.2), 100);
  }

  TEST_CASE("a valley with B following: refused with the reason and the way out") {
    // With B following, the nose is held at no crease (nose_roll): the offset of a contact
    // beside the valley overhangs the far plane, and no step holds the tolerance. The
    // refusal says so, and names b_axis: fixed; it had said "the path is not smooth here".
    const Roof valley(-0.2, 0.3);
    SpiralOptions o = ridge_spiral(2.6, 0.05, 2e-4, 0.2);
    o.tool.axis_offset = 60;
    o.tool.b_follows = true;
    ContactCollector out;
    CHECK_THROWS_WITH_AS(plan_spiral(valley, BaseSurface::plane(2.6), o, out),
                         doctest::Contains("with B following the normal the nose is held at no "
                                           "crease, and near r = "),
                         InputError);
    CHECK_THROWS_WITH_AS(plan_spiral(valley, BaseSurface::plane(2.6), o, out),
                         doctest::Contains("a valley of the design is sharper than the nose, "
                                           "whose offset would cut into the far flank (cut it "
                                           "with b_axis: fixed"),
                         InputError);
    // B fixed, the same valley is held and planned.
    o.tool.b_follows = false;
    o.tool.axis_offset = 0;
    CHECK_NOTHROW(plan_spiral(valley, BaseSurface::plane(2.6), o, out));
  }

  TEST_CASE("a NURBS ridge, found from its knots: no jump, no gouge") {
    // The V-groove of the seam tests turned over: z = −0.1115·|x − 0.5|, a cubic with a
    // triple knot on the ridge line. The library before: 29 jumps, the nose 1.13 µm into
    // the ridge.
    const NurbsHeightField ridge(test::v_groove(0.5, -0.1115));
    check_rolling_spiral(ridge, ridge_spiral(1.2, 0.05, 2e-4, 0.2), 20);
  }

  TEST_CASE("a concave microlens array (the mold of a convex one): no jump, no gouge at the rims") {
    // Bowls of radius 0.6 mm, 0.2 mm across at a 0.25 mm pitch, under a 0.2 mm nose, which
    // fits every section of them (the tightest, √(0.6² − 0.1²) = 0.59 mm). Each rim is a
    // ridge; before the nose rolled: 985 jumps, the nose 603 nm into the design.
    const LensletArray bowls(mold_bowls(1.0));
    check_rolling_spiral(bowls, ridge_spiral(0.9, 0.01, 2e-4, 0.2), 100);
  }

  TEST_CASE("the same bowls decentred: their rims are still rolled over, no jump, no gouge") {
    // A segment of the array off its centre (decenter {x: 0.1, y: 0.05}, no tilt): the
    // radial sections are the array's lines through the decentred point, whose rims it
    // knows. Before (no crease reported off the axis), the microlens_mold example job so
    // decentred: 1 904 jumps and 596 nm into the design, by an NC-only check.
    const TransformedSurface bowls(std::make_unique<LensletArray>(mold_bowls(1.2)), 0.1, 0.05,
                                   Eigen::Matrix3d::Identity());
    check_rolling_spiral(bowls, ridge_spiral(0.9, 0.01, 2e-4, 0.2), 100);
  }

  TEST_CASE(
      "the same bowls tilted: their rims, seen as ellipses, are rolled over, no jump, no gouge") {
    // Tilted 0.3° about x (and 0.2° about y), a rim is no closed form along a line: the
    // rims are the array's circles in space, moved and seen along z (ProjectedRims).
    // Before (no crease reported on a tilt), the microlens_mold example job tilted 0.3°:
    // 2 607 jumps and 600 nm into the design, by an NC-only check.
    const TransformedSurface bowls(std::make_unique<LensletArray>(mold_bowls(2.0)), 0.0, 0.0,
                                   TransformedSurface::rotation_from_tilts(
                                       0.3 * std::numbers::pi / 180, 0.2 * std::numbers::pi / 180));
    check_rolling_spiral(bowls, ridge_spiral(0.9, 0.01, 2e-4, 0.2), 100);
  }
}

}  // namespace
}  // namespace freeturn
