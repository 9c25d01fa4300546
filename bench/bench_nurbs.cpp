// NURBS kernel figures (issue: point + first derivatives ≤ 150 ns, warm inversion ≤ 1 µs,
// cold inversion ≤ 20 µs, warm ray intersection ≤ 1 µs, on one core).
// The surface is the tests' rational bicubic 20 × 20 freeform (a polar fan with a pole).
#include <benchmark/benchmark.h>

#include <random>

#include "freeturn/nurbs/surface_locator.hpp"
#include "freeturn/nurbs/surface_span_cache.hpp"
#include "nurbs/fixtures.hpp"

using freeturn::nurbs::SurfaceLocator;
using freeturn::nurbs::Vector3d;

namespace {

const freeturn::nurbs::NurbsSurface& surface() {
  static const auto s = freeturn::test::freeform_with_pole();
  return s;
}

// Points 0.2 mm off the surface along a spiral in parameter space, the way a tool path
// visits them: each is a small step from the one before.
struct PathPoint {
  double u, v;
  Vector3d p;
};
const std::vector<PathPoint>& path() {
  static const std::vector<PathPoint> pts = [] {
    std::vector<PathPoint> out;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      const double t = double(k) / n;
      const double u = 0.05 + 0.9 * t, v = 0.5 + 0.45 * std::sin(60 * t);
      out.push_back({u, v, surface().point(u, v) + 0.2 * surface().normal(u, v)});
    }
    return out;
  }();
  return pts;
}

}  // namespace

// S and its partials up to the argument's order along a walk over the domain, by
// `evaluate(u, v, order)`.
template <class Evaluate>
void walk(benchmark::State& state, Evaluate&& evaluate) {
  const int order = static_cast<int>(state.range(0));
  double u = 0.1, v = 0.2, sum = 0;
  for (auto _ : state) {
    const auto d = evaluate(u, v, order);
    sum += d.point.x() + d.su.y() + d.sv.z() + d.suu.y() + d.svv.z();
    u += 0.000123;
    v += 0.000321;
    if (u > 1) u -= 1;
    if (v > 1) v -= 1;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}

static void BM_SurfaceEvaluate(benchmark::State& state) {
  walk(state, [&](double u, double v, int order) { return surface().evaluate(u, v, order); });
}
// Argument: the derivative order (1: point and first partials, 2: with second partials).
BENCHMARK(BM_SurfaceEvaluate)->Arg(1)->Arg(2);

// The same walk through the span cache (nurbs/surface_span_cache.hpp): consecutive points
// stay in a span, whose power form is built once.
static void BM_SurfaceEvaluateSpanCache(benchmark::State& state) {
  freeturn::nurbs::SurfaceSpanCache cache(surface());
  walk(state, [&](double u, double v, int order) { return cache.evaluate(u, v, order); });
}
BENCHMARK(BM_SurfaceEvaluateSpanCache)->Arg(1)->Arg(2);

static void BM_InversionWarm(benchmark::State& state) {
  const SurfaceLocator locator(surface());
  const auto& pts = path();
  std::size_t k = 1;
  double u = pts[0].u, v = pts[0].v;
  for (auto _ : state) {
    const auto r = locator.closest_point(pts[k].p, u, v);
    u = r.u;
    v = r.v;
    benchmark::DoNotOptimize(r.distance);
    if (++k == pts.size()) {
      k = 1;
      u = pts[0].u;
      v = pts[0].v;
    }
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InversionWarm);

static void BM_InversionCold(benchmark::State& state) {
  const SurfaceLocator locator(surface());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0, 1), off(-1, 1);
  std::vector<Vector3d> queries;
  for (int k = 0; k < 1000; ++k)
    queries.push_back(surface().point(unit(rng), unit(rng)) +
                      Vector3d(off(rng), off(rng), off(rng)));
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(locator.closest_point(queries[k]).distance);
    k = (k + 1) % queries.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InversionCold);

static void BM_RayIntersectionWarm(benchmark::State& state) {
  const SurfaceLocator locator(surface());
  const auto& pts = path();
  // Rays along −normal from the offset points, as the planner projects base points.
  std::vector<Vector3d> dirs;
  for (const auto& p : pts) dirs.push_back(-surface().normal(p.u, p.v));
  std::size_t k = 1;
  double u = pts[0].u, v = pts[0].v;
  for (auto _ : state) {
    const auto h = locator.intersect_ray(pts[k].p, dirs[k], u, v);
    u = h.u;
    v = h.v;
    benchmark::DoNotOptimize(h.t);
    if (++k == pts.size()) {
      k = 1;
      u = pts[0].u;
      v = pts[0].v;
    }
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RayIntersectionWarm);

BENCHMARK_MAIN();
