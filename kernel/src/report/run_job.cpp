#include "freeturn/report/run_job.hpp"

#include "freeturn/report/job_files.hpp"

namespace freeturn {

RunResult run_job(const Job& job, const RunOptions& options, RunObserver* observer) {
  JobFiles files;
  return run_pipeline(job, options, files, observer);
}

RunResult simulate_job(const Job& job, const SimulationOptions& simulation, RunOptions options,
                       RunObserver* observer) {
  options.simulation = simulation;
  return run_job(job, options, observer);
}

RunResult simulate_program(const Job& job, const std::string& program,
                           const SimulationOptions& simulation, RunOptions options) {
  options.simulation = simulation;
  JobFiles files;
  return run_program_simulation(job, program, options, files);
}

}  // namespace freeturn
