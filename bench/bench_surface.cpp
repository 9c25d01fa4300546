// Design-surface evaluation: sag + gradient per point, the planner's hot path.
#include <benchmark/benchmark.h>

#include "freeturn/surface/even_asphere.hpp"

static void BM_EvenAsphereSagGradient(benchmark::State& state) {
  const freeturn::EvenAsphere s(1.0 / 50.0, -0.8, {1.2e-6, -3e-9, 4e-12});
  double x = -10.0, y = 3.0, sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    sum += z + zx + zy;
    x += 1e-6;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EvenAsphereSagGradient);

BENCHMARK_MAIN();
