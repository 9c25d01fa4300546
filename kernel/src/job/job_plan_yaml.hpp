#pragma once
// The run sections of a job (tool, strategy, cutting, machine, outputs). Internal to job.cpp.

#include "freeturn/job/job.hpp"
#include "freeturn/job/yaml_reader.hpp"

namespace freeturn::detail {

// Reads every run section of `job`; all of tool, strategy, cutting and machine must be
// present when any is. Returns nothing when none is. `design`: what the tool settings are
// judged against (a waviness on a creased design).
std::optional<JobPlan> read_job_plan(MapReader& job, const Aperture& aperture,
                                     const Surface& design);

}  // namespace freeturn::detail
