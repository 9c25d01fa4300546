// Runs a freeturn job from C++: the NC programs, CL data and report the command line
// would write, with the verdict and figures from the result rather than from stdout.
// usage: run_job JOB.yaml OUT_DIR
#include <cstdio>

#include <freeturn/freeturn.hpp>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: run_job JOB.yaml OUT_DIR\n");
    return 2;
  }
  try {
    const freeturn::Job job = freeturn::load_job(argv[1]);
    freeturn::RunOptions options;
    options.output_dir = argv[2];
    const freeturn::RunResult result = freeturn::run_job(job, options);
    const freeturn::PassFigures& finish = result.report.passes.back();
    std::printf("%s: %ld points, chord error max %.3f nm, cycle %.1f s, %s\n", job.name.c_str(),
                finish.points, finish.chord_max * 1e6, finish.cycle_time,
                result.safe() ? "PASS" : "UNSAFE");
    for (const std::string& file : result.files) std::printf("  %s\n", file.c_str());
    return result.safe() ? 0 : 1;
  } catch (const freeturn::CheckFailure& e) {
    std::fprintf(stderr, "FAIL: %s\n", e.what());
    return 1;
  } catch (const freeturn::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
