// Nose-radius compensation with every check on: cutter locations per second for a
// 66-term Zernike surface, one chunk of 4096 contact points at a time (the pipeline's
// chunk), and compensation alone.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/zernike.hpp"
#include "freeturn/tool/clearance.hpp"
#include "freeturn/tool/tool_compensator.hpp"

namespace {

struct NullCutterSink final : freeturn::CutterSink {
  void write(std::span<const freeturn::CutterLocation> chunk) override { count += static_cast<long>(chunk.size()); }
  long count = 0;
};

const freeturn::Zernike& surface() {
  static const freeturn::Zernike z = [] {
    std::vector<double> a(66);
    for (int j = 0; j < 66; ++j) a[j] = 2e-4 * std::sin(1.0 + j) / (1 + j / 10.0);
    return freeturn::Zernike(1 / 80.0, -0.6, {1e-6}, 8.0, a);
  }();
  return z;
}

std::vector<freeturn::ContactPoint> contact_chunk() {
  freeturn::SpiralOptions o;
  o.outer_radius = 4;
  o.pitch = 0.05;
  o.points.rule = freeturn::CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 360;
  freeturn::ContactCollector all;
  freeturn::plan_spiral(surface(), freeturn::BaseSurface::plane(4), o, all);
  all.points.resize(freeturn::ContactChunker::kChunkSize);
  return all.points;
}

void BM_CompensateAndCheck(benchmark::State& state) {
  const auto chunk = contact_chunk();
  freeturn::CompensationOptions c;
  c.tool.nose_radius = 0.5;
  c.tool.included_angle = 2.0;
  c.tool.clearance_angle = 0.3;
  freeturn::ToolCheckOptions checks;
  checks.outer_radius = 4;
  checks.gouge_samples = static_cast<int>(state.range(0));
  if (checks.gouge_samples == 0)
    checks.policy[static_cast<int>(freeturn::ToolCheck::kGlobalGouge)] = freeturn::CheckPolicy::kOff;
  NullCutterSink sink;
  freeturn::ToolCompensator compensator(surface(), c, checks, sink);
  for (auto _ : state) compensator.write(chunk);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(chunk.size()));
}

// The clearance base a run computes once before posting (129 × 360 sags and the pattern
// search from the 8 best): its cost against the planning it precedes.
void BM_ProgramZCeiling(benchmark::State& state) {
  freeturn::CompensationOptions c;
  c.tool.nose_radius = 0.5;
  for (auto _ : state) benchmark::DoNotOptimize(freeturn::program_z_ceiling(surface(), 0, 4, c, 0));
}

}  // namespace

// Argument: samples of the global gouge check along the edge (0: that check off).
BENCHMARK(BM_CompensateAndCheck)->Arg(0)->Arg(16);
BENCHMARK(BM_ProgramZCeiling)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
