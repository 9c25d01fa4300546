#include "freeturn/report/job_files.hpp"

#include <filesystem>
#include <vector>

#include "freeturn/io/mesh_export.hpp"
#include "freeturn/report/report_files.hpp"
#include "freeturn/verify/residual_output.hpp"

namespace freeturn {
namespace {

std::string in_folder(const std::string& folder, const std::string& name) {
  return (std::filesystem::path(folder) / name).string();
}

}  // namespace

void JobFiles::begin_finishing_pass(const Job& job, const std::string& folder, OutputSet& outputs) {
  cl_.reset();
  if (!job.plan->outputs.cl_csv) return;
  cl_ = std::make_unique<ClFile>(outputs.add(in_folder(folder, job.name + ".cl.csv")),
                                 job.plan->limits.max_file_mb * 1048576.0);
}

void JobFiles::finishing_chunk(std::span<const CutterLocation> locations,
                               std::span<const AxisRecord> records) {
  if (cl_) cl_->write(locations, records);
}

void JobFiles::finish(const Job& job, const RunReport& report, const Surface& design,
                      const std::string& folder, OutputSet& outputs) {
  const double inner = job.aperture.inner_radius;
  if (report.simulated) {
    write_residual_csv(*report.simulation, inner,
                       outputs.add(in_folder(folder, job.name + ".residual.csv")));
    write_residual_ply(*report.simulation, design, inner,
                       outputs.add(in_folder(folder, job.name + ".residual.ply")));
  }
  if (job.plan->outputs.mesh) {
    write_surface_mesh_obj(design, inner, job.aperture.outer_radius, 64, 256,
                           outputs.add(in_folder(folder, job.name + ".surface.obj")));
    std::vector<Eigen::Vector3d> path;
    for (const PlotPoint& p : report.passes.back().samples) path.emplace_back(p.x, p.y, p.z);
    write_polyline_vtk(path, outputs.add(in_folder(folder, job.name + ".path.vtk")));
  }
  if (job.plan->outputs.report)
    write_report(report, design, in_folder(folder, job.name + ".report.json"),
                 in_folder(folder, job.name + ".report.html"), outputs);
}

}  // namespace freeturn
