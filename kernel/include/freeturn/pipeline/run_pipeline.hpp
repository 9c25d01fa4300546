#pragma once
// A job run end to end (docs/conventions.md, "Layout"). run_pipeline writes the NC
// programs and hands the rest to a RunFiles (pipeline/run_files.hpp); freeturn::run_job
// (report/run_job.hpp) is this with the files the command line writes.
//
// The pipeline streams: planner → tool compensation and checks → machine axes and limits
// → post-processor plugin, chunk by chunk. Each pass (roughing passes, then the finish)
// is its own program; every output is written under a temporary name and put in place
// only when the whole job has succeeded, all as one set (io/output_set.hpp), so a job
// that fails midway leaves nothing.
//
// Errors are exceptions: InputError for bad input (the job, the machine, the plugin, a
// limit), at the file:line:col of the setting that causes it; CheckFailure for a check
// the job sets to error (nothing written). A program that is written but not safe to cut
// (a check downgraded to a warning found something) comes back with its reasons in
// RunReport::unsafe. Nothing is printed: progress and warnings go to the observer.
//
// A post-processor plugin that crashes or hangs cannot be unwound from: the process ends
// through the handler set with set_plugin_fault_handler (post/plugin_watch.hpp, included
// here for the embedder to choose it).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "freeturn/job/job.hpp"
#include "freeturn/job/yaml_limits.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/pipeline/run_files.hpp"
#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/post/plugin_watch.hpp"
#include "freeturn/tool/cutter_location.hpp"
#include "freeturn/verify/cut_simulation.hpp"

namespace freeturn {

struct RunOptions {
  std::string output_dir = ".";
  // Also cut the finishing pass in simulation (verify/cut_simulation.hpp) and write its
  // residual (grid CSV, coloured PLY) with its figures in the report.
  std::optional<SimulationOptions> simulation;
  std::uintmax_t max_yaml_bytes = kMaxYamlBytes;  // the machine file's size bound
  // Threads that plan the spiral (0: the hardware's; at most kMaxThreads, else an
  // InputError). Every output is the same on any number; the simulation has its own
  // (SimulationOptions::threads).
  int threads = 0;
  // A constant-rpm spiral is planned once to find the highest speed its blocks allow, then
  // written at that speed. The plan does not depend on the speed, so the first run's path
  // is kept in a temporary file, up to this many bytes (120 B a point), and sent again
  // instead of planned again; a longer path is planned twice. The outputs are the same
  // bytes either way.
  std::uintmax_t max_replay_bytes = std::uintmax_t{1} << 30;
};

// What a run tells its caller while it works, on the calling thread. The defaults ignore it.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void warning(const std::string& text) { (void)text; }
  // Once per chunk of a pass: the contact's θ (rad) and r (mm) reached, points so far.
  virtual void progress(const std::string& pass, double theta, double r, long points) {
    (void)pass, (void)theta, (void)r, (void)points;
  }
  virtual void pass_done(const std::string& pass) { (void)pass; }
  // Each chunk of a pass's cutter locations with the machine blocks made of them (one
  // record per location, in path order), as they stream: the CL data without a file.
  virtual void cutter_locations(const std::string& pass, std::span<const CutterLocation> locations,
                                std::span<const AxisRecord> records) {
    (void)pass, (void)locations, (void)records;
  }
};

struct RunResult {
  RunReport report;                // figures, verdict, worst places
  std::vector<std::string> files;  // the paths written, in the order they were put in place
  bool safe() const { return report.safe(); }
};

// Plans, checks and posts the job, and writes its programs and `files` into
// options.output_dir.
RunResult run_pipeline(const Job& job, const RunOptions& options, RunFiles& files,
                       RunObserver* observer = nullptr);

// Everything run_pipeline does but writing: the report's figures and verdict. The plugin reads
// its settings and takes one block at the clearance height, so settings and an approach
// run_pipeline would refuse are refused here too.
RunReport check_job(const Job& job, const RunOptions& options = {}, RunObserver* observer = nullptr);

// The finishing pass's cutter locations and machine blocks, planned and checked as
// check_job does, without writing: the CL file's rows in memory.
struct PlannedPath {
  std::vector<CutterLocation> locations;
  std::vector<AxisRecord> records;
};
// Cuts, in simulation, an NC program written for the job's machine, by freeturn or by
// another CAM (`freeturn simulate JOB --program FILE`): its blocks (and the child files it
// calls) read back through the machine's axis layout (sign, offset, C wrapped), the nose
// the job's tool, its programmed point what the job's compensation says it is. The grid is
// options.simulation's (defaults as for the job's own), the whole lower arc of the nose
// swept. Writes the residual and the report through `files`, as `simulate` does; nothing
// is planned and no program is written. Throws InputError at the program's file:line.
RunResult run_program_simulation(const Job& job, const std::string& program,
                                 const RunOptions& options, RunFiles& files);

PlannedPath plan_job(const Job& job, const RunOptions& options = {});

}  // namespace freeturn
