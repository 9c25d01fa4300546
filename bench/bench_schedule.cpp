// Block scheduling throughput (machine/block_schedule.hpp): blocks per second through a
// BlockScheduler on a Moore 250UPL's limits, for a spiral every block of which can keep its
// nominal time (10 rpm), and for one where most must be slowed (200 rpm, a 0.5 mm Z wobble).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "freeturn/machine/block_schedule.hpp"
#include "machine/fixtures.hpp"

namespace {

using namespace freeturn;

class Discard final : public AxisSink {
 public:
  void write(std::span<const AxisRecord> chunk) override {
    count += static_cast<long>(chunk.size());
  }
  long count = 0;
};

// 1000 blocks per turn at `rpm`, X creeping inward, Z = amplitude·sin(8θ).
std::vector<AxisRecord> spiral(long blocks, double rpm, double amplitude) {
  std::vector<AxisRecord> r(static_cast<std::size_t>(blocks));
  const double dt = 60.0 / rpm / 1000;
  for (long k = 0; k < blocks; ++k) {
    const double theta = 2 * M_PI * static_cast<double>(k) / 1000;
    r[static_cast<std::size_t>(k)] = {
        4 - 1e-6 * static_cast<double>(k), amplitude * std::sin(8 * theta),
        std::fmod(0.36 * static_cast<double>(k), 360.0), 0, k ? dt : 0.0};
  }
  return r;
}

void run(benchmark::State& state, double rpm, double amplitude) {
  const MachineDescription m = test::moore_250upl_xzc();
  const std::vector<AxisRecord> in = spiral(state.range(0), rpm, amplitude);
  double slowed = 0;
  for (auto _ : state) {
    Discard out;
    BlockScheduler s(m, out);
    for (std::size_t k = 0; k < in.size(); k += 4096)
      s.write(
          std::span<const AxisRecord>(in.data() + k, std::min<std::size_t>(4096, in.size() - k)));
    s.finish();
    benchmark::DoNotOptimize(out.count);
    slowed = static_cast<double>(s.report().slowed_blocks) / static_cast<double>(in.size());
  }
  state.counters["blocks/s"] = benchmark::Counter(static_cast<double>(in.size()),
                                                  benchmark::Counter::kIsIterationInvariantRate);
  state.counters["slowed"] = slowed;
}

void BM_ScheduleNominal(benchmark::State& state) {
  run(state, 10, 0.001);
}
void BM_ScheduleSlowed(benchmark::State& state) {
  run(state, 200, 0.5);
}

}  // namespace

BENCHMARK(BM_ScheduleNominal)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScheduleSlowed)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
