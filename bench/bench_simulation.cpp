// The cut simulation of issue 9's reference pass: a 10-mm-aperture (r ≤ 5 mm) finishing
// pass at 2 µm pitch on a 66-term Zernike freeform, chord-controlled at 0.1 µm, nose
// 0.5 mm, simulated on the default grid (pitch/8 radially, 360 columns: 20 001 × 360 =
// 7.2 million cells, or 1800 columns). Streams plan → compensation → simulation as `freeturn simulate`
// does; `path_only` is the same pipeline without the simulation, so the difference is the
// simulation's cost. Args: threads, columns (1800 columns: 36 million cells, 2.5 µm apart
// at the centre… 17 µm at the edge).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/zernike.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "freeturn/verify/cut_simulation.hpp"

namespace {

using namespace freeturn;

constexpr double kPitch = 0.002, kOuter = 5.0, kNose = 0.5;

const Zernike& surface() {
  static const Zernike z = [] {
    std::vector<double> a(66);
    for (int j = 0; j < 66; ++j) a[j] = 2e-4 * std::sin(1.0 + j) / (1 + j / 10.0);
    return Zernike(1 / 80.0, -0.6, {1e-6}, 8.0, a);
  }();
  return z;
}

struct NullCutterSink final : CutterSink {
  void write(std::span<const CutterLocation> chunk) override { count += static_cast<long>(chunk.size()); }
  long count = 0;
};

long run(CutterSink& sink) {
  SpiralOptions o;
  o.outer_radius = kOuter;
  o.pitch = kPitch;
  o.tool.nose_radius = kNose;
  o.points.tolerance = 1e-4;
  CompensationOptions c;
  c.tool.nose_radius = kNose;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  ToolCompensator compensator(surface(), c, checks, sink);
  return plan_spiral(surface(), BaseSurface::plane(kOuter), o, compensator).points;
}

void path_only(benchmark::State& state) {
  long points = 0;
  for (auto _ : state) {
    NullCutterSink sink;
    points = run(sink);
  }
  state.counters["points"] = static_cast<double>(points);
}

void simulate(benchmark::State& state) {
  SimulationOptions s;
  s.inner_radius = 0;
  s.outer_radius = kOuter;
  s.radial_step = kPitch / 8;
  s.band = 3 * kPitch;
  s.margin = kPitch;
  s.threads = static_cast<int>(state.range(0));
  s.compensation.tool.nose_radius = kNose;
  s.columns = static_cast<int>(state.range(1));
  SimulationResult r;
  long points = 0;
  for (auto _ : state) {
    CutSimulator simulator(surface(), kNose, s);
    points = run(simulator);
    r = simulator.finish();
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["cells"] = static_cast<double>(r.rings) * r.columns;
  state.counters["pv_nm"] = r.pv * 1e6;
  state.counters["predicted_pv_nm"] = r.predicted.pv() * 1e6;
}

}  // namespace

BENCHMARK(path_only)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(simulate)->Args({1, 360})->Args({2, 360})->Args({1, 1800})->Args({2, 1800})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_MAIN();
