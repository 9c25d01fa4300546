#include "freeturn/report/report_files.hpp"

#include "freeturn/io/atomic_file.hpp"
#include "report_writers.hpp"

namespace freeturn {

std::string warnings_json(const std::vector<ReportWarning>& warnings) {
  return detail::warnings_json(warnings);
}

void write_report(const RunReport& r, const Surface& design, const std::string& json_path,
                  const std::string& html_path, OutputSet& outputs) {
  outputs.add(json_path).write(detail::report_json(r));
  outputs.add(html_path).write(detail::report_html(r, design));
}

}  // namespace freeturn
