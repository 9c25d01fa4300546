#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "freeturn/path/spiral.hpp"
#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "freeturn/verify/cut_simulation.hpp"

using namespace freeturn;

namespace {

// A flat face cut by a planar spiral under a 0.5 mm nose whose every block is moved `depth`
// (mm) down into it after compensation, on the simulation's grid: the nose's lowest points
// lie exactly `depth` below the face.
std::shared_ptr<SimulationResult> flat_cut_lowered_by(double depth) {
  struct Lowered final : CutterSink {
    CutterSink& next;
    double depth;
    Lowered(CutterSink& n, double d) : next(n), depth(d) {}
    void write(std::span<const CutterLocation> chunk) override {
      std::vector<CutterLocation> moved(chunk.begin(), chunk.end());
      for (CutterLocation& cl : moved) cl.z -= depth, cl.nose_centre.z() -= depth;
      next.write(moved);
    }
  };
  const EvenAsphere flat(0, 0);
  SpiralOptions o;
  o.outer_radius = 2.0;
  o.pitch = 0.01;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 64;
  CompensationOptions c;
  c.tool.nose_radius = 0.5;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  SimulationOptions s;
  s.inner_radius = 0.5;
  s.outer_radius = 1.5;
  s.radial_step = 0.001;
  s.columns = 64;
  s.compensation = c;
  CutSimulator simulator(flat, 0.5, s);
  Lowered lowered(simulator, depth);
  ToolCompensator compensator(flat, c, checks, lowered);
  plan_spiral(flat, BaseSurface::plane(2.0), o, compensator);
  return std::make_shared<SimulationResult>(simulator.finish());
}

}  // namespace

TEST_SUITE("pipeline") {
  TEST_CASE("the report's block charts follow a PVT controller's cubics, not straight lines") {
    // X runs at 1 mm/s and stops within one block, 1 s a block: 0, 1, 2, 3, 3, 3. The
    // controller's velocities are the central differences (1, 1, 1, 0.5, 0, 0, one-sided at
    // the ends). On the block 2 → 3 (va 1, vb 0.5, slope 1) the velocity is
    // v(u) = −1.5u² + u + 1, which peaks at u = 1/3 at 7/6 (the overshoot of a sixth), and
    // the acceleration runs from 1 to −2; on 3 → 3 (va 0.5, vb 0) v falls from 0.5 and the
    // acceleration starts at −2. The first block starts from rest: 1 mm/s over 1 s. C turns
    // at 5°/s through 360° (350, 355, 0, 5, 10, 15), read unwrapped. A straight-line reading
    // of the same blocks has X's largest acceleration at 1 mm/s², not 2.
    PassFigures figures;
    AxisSpec x;
    const double xs[] = {0, 1, 2, 3, 3, 3}, cs[] = {350, 355, 0, 5, 10, 15};
    for (int k = 0; k < 6; ++k) {
      AxisRecord r;
      r.x = xs[k];
      r.c = cs[k];
      r.time = k == 0 ? 0.0 : 1.0;
      figures.add_block(r, x, true, true);
    }
    figures.finish(PathSummary{}, DynamicsReport{}, ToolCheckReport{});
    REQUIRE(figures.blocks.size() == 5);
    const double v_x[] = {1, 1, 7.0 / 6, 0.5, 0}, a_x[] = {1, 0, -2, -2, 0};
    for (int k = 0; k < 5; ++k) {
      const BlockPoint& b = figures.blocks[static_cast<std::size_t>(k)];
      CAPTURE(k);
      CHECK(b.r == doctest::Approx(xs[k + 1]).epsilon(1e-15));
      CHECK(b.v[0] == doctest::Approx(v_x[k]).epsilon(1e-12));
      CHECK(b.a[0] == doctest::Approx(a_x[k]).epsilon(1e-12));
      CHECK(b.v[1] == 0);
      CHECK(b.a[1] == 0);
      CHECK(b.v[2] == doctest::Approx(5).epsilon(1e-12));
      CHECK(b.a[2] == doctest::Approx(k == 0 ? 5.0 : 0.0).epsilon(1e-12));
    }
    // The same blocks read as straight lines.
    PassFigures linear;
    for (int k = 0; k < 6; ++k) {
      AxisRecord r;
      r.x = xs[k];
      r.time = k == 0 ? 0.0 : 1.0;
      linear.add_block(r, x, true, false);
    }
    REQUIRE(linear.blocks.size() == 5);
    double largest = 0;
    for (const BlockPoint& b : linear.blocks) largest = std::max(largest, std::abs(b.a[0]));
    CHECK(largest == 1);
  }

  TEST_CASE("the report's turn samples take a path that starts below θ = 0") {
    // A program read back may start at a negative C (an accumulating C axis, a sign of −1):
    // its first turn is −1, the value turn_ starts at, and the first sample had gone into a
    // turn never opened (a crash in `simulate --program`).
    TurnSamples samples;
    const double step = 2 * std::numbers::pi / TurnSamples::kTurnPoints;
    for (int k = -10; k < 3 * TurnSamples::kTurnPoints; ++k) samples.add((k + 0.5) * step, k, 0);  // mid-step: no floor on a boundary
    // Turns −1, 0, 1 and 2, one sample per step of each: 10, 240, 240 and 240.
    REQUIRE(samples.turns.size() == 4);
    CHECK(samples.turns[0].size() == 10);
    CHECK(samples.turns[1].size() == TurnSamples::kTurnPoints);
    CHECK(samples.turns[3].size() == TurnSamples::kTurnPoints);
    CHECK(samples.turns[0].front().first == -10.0f);
    CHECK(samples.start_x == -10);
  }

  TEST_CASE("the verdict judges the simulated cut: more than 10 nm below the design is UNSAFE") {
    // A program's own blocks, cut in simulation, are a second witness beside the planner's
    // figures: a chord measure that fell short had let 45 nm below the design pass.
    for (const double depth : {30e-6, 5e-6}) {
      RunReport report;
      report.simulation = flat_cut_lowered_by(depth);
      CHECK(report.simulation->min == doctest::Approx(-depth).epsilon(1e-6));
      // The report's own grid (not asked for) is not judged: the verdict would otherwise
      // depend on whether a report is written.
      judge(report);
      CHECK(report.warnings.empty());
      report.simulated = true;
      judge(report);
      const auto it =
          std::find_if(report.warnings.begin(), report.warnings.end(),
                       [](const ReportWarning& w) { return w.kind == "simulated_gouge"; });
      if (depth > kChordDipAllowed) {
        REQUIRE(it != report.warnings.end());
        CHECK(it->severity == ReportWarning::Severity::kUnsafe);
        CHECK(it->value == doctest::Approx(depth * 1e6).epsilon(1e-6));
        CHECK(it->limit == doctest::Approx(10.0));
        CHECK(it->r_mm >= 0.5);
        CHECK(it->r_mm <= 1.5);
        CHECK_FALSE(report.safe());
      } else {
        CHECK(it == report.warnings.end());
      }
    }
  }
}
