// The base surface fit alone (paper 000, §4), as the example jobs ask for it: wall time per
// fit and the α_max it reaches (degrees), so that a faster solver
// can be seen to reach the same optimum (in the label). Arguments: the job (0 the demo's compound eye,
// minimax about z; 1 the same with the axis searched; 2 the off-axis parabola segment,
// minimax with the axis searched).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <numbers>
#include <string>

#include "freeturn/job/job.hpp"
#include "freeturn/path/base_plan.hpp"

namespace {

const char* const kJobs[] = {"compound_eye", "compound_eye", "oap_segment"};

void BM_BaseFit(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const freeturn::Job job =
      freeturn::load_job(std::string(FREETURN_SOURCE_DIR) + "/configs/jobs/" + kJobs[which] + ".yaml");
  freeturn::BasePlanOptions o = job.plan->strategy.base;
  o.kind = freeturn::BaseKind::kMinimax;
  o.search_axis = which > 0;
  o.angle_limit = 0;
  double alpha = 0;
  for (auto _ : state) {
    const freeturn::BasePlan plan = freeturn::plan_base_surface(
        *job.surface, job.aperture.inner_radius, job.aperture.outer_radius, o);
    alpha = plan.quasi_revolution.max_angle;
  }
  char text[96];
  std::snprintf(text, sizeof text, "%s%s alpha_max %.4f deg", kJobs[which],
                o.search_axis ? " +axis" : "", alpha * 180 / std::numbers::pi);
  state.SetLabel(text);
}
BENCHMARK(BM_BaseFit)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
