// freeturn sample: the design surface over the aperture, as CSV.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "commands.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/io/surface_samples.hpp"
#include "freeturn/job/job.hpp"

namespace freeturn::cli {

int run_sample(const std::vector<std::string>& args) {
  std::string job_path, out_dir = ".";
  int grid = 201;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool has_value = i + 1 < args.size();
    if ((a == "-o" || a == "--output") && has_value) {
      out_dir = args[++i];
    } else if (a == "--grid" && has_value) {
      grid = static_cast<int>(option_integer("--grid", args[++i], 2, 20001, "an integer from 2 to 20001"));
    } else if (!a.empty() && a[0] != '-' && job_path.empty()) {
      job_path = a;
    } else {
      throw InputError("usage", "unexpected argument '" + a +
                                    "'; usage: freeturn sample JOB.yaml [-o DIR] [--grid N]");
    }
  }
  if (job_path.empty()) throw InputError("usage", "freeturn sample JOB.yaml [-o DIR] [--grid N]");

  const Job job = load_job(job_path, cli::yaml_byte_bound());
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw InputError(out_dir, "cannot create the output folder: " + ec.message());
  const std::string path = (std::filesystem::path(out_dir) / (job.name + ".surface.csv")).string();
  const SampleSummary s = write_surface_samples_csv(*job.surface, job.aperture.inner_radius,
                                                    job.aperture.outer_radius, grid, path);
  std::printf(
      "%s: %ld points of the %s surface, sag %.9g to %.9g mm (PV %.6g um), "
      "max slope %.4f deg\n",
      path.c_str(), s.points, job.surface->type(), s.z_min, s.z_max, (s.z_max - s.z_min) * 1e3,
      s.max_slope * 180.0 / std::numbers::pi);
  return kExitOk;
}

}  // namespace freeturn::cli
