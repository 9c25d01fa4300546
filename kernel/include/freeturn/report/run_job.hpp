#pragma once
// A job run as the command line runs it: the pipeline (pipeline/run_pipeline.hpp) with
// the files the job's `outputs:` section asks for (report/job_files.hpp). Errors, the
// observer and the result are run_pipeline's.

#include "freeturn/pipeline/run_pipeline.hpp"

namespace freeturn {

// Plans, checks and posts the job, and writes its programs and files into
// options.output_dir, all put in place as one set when the whole job has succeeded.
RunResult run_job(const Job& job, const RunOptions& options = {}, RunObserver* observer = nullptr);

// run_job with the finishing pass also cut in simulation, its residual written and reported.
RunResult simulate_job(const Job& job, const SimulationOptions& simulation, RunOptions options = {},
                       RunObserver* observer = nullptr);

// An NC program, not the job's own, cut in simulation (run_program_simulation) with the
// job's residual and report files written into options.output_dir.
RunResult simulate_program(const Job& job, const std::string& program,
                           const SimulationOptions& simulation, RunOptions options = {});

}  // namespace freeturn
