#pragma once
// The files freeturn writes for a job beside its NC programs, as the job's `outputs:`
// section asks (docs/job-schema.md):
//   <job>.cl.csv            the finishing pass's CL data (cl_csv: true; report/cl_file.hpp)
//   <job>.residual.csv/.ply the simulated residual (when the run simulates; verify/)
//   <job>.surface.obj, <job>.path.vtk  the design and the path as meshes (mesh: true)
//   <job>.report.json, <job>.report.html  the report (report: true; report/report_files.hpp)

#include <memory>

#include "freeturn/pipeline/run_files.hpp"
#include "freeturn/report/cl_file.hpp"

namespace freeturn {

class JobFiles final : public RunFiles {
 public:
  void begin_finishing_pass(const Job& job, const std::string& folder, OutputSet& outputs) override;
  void finishing_chunk(std::span<const CutterLocation> locations,
                       std::span<const AxisRecord> records) override;
  void finish(const Job& job, const RunReport& report, const Surface& design,
              const std::string& folder, OutputSet& outputs) override;

 private:
  std::unique_ptr<ClFile> cl_;
};

}  // namespace freeturn
