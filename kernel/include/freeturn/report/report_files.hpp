#pragma once
// report.json (every figure, for programs) and report.html (the same for a person, with
// inline SVG plots and the residual as an image), written from a run's report.

#include <string>

#include "freeturn/io/output_set.hpp"
#include "freeturn/pipeline/run_report.hpp"

namespace freeturn {

// Writes both files into `outputs`, to be put in place with the rest of the run.
void write_report(const RunReport& r, const std::string& json_path, const std::string& html_path,
                  OutputSet& outputs);

}  // namespace freeturn
