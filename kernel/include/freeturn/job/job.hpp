#pragma once
// The job: what a user asks freeturn to do, read from YAML (docs/job-schema.md).
// The schema grows with the planner, tools and machines; unknown keys are errors.

#include <memory>
#include <string>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct Aperture {
  double outer_radius = 0;  // mm, > 0
  double inner_radius = 0;  // mm, 0 <= inner < outer
};

struct Job {
  std::string file;  // where it was read from
  std::string name;  // used in output file names: letters, digits, '-', '_', '.'
  Aperture aperture;
  std::unique_ptr<Surface> surface;
};

// Reads and validates a job file. Throws InputError ("file:line:col: what") on bad input.
Job load_job(const std::string& path);

}  // namespace freeturn
