#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "freeturn/verify/cut_simulation.hpp"

using namespace freeturn;

namespace {

// A flat face cut by a planar spiral of pitch f (equal angles aligned with the grid's
// columns), compensated for nose radius `planned`, simulated with nose radius `actual`.
// `waviness`: the measured nose-radius error, compensated for and simulated.
SimulationResult cut_flat(double f, double planned, double actual,
                          std::vector<std::pair<double, double>> waviness = {}) {
  const EvenAsphere flat(0, 0);
  SpiralOptions o;
  o.outer_radius = 2.0;
  o.pitch = f;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 8;
  CompensationOptions c;
  c.tool.nose_radius = planned;
  c.tool.waviness = std::move(waviness);
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  SimulationOptions s;
  s.inner_radius = 0.5;  // away from the first and last turns
  s.outer_radius = 1.5;
  s.radial_step = f / 2000;
  s.columns = 8;
  s.band = 2 * f;
  s.compensation = c;
  CutSimulator simulator(flat, actual, s);
  ToolCompensator compensator(flat, c, checks, simulator);
  plan_spiral(flat, BaseSurface::plane(2.0), o, compensator);
  return simulator.finish();
}

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE("a radial step as wide as the aperture is refused: it would sample r = 0 alone") {
    const EvenAsphere flat(0, 0);
    SimulationOptions s;
    s.outer_radius = 4.0;
    s.columns = 2;
    s.radial_step = 10;  // radii 0 only: a form error of 0 for any cut
    CHECK_THROWS_WITH_AS(CutSimulator(flat, 0.2, s),
                         doctest::Contains("leaves 1 radii over r = 0 to 4 mm"), InputError);
    s.radial_step = 2.1;  // 0 and 2.1: still too few
    CHECK_THROWS_AS(CutSimulator(flat, 0.2, s), InputError);
    s.radial_step = 2;  // 0, 2 and 4
    CHECK_NOTHROW(CutSimulator(flat, 0.2, s));
  }

  TEST_CASE("flat face: the scallop between passes f apart is R − √(R² − f²/4) to 1e-3") {
    const double f = 0.05, R = 0.5;
    const SimulationResult r = cut_flat(f, R, R);
    CHECK(r.uncut == 0);
    const double scallop = R - std::sqrt(R * R - f * f / 4);
    CHECK(r.max == doctest::Approx(scallop).epsilon(1e-3).scale(0));
    CHECK(r.pv == doctest::Approx(scallop).epsilon(1e-3).scale(0));
    CHECK(r.min >= -1e-12);  // nowhere below the design
  }

  TEST_CASE("a nose 1 µm larger than planned cuts 1 µm too deep") {
    const double f = 0.05, R = 0.5;
    const SimulationResult r = cut_flat(f, R, R + 0.001);
    CHECK(r.min == doctest::Approx(-0.001).epsilon(1e-3).scale(0));
    // The scallop of the larger nose rides on the 1 µm offset.
    const double scallop = (R + 0.001) - std::sqrt((R + 0.001) * (R + 0.001) - f * f / 4);
    CHECK(r.max == doctest::Approx(scallop - 0.001).epsilon(1e-2).scale(0));
  }

  TEST_CASE("a nose whose waviness is δ at every angle cuts as a round nose of R + δ") {
    // Compensated for its waviness, the centre stands R + δ off the face; simulated as a
    // round nose of R it would leave δ everywhere (or gouge δ where δ < 0). The real edge
    // lies R + δ from the centre: on the face, and scallops of the nose R + δ between.
    const double f = 0.05, R = 0.5;
    for (const double delta : {0.001, -0.001}) {
      CAPTURE(delta);
      const SimulationResult r = cut_flat(
          f, R, R,
          {{-90.0 * std::numbers::pi / 180, delta}, {90.0 * std::numbers::pi / 180, delta}});
      const double rho = R + delta;
      const double scallop = rho - std::sqrt(rho * rho - f * f / 4);
      CHECK(r.max == doctest::Approx(scallop).epsilon(1e-3).scale(0));
      CHECK(r.min >= -1e-12);  // nowhere below the face
      CHECK(r.min <= 1e-9);    // and on it where a pass's contact is
    }
  }
}

#include <cstring>

#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/verify/residual_output.hpp"

namespace {

// A sphere of R 30 mm decentred 8 mm: its sag varies around the spindle, so the motion
// interpolated between blocks errs on both sides of the design, as much as ε. Spiral
// at 10 µm pitch, nose 0.5 mm, chord tolerance ε, the grid over r ∈ [0.5, 1] mm.
struct OffAxisCut {
  SimulationResult result;
  double chord_above = 0, chord_below = 0, scallop = 0;  // the planner's, over the grid
};

OffAxisCut cut_off_axis_sphere(double eps, int threads, double actual_nose = 0.5) {
  const TransformedSurface sphere(std::make_unique<EvenAsphere>(1 / 30.0, 0), 8, 0,
                                  Eigen::Matrix3d::Identity());
  const double f = 0.01, R = 0.5;
  SpiralOptions o;
  o.outer_radius = 1.2;
  o.pitch = f;
  o.tool.nose_radius = R;
  o.points.tolerance = eps;
  o.points.max_angle_step = 1.0;  // the tolerance, not the cap, sets the steps
  CompensationOptions c;
  c.tool.nose_radius = R;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  SimulationOptions s;
  s.inner_radius = 0.5;
  s.outer_radius = 1.0;
  s.radial_step = f / 100;
  s.columns = 1024;
  s.band = 3 * f;
  s.threads = threads;
  s.compensation = c;
  CutSimulator simulator(sphere, actual_nose, s);
  struct Tee final : CutterSink {
    CutSimulator* sim = nullptr;
    OffAxisCut* out = nullptr;
    void write(std::span<const CutterLocation> chunk) override {
      for (const CutterLocation& cl : chunk) {
        if (cl.contact.r < 0.5 || cl.contact.r > 1.0) continue;
        (cl.contact.chord_below ? out->chord_below : out->chord_above) =
            std::max(cl.contact.chord_below ? out->chord_below : out->chord_above, cl.contact.chord_error);
        out->scallop = std::max(out->scallop, cl.contact.scallop);
      }
      sim->write(chunk);
    }
  } tee;
  OffAxisCut cut;
  tee.sim = &simulator;
  tee.out = &cut;
  ToolCompensator compensator(sphere, c, checks, tee);
  plan_spiral(sphere, BaseSurface::plane(1.2), o, compensator);
  cut.result = simulator.finish();
  return cut;
}

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE("a sphere cut with chord tolerance ε: the residual within [0, ε + scallop], and at least 80% of it") {
    const double eps = 5e-4;
    const OffAxisCut cut = cut_off_axis_sphere(eps, 0);
    const SimulationResult& r = cut.result;
    MESSAGE("simulated PV " << r.pv * 1e6 << " nm (max " << r.max * 1e6 << ", min " << r.min * 1e6
                            << "); predicted PV " << r.predicted.pv() * 1e6 << " nm (max " << r.predicted.max() * 1e6
                            << ", min " << r.predicted.min() * 1e6 << ")");
    CHECK(r.uncut == 0);
    // The one-sided band (path/cutter_points.hpp): the blocks stand off ε/2 and every
    // segment bends at most ε/2 either way from there, so the planner's chord errors reach
    // ε above the design and none lies below it, though the section curves both ways in θ
    // around the turn.
    CHECK(cut.chord_above <= eps);
    CHECK(cut.chord_above >= 0.9 * eps);
    CHECK(cut.chord_below == 0);
    // The planner's scallop, against the closed form s²/8 · (1/R − κ) for passes s apart
    // along the section (the radial pitch f lengthened by the section's slope g_r) on a
    // section of curvature κ (concave toward the tool): the radial plane at θ cuts the
    // sphere (radius 30, centre (8, 0, 30)) in a circle of radius √(30² − (8 sin θ)²).
    // Largest over the grid's annulus, r ∈ [0.5, 1] mm.
    const double scallop = cut.scallop;
    double expected = 0;
    for (int i = 0; i <= 50; ++i)
      for (int j = 0; j < 720; ++j) {
        const double r = 0.5 + 0.5 * i / 50, th = 2 * std::numbers::pi * j / 720;
        const double x = r * std::cos(th) - 8, y = r * std::sin(th);
        const double slope = (x * std::cos(th) + y * std::sin(th)) / std::sqrt(900 - x * x - y * y);
        const double spacing2 = 0.01 * 0.01 * (1 + slope * slope);
        const double kappa = 1 / std::sqrt(900 - 64 * std::sin(th) * std::sin(th));
        expected = std::max(expected, spacing2 / 8 * (1 / 0.5 - kappa));
      }
    MESSAGE("scallop " << scallop * 1e6 << " nm, closed form " << expected * 1e6 << " nm");
    CHECK(scallop == doctest::Approx(expected).epsilon(1e-3).scale(0));
    // Material left: at most ε + scallop, at least 80% of it. Never cut below the design
    // (the sampled chord estimate may miss a peak by a part in a thousand of ε/2).
    CHECK(r.max <= eps + scallop);
    CHECK(r.max >= 0.8 * (eps + scallop));
    CHECK(r.min >= -0.001 * eps);
    CHECK(r.pv <= eps + scallop);
  }

  TEST_CASE("the planner's prediction is an upper bound on the simulated PV within 10%") {
    for (const double eps : {2e-4, 5e-4}) {
      const SimulationResult r = cut_off_axis_sphere(eps, 0).result;
      CAPTURE(eps);
      CHECK(r.predicted.pv() >= r.pv);
      CHECK(r.predicted.pv() <= 1.1 * r.pv);
      CHECK(r.predicted.max_chord_below == 0);  // the band is one-sided
    }
  }

  TEST_CASE("the worst places name their cause: chord, scallop, gouge") {
    // Chord-dominated: ε = 0.5 µm against a 25 nm scallop.
    const SimulationResult chord = cut_off_axis_sphere(5e-4, 0).result;
    REQUIRE(chord.worst.size() == 5);
    for (const ResidualPlace& p : chord.worst) CHECK(p.cause == ResidualCause::kChord);
    // Largest first.
    for (std::size_t k = 1; k < chord.worst.size(); ++k)
      CHECK(std::abs(chord.worst[k].residual) <= std::abs(chord.worst[k - 1].residual));
    // A flat face has no chord error: the worst places are scallop crests, whose flank
    // height is the residual itself, (f/2)²/2R to 1e-3.
    const SimulationResult flat = cut_flat(0.05, 0.5, 0.5);
    REQUIRE(!flat.worst.empty());
    for (const ResidualPlace& p : flat.worst) {
      CHECK(p.cause == ResidualCause::kScallop);
      CHECK(p.scallop_part == doctest::Approx(p.residual).epsilon(1e-2).scale(0));
    }
    // A nose 1 µm larger than planned cuts 1 µm below the design, far beyond any chord
    // error: a gouge. The band is one-sided (the motion stays in [0, ε] above the design
    // and reaches it where a chord dips the most), so the deepest place is 1 µm below the
    // design, to a few nm where the grid's cells miss the lowest point.
    const SimulationResult deep = cut_off_axis_sphere(2e-4, 0, 0.501).result;
    REQUIRE(!deep.worst.empty());
    CHECK(deep.worst.front().cause == ResidualCause::kGouge);
    CHECK(deep.worst.front().residual >= -0.001 - 1e-9);
    CHECK(deep.worst.front().residual <= -0.001 + 0.05 * 2e-4);
  }

  TEST_CASE("the simulation is the same, bit for bit, on 1, 2 and 5 threads") {
    const SimulationResult one = cut_off_axis_sphere(5e-4, 1).result;
    for (const int threads : {2, 5}) {
      const SimulationResult many = cut_off_axis_sphere(5e-4, threads).result;
      CAPTURE(threads);
      REQUIRE(many.residual.size() == one.residual.size());
      CHECK(std::memcmp(many.residual.data(), one.residual.data(), one.residual.size() * sizeof(double)) == 0);
      CHECK(std::memcmp(&many.rms, &one.rms, sizeof(double)) == 0);
      CHECK(many.pv == one.pv);
      CHECK(many.worst.size() == one.worst.size());
    }
  }

  TEST_CASE("the heat map: per pixel, the radial mean at the nearest column") {
    // A hand-made grid: rings at 0.05 + 0.25i mm (i = 0…4), 4 columns; residual = i,
    // except ring 2 at 90°, never cut.
    SimulationResult r;
    r.rings = 5;
    r.columns = 4;
    r.radial_step = 0.25;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 4; ++j) r.residual.push_back(i == 2 && j == 1 ? std::nan("") : i);
    // 5 × 5 pixels over [−1.05, 1.05]², 0.42 wide: each takes the rings within 0.21 of
    // its centre's radius, at the column nearest its centre's angle.
    const ResidualHeatMap m = residual_heat_map(r, 0.05, 5);
    CHECK(m.half_width == doctest::Approx(1.05));
    const auto at = [&](int x, int y) { return m.mean[static_cast<std::size_t>(y * 5 + x)]; };
    CHECK(at(2, 2) == doctest::Approx(0.0));  // centre: ring 0
    CHECK(at(3, 2) == doctest::Approx(1.5));  // (0.42, 0): rings 1, 2 at 0°
    CHECK(at(2, 1) == doctest::Approx(1.0));  // (0, 0.42): rings 1 and 2 at 90°, 2 uncut
    CHECK(at(4, 1) == doctest::Approx(3.5));  // (0.84, 0.42), r 0.94 at 26.6° → 0°: rings 3, 4
    CHECK(std::isnan(at(0, 0)));              // r 1.19: beyond the grid
    CHECK(m.low == doctest::Approx(0.0));
    CHECK(m.high == doctest::Approx(3.5));
  }
}

namespace {

// One block of a hand-made path at angle θ over a flat design z = 0: contact at radius
// `r`, nose centre (r, centre_z), the programmed axes x, z, B as given.
CutterLocation block(double theta, double r, double centre_z, double x, double z, double b) {
  CutterLocation cl;
  cl.contact.theta = theta;
  cl.contact.r = r;
  cl.contact.point = {r * std::cos(theta), r * std::sin(theta), 0.0};
  cl.nose_centre = {r * std::cos(theta), r * std::sin(theta), centre_z};
  cl.x = x;
  cl.z = z;
  cl.b = b;
  cl.c = theta;
  return cl;
}

SimulationOptions ring_grid(int columns) {
  SimulationOptions s;
  s.inner_radius = 0.9;
  s.outer_radius = 1.1;
  s.radial_step = 0.001;
  s.columns = columns;
  s.band = 0.05;
  return s;
}

double residual_at(const SimulationResult& r, double inner, double radius, int column) {
  const int ring = static_cast<int>(std::lround((radius - inner) / r.radial_step));
  return r.residual[static_cast<std::size_t>(ring) * static_cast<std::size_t>(r.columns) + static_cast<std::size_t>(column)];
}

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE("B about a pivot: the nose swings on an arc between blocks, L(1 − cos δ) below the chord") {
    // Two blocks with B = −δ and +δ, the nose centre R above a flat face at both; the
    // controller moves the pivot (centre + L·(sin B, cos B)) and B linearly, so halfway
    // the centre is L(1 − cos δ) lower than at the blocks, and cuts that deep.
    const double R = 0.5, L = 50, delta = 0.01;
    const int columns = 64;
    const double step = 2 * std::numbers::pi / columns;
    SimulationOptions s = ring_grid(columns);
    s.compensation.tool.nose_radius = R;
    s.compensation.b_mode = BMode::kFollow;
    s.compensation.pivot_distance = L;
    const EvenAsphere flat(0, 0);
    CutSimulator pivot(flat, R, s);
    const CutterLocation a = block(0, 1.0, R, 1.0 + L * std::sin(-delta), R + L * std::cos(-delta), -delta);
    const CutterLocation b = block(2 * step, 1.0, R, 1.0 + L * std::sin(delta), R + L * std::cos(delta), delta);
    const std::vector<CutterLocation> path{a, b};
    pivot.write(path);
    const SimulationResult r = pivot.finish();
    CHECK(residual_at(r, 0.9, 1.0, 1) == doctest::Approx(-L * (1 - std::cos(delta))).epsilon(1e-9).scale(1));
    CHECK(residual_at(r, 0.9, 1.0, 0) == doctest::Approx(0.0).epsilon(1e-12).scale(1));
    // Programmed at the nose centre, the same motion stays on the face.
    SimulationOptions centre = ring_grid(columns);
    centre.compensation.tool.nose_radius = R;
    CutSimulator direct(flat, R, centre);
    const std::vector<CutterLocation> centres{block(0, 1.0, R, 1.0, R, -delta), block(2 * step, 1.0, R, 1.0, R, delta)};
    direct.write(centres);
    CHECK(residual_at(direct.finish(), 0.9, 1.0, 1) == doctest::Approx(0.0).epsilon(1e-12).scale(1));
  }

  TEST_CASE("PVT: the cubic through neighbour-derived velocities reproduces a quadratic exactly; linear does not") {
    // Blocks every 4 columns with the nose centre at R + aθ²: centred differences of a
    // quadratic are its derivative, so between interior blocks the cubic Hermite is the
    // quadratic itself; linear interpolation leaves a·h²/4 at mid-block.
    const double R = 0.5, a = 1e-4;
    const int columns = 128, every = 4;
    const double step = 2 * std::numbers::pi / columns, h = every * step;
    std::vector<CutterLocation> path;
    for (int k = 0; k * every <= columns - every; ++k) {
      const double theta = k * h, z = R + a * theta * theta;
      path.push_back(block(theta, 1.0, z, 1.0, z, 0.0));
    }
    const EvenAsphere flat(0, 0);
    for (const Interpolation mode : {Interpolation::kCubic, Interpolation::kLinear}) {
      SimulationOptions s = ring_grid(columns);
      s.compensation.tool.nose_radius = R;
      s.interpolation = mode;
      CutSimulator simulator(flat, R, s);
      // In two chunks, so that a segment's neighbours straddle a write.
      simulator.write(std::span(path).first(7));
      simulator.write(std::span(path).subspan(7));
      const SimulationResult r = simulator.finish();
      double worst = 0;
      for (int column = every + 1; column < columns - 2 * every; ++column) {
        const double phi = column * step;
        worst = std::max(worst, std::abs(residual_at(r, 0.9, 1.0, column) - a * phi * phi));
      }
      if (mode == Interpolation::kCubic) CHECK(worst < 1e-15);
      else CHECK(worst == doctest::Approx(a * h * h / 4).epsilon(1e-9));
    }
  }
}

TEST_SUITE("verify") {
  TEST_CASE("the prediction: chord errors by side, a jump's on both, scallops within the figures' radii") {
    const EvenAsphere flat(0, 0);
    SimulationOptions s = ring_grid(8);
    s.margin = 0.02;  // figures over r ∈ [0.92, 1.08]
    CutSimulator simulator(flat, 0.5, s);
    std::vector<CutterLocation> path{block(0.0, 1.0, 0.5, 1.0, 0.5, 0), block(0.1, 1.0, 0.5, 1.0, 0.5, 0),
                                     block(0.2, 1.0, 0.5, 1.0, 0.5, 0), block(0.3, 1.0, 0.5, 1.0, 0.5, 0),
                                     block(0.4, 1.09, 0.5, 1.09, 0.5, 0)};
    path[1].contact.chord_error = 2e-4;  // above
    path[1].contact.scallop = 5e-5;
    path[2].contact.chord_error = 3e-4;
    path[2].contact.chord_below = true;
    path[3].contact.chord_error = 1e-4;  // a jump: both sides
    path[3].contact.chord_jump = true;
    path[4].contact.chord_error = 9e-3;  // outside the figures' radii
    path[4].contact.scallop = 9e-3;
    simulator.write(path);
    const ResidualPrediction p = simulator.finish().predicted;
    CHECK(p.max_chord_above == 2e-4);
    CHECK(p.max_chord_below == 3e-4);
    CHECK(p.max_scallop == 5e-5);
    CHECK(p.pv() == doctest::Approx(2e-4 + 5e-5 + 3e-4));
    // A jump larger than either side shows on both.
    CutSimulator jumped(flat, 0.5, s);
    path[3].contact.chord_error = 7e-4;
    jumped.write(path);
    const ResidualPrediction q = jumped.finish().predicted;
    CHECK(q.max_chord_above == 7e-4);
    CHECK(q.max_chord_below == 7e-4);
  }
}

#include "freeturn/surface/polynomial_height.hpp"

namespace {

// Passes compensated locations on with the spindle angle and X that compensation wrote for
// a tool above centre until December 2026: the nose centre's own, x = √(c_r² − h²),
// C = θ − atan2(h, x) and z = c_z, which is right only for the edge point under the centre.
class CentreAngleMapping final : public CutterSink {
 public:
  CentreAngleMapping(double h, CutterSink& next) : h_(h), next_(next) {}
  void write(std::span<const CutterLocation> chunk) override {
    for (CutterLocation cl : chunk) {
      const double c_r = std::hypot(cl.nose_centre.x(), cl.nose_centre.y());
      cl.x = std::sqrt(c_r * c_r - h_ * h_);
      cl.c = cl.contact.theta - std::atan2(h_, cl.x);
      cl.z = cl.nose_centre.z();
      next_.write(std::span<const CutterLocation>(&cl, 1));
    }
  }

 private:
  double h_;
  CutterSink& next_;
};

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE(
      "a tool above centre cuts with an arc in the rake plane: on a tilted plane the "
      "nose laid in that plane leaves it whole; the centre's angle alone cuts the closed "
      "form's depth into it") {
    // z = s·x. At spindle angle C the arc (X − R sin φ, h, Z − R cos φ) stands over the plane
    // by Z − s(X cos C − h sin C) − R cos φ + sR sin φ cos C, least R√(1 + s² cos² C) below
    // Z − s·x_c, x_c the centre's x on the part. With the centre placed in the radial plane
    // at θ (tangent there: Z − s·x_c = R√(1 + s² cos² θ)) and C = θ − γ, γ = atan2(h, X),
    // the arc dips R(√(1 + s² cos²(θ − γ)) − √(1 + s² cos² θ)) below the plane.
    const double s = 0.3, R = 0.2, h = 0.01, inner = 0.3;
    const PolynomialHeight plane(1.0, 1, {0, 0, s, 0});
    SpiralOptions o;
    o.outer_radius = 1.0;
    o.pitch = 0.02;
    o.points.rule = CutterPointRule::kEqualAngle;
    o.points.points_per_revolution = 720;
    CompensationOptions c;
    c.tool.nose_radius = R;
    c.tool.centre_height = h;
    ToolCheckOptions checks;
    checks.policy.fill(CheckPolicy::kOff);
    SimulationOptions g;
    g.inner_radius = inner;
    g.outer_radius = 0.9;
    g.radial_step = 0.0005;
    g.columns = 720;
    g.compensation = c;
    const auto simulate = [&](bool centre_angle) {
      CutSimulator simulator(plane, R, g);
      CentreAngleMapping old(h, simulator);
      ToolCompensator compensator(plane, c, checks,
                                  centre_angle ? static_cast<CutterSink&>(old) : simulator);
      plan_spiral(plane, BaseSurface::plane(o.outer_radius), o, compensator);
      return simulator.finish();
    };
    const SimulationResult laid = simulate(false);
    MESSAGE("the nose laid in the rake plane: ", laid.min * 1e6, " nm");
    CHECK(laid.min > -1e-9);
    CHECK(laid.min < 1e-7);
    // The closed form's deepest at the innermost ring, along the normal.
    double deepest = 0;
    for (int k = 0; k < 36000; ++k) {
      const double theta = 2 * std::numbers::pi * k / 36000, ct = std::cos(theta);
      const double c_r = inner - R * s * ct / std::sqrt(1 + s * s * ct * ct);
      const double gamma = std::atan2(h, std::sqrt(c_r * c_r - h * h));
      const double cg = std::cos(theta - gamma);
      deepest =
          std::max(deepest, R * (std::sqrt(1 + s * s * cg * cg) - std::sqrt(1 + s * s * ct * ct)));
    }
    deepest /= std::sqrt(1 + s * s);
    const SimulationResult centre_angle = simulate(true);
    MESSAGE("the centre's angle alone: ", centre_angle.min * 1e6, " nm; closed form ",
            -deepest * 1e6, " nm");
    CHECK(deepest > 1e-4);
    CHECK(centre_angle.min == doctest::Approx(-deepest).epsilon(0.02).scale(0));
  }
}
