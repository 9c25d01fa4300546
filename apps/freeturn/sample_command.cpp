// freeturn sample: the design surface over the aperture, as CSV.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "commands.hpp"
#include "freeturn/freeturn.hpp"
#include "freeturn/io/surface_samples.hpp"

namespace freeturn::cli {

int run_sample(const SampleArgs& args) {
  const Job job = load_job(args.job, yaml_byte_bound());
  std::error_code ec;
  std::filesystem::create_directories(args.output, ec);
  if (ec) throw InputError(args.output, "cannot create the output folder: " + ec.message());
  const std::string path = (std::filesystem::path(args.output) / (job.name + ".surface.csv")).string();
  SampleSummary s;
  try {
    s = write_surface_samples_csv(*job.surface, job.aperture.inner_radius,
                                  job.aperture.outer_radius, args.grid, path,
                                  job.plan ? job.plan->limits.max_file_mb : Limits{}.max_file_mb);
  } catch (const InputError& e) {
    // The file's bound is the job's (its `limits:`, or the job itself where it gives none).
    if (e.where() != "limits.max_file_mb") throw;
    throw InputError(job.place(e.where()), e.where() + ": " + e.problem());
  }
  if (!args.quiet)
    std::printf(
      "%s: %ld points of the %s surface, sag %.9g to %.9g mm (PV %.6g um), "
      "max slope %.4f deg\n",
      path.c_str(), s.points, job.surface->type(), s.z_min, s.z_max, (s.z_max - s.z_min) * 1e3,
      s.max_slope * 180.0 / std::numbers::pi);
  return kExitOk;
}

}  // namespace freeturn::cli
