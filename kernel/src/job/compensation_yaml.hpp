#pragma once
// The job's `compensation:` section (docs/metrology.md): one measured part, or a list of
// them, each read (io/measurement_file.hpp), registered to the design and its error
// fitted (metrology/registration.hpp). Internal to job/.

#include <memory>
#include <vector>

#include "freeturn/job/job.hpp"
#include "freeturn/job/yaml_reader.hpp"

namespace freeturn::detail {

// The design corrected by every measured part, and the parts in `parts`. Throws InputError
// at the key (or the measurement file's line) that is wrong.
std::unique_ptr<Surface> read_compensation(const YAML::Node& node, const std::string& job_file,
                                           std::unique_ptr<Surface> design, const Aperture& aperture,
                                           std::vector<MeasuredPart>& parts);

}  // namespace freeturn::detail
