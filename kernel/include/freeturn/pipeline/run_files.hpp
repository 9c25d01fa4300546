#pragma once
// The files a run writes beside its NC programs (the CL data, the report, the residual,
// meshes), supplied by the layer above the pipeline (report/job_files.hpp). The pipeline
// plans, checks and posts; what else becomes a file, and in what format, is not its rule.
//
// Every file goes into the run's OutputSet, put in place with the programs only when the
// whole job has succeeded (io/output_set.hpp). A writer that throws (InputError at a
// limit's key, say) stops the run and nothing is left behind.

#include <span>
#include <string>

#include "freeturn/io/output_set.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

class RunFiles {
 public:
  virtual ~RunFiles() = default;
  // Before the finishing pass is planned: the files that stream with it are opened in
  // `outputs`, under `folder`.
  virtual void begin_finishing_pass(const Job& job, const std::string& folder,
                                    OutputSet& outputs) {
    (void)job, (void)folder, (void)outputs;
  }
  // Each chunk of the finishing pass, in path order: one axis record per cutter location.
  virtual void finishing_chunk(std::span<const CutterLocation> locations,
                               std::span<const AxisRecord> records) {
    (void)locations, (void)records;
  }
  // After every pass succeeded: the files made from the whole run. `design` is the
  // surface cut, in the frame the program is written in.
  virtual void finish(const Job& job, const RunReport& report, const Surface& design,
                      const std::string& folder, OutputSet& outputs) {
    (void)job, (void)report, (void)design, (void)folder, (void)outputs;
  }
};

}  // namespace freeturn
