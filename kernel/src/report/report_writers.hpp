#pragma once
// The report's two texts, made from a run's report (report_files.hpp writes them).
// Internal to report/.

#include <string>

#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

// report.json, as docs/report.schema.json describes it: valid UTF-8 whatever the job's
// text holds (a byte that is not UTF-8 becomes U+FFFD).
std::string report_json(const RunReport& r);
// The warnings as report.json's `warnings` array.
std::string warnings_json(const std::vector<ReportWarning>& warnings);

// report.html: one page, no script, no file or network beside it. `design`: the surface as
// it is cut (the frame of the path), for the height map.
std::string report_html(const RunReport& r, const Surface& design);

}  // namespace freeturn::detail
