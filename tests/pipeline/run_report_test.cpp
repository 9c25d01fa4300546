#include <doctest/doctest.h>

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
