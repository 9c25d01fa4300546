// Design-surface evaluation: sag + gradient per point, the planner's hot path.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/qbfs.hpp"
#include "freeturn/surface/zernike.hpp"
#include "nurbs/fixtures.hpp"

namespace {

// Sag + gradient along a walk: `next` moves (x, y) between calls, as a path does.
template <typename Next>
void sag_gradient_walk(benchmark::State& state, const freeturn::Surface& s, double x, double y,
                       Next next) {
  double sum = 0;
  for (auto _ : state) {
    double z, zx, zy;
    s.sag_gradient(x, y, z, zx, zy);
    sum += z + zx + zy;
    next(x, y);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}

void step_x(double& x, double&) { x += 1e-6; }

freeturn::Zernike zernike66() {
  std::vector<double> a(66);
  for (int j = 0; j < 66; ++j) a[j] = 1e-3 * std::sin(1.0 + j);
  return freeturn::Zernike(1 / 80.0, -0.6, {1e-6}, 10.0, a);
}

void BM_EvenAsphereSagGradient(benchmark::State& state) {
  const freeturn::EvenAsphere s(1.0 / 50.0, -0.8, {1.2e-6, -3e-9, 4e-12});
  sag_gradient_walk(state, s, -10.0, 3.0, step_x);
}
BENCHMARK(BM_EvenAsphereSagGradient);

void BM_Zernike66SagGradient(benchmark::State& state) {
  sag_gradient_walk(state, zernike66(), -7.0, 2.0, step_x);
}
BENCHMARK(BM_Zernike66SagGradient);

void BM_Zernike66Hessian(benchmark::State& state) {
  const freeturn::Zernike s = zernike66();
  double x = -7.0, sum = 0;
  for (auto _ : state) {
    const auto h = s.height_derivatives(x, 2.0);
    sum += h.z + h.zxx;
    x += 1e-6;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Zernike66Hessian);

// A compound eye of about 200 lenslets: base R 40 mm, lenslets R −1.5 mm, D 0.9 mm,
// pitch 1 mm, hexagonal, over a 7.5 mm aperture radius.
void BM_CompoundEyeSagGradient(benchmark::State& state) {
  freeturn::LensletArrayOptions o;
  o.base_curvature = 1 / 40.0;
  o.lens_radius = -1.5;
  o.lens_diameter = 0.9;
  o.pitch = 1.0;
  o.extent = 7.5;
  const freeturn::LensletArray s(o);
  state.counters["lenslets"] = s.lenslet_count();
  sag_gradient_walk(state, s, -7.0, -0.3, [](double& x, double&) {
    x += 0.000731;
    if (x > 7.0) x = -7.0;
  });
}
BENCHMARK(BM_CompoundEyeSagGradient);

void BM_Qbfs12SagGradient(benchmark::State& state) {
  std::vector<double> a(12);
  for (int m = 0; m < 12; ++m) a[m] = 1e-3 * std::cos(1.0 + m);
  sag_gradient_walk(state, freeturn::Qbfs(1 / 60.0, 10.0, a), -7.0, 2.0, step_x);
}
BENCHMARK(BM_Qbfs12SagGradient);

// A rational bicubic 20 × 20 freeform seen as z(x, y): each query inverts (x, y) → (u, v)
// by Newton from the previous query, as along a spiral (steps of 10 µm on a circle).
void BM_NurbsHeightFieldSagGradient(benchmark::State& state) {
  const freeturn::NurbsHeightField s(freeturn::test::freeform_with_pole());
  double phi = 0.1;
  sag_gradient_walk(state, s, 5.0 * std::cos(phi), 5.0 * std::sin(phi), [&](double& x, double& y) {
    phi += 0.002;
    if (phi > 4.5) phi = 0.1;
    x = 5.0 * std::cos(phi);
    y = 5.0 * std::sin(phi);
  });
}
BENCHMARK(BM_NurbsHeightFieldSagGradient);

}  // namespace

BENCHMARK_MAIN();
