// Design-surface evaluation: sag + gradient per point, the planner's hot path.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/qbfs.hpp"
#include "nurbs/fixtures.hpp"
#include "freeturn/surface/zernike.hpp"

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

static void BM_Zernike66SagGradient(benchmark::State& state) {
  std::vector<double> a(66);
  for (int j = 0; j < 66; ++j) a[j] = 1e-3 * std::sin(1.0 + j);
  const freeturn::Zernike s(1 / 80.0, -0.6, {1e-6}, 10.0, a);
  double x = -7.0, y = 2.0, sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    sum += z + zx + zy;
    x += 1e-6;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Zernike66SagGradient);

static void BM_Zernike66Hessian(benchmark::State& state) {
  std::vector<double> a(66);
  for (int j = 0; j < 66; ++j) a[j] = 1e-3 * std::sin(1.0 + j);
  const freeturn::Zernike s(1 / 80.0, -0.6, {1e-6}, 10.0, a);
  double x = -7.0, y = 2.0, sum = 0;
  for (auto _ : state) {
    const auto h = s.height_derivatives(x, y);
    sum += h.z + h.zxx;
    x += 1e-6;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Zernike66Hessian);

// A compound eye of about 200 lenslets: base R 40 mm, lenslets R −1.5 mm, D 0.9 mm,
// pitch 1 mm, hexagonal, over a 7.5 mm aperture radius.
static void BM_CompoundEyeSagGradient(benchmark::State& state) {
  freeturn::LensletArrayOptions o;
  o.base_curvature = 1 / 40.0;
  o.lens_radius = -1.5;
  o.lens_diameter = 0.9;
  o.pitch = 1.0;
  o.extent = 7.5;
  const freeturn::LensletArray s(o);
  state.counters["lenslets"] = s.lenslet_count();
  double x = -7.0, y = -0.3, sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    sum += z + zx + zy;
    x += 0.000731;
    if (x > 7.0) x = -7.0;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CompoundEyeSagGradient);

static void BM_Qbfs12SagGradient(benchmark::State& state) {
  std::vector<double> a(12);
  for (int m = 0; m < 12; ++m) a[m] = 1e-3 * std::cos(1.0 + m);
  const freeturn::Qbfs s(1 / 60.0, 10.0, a);
  double x = -7.0, y = 2.0, sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    sum += z + zx + zy;
    x += 1e-6;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Qbfs12SagGradient);

// A rational bicubic 20 × 20 freeform seen as z(x, y): each query inverts (x, y) → (u, v)
// by Newton from the previous query, as along a spiral (steps of 10 µm on a circle).
static void BM_NurbsHeightFieldSagGradient(benchmark::State& state) {
  const freeturn::NurbsHeightField s(freeturn::test::freeform_with_pole());
  double phi = 0.1, sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(5.0 * std::cos(phi), 5.0 * std::sin(phi), z, zx, zy);
    sum += z + zx + zy;
    phi += 0.002;
    if (phi > 4.5) phi = 0.1;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NurbsHeightFieldSagGradient);

BENCHMARK_MAIN();
