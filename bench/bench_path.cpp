// Spiral planning throughput: contact points per second, traditional (plane base,
// projection along z) and space (least-squares base, projection along its normal)
// spirals, chord-controlled at 0.1 µm, for a sphere, a 66-term Zernike surface and a
// rational bicubic NURBS surface. Points go to a sink that only counts them. The second
// argument is the nose radius in µm: 0 measures the chord on the contact path, 500 on
// the nose-centre motion the machine interpolates (two evaluations per sample, not one).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/zernike.hpp"
#include "path/fixtures.hpp"

namespace {

struct CountingSink final : freeturn::ContactSink {
  void write(std::span<const freeturn::ContactPoint> chunk) override {
    count += static_cast<long>(chunk.size());
  }
  long count = 0;
};

std::unique_ptr<freeturn::Surface> make_surface(int which) {
  if (which == 0) return std::make_unique<freeturn::EvenAsphere>(1 / 40.0, 0.0);
  if (which == 1) {
    std::vector<double> a(66);
    for (int j = 0; j < 66; ++j) a[j] = 2e-4 * std::sin(1.0 + j) / (1 + j / 10.0);
    return std::make_unique<freeturn::Zernike>(1 / 80.0, -0.6, std::array<double, 9>{1e-6}, 8.0, a);
  }
  // A rational bicubic 20 × 20 net whose height field must invert (x, y) → (u, v).
  return std::make_unique<freeturn::NurbsHeightField>(freeturn::test::wavy_nurbs(20, 0.3));
}

const char* const kNames[] = {"sphere", "zernike66", "nurbs"};

void run(benchmark::State& state, bool space) {
  const double nose = static_cast<double>(state.range(1)) * 1e-3;
  const auto surface = make_surface(static_cast<int>(state.range(0)));
  const double outer = 4.0;
  const freeturn::BaseSurface base =
      space ? freeturn::fit_base_least_squares(freeturn::sample_aperture(*surface, 0, outer, 24, 48))
            : freeturn::BaseSurface::plane(outer);
  freeturn::SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = 0.05;
  o.points.tolerance = 1e-4;
  o.points.max_angle_step = 0.05;
  o.tool.nose_radius = nose;
  long points = 0;
  for (auto _ : state) {
    CountingSink sink;
    freeturn::plan_spiral(*surface, base, o, sink);
    points += sink.count;
  }
  state.SetLabel(kNames[state.range(0)]);
  state.counters["points"] = static_cast<double>(points) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(points);
}

void BM_TraditionalSpiral(benchmark::State& state) { run(state, false); }
void BM_SpaceSpiral(benchmark::State& state) { run(state, true); }

}  // namespace

BENCHMARK(BM_TraditionalSpiral)->ArgsProduct({{0, 1, 2}, {0, 500}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpaceSpiral)->ArgsProduct({{0, 1, 2}, {0, 500}})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
