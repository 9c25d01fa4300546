#pragma once
// <job>.report.json (every figure, for programs; docs/report.schema.json) and
// <job>.report.html (the same for a person, one self-contained page; docs/report.md),
// written from a run's report.

#include <string>
#include <vector>

#include "freeturn/io/output_set.hpp"
#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

// Writes both files into `outputs`, to be put in place with the rest of the run.
// The warnings as report.json writes them (its `warnings` array, one line): for programs
// that read the records without the file (the Python module).
std::string warnings_json(const std::vector<ReportWarning>& warnings);

// design: the surface as cut (the path's frame), for the page's height map.
void write_report(const RunReport& r, const Surface& design, const std::string& json_path,
                  const std::string& html_path, OutputSet& outputs);

}  // namespace freeturn
