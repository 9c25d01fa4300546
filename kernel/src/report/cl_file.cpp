#include "freeturn/report/cl_file.hpp"

#include <charconv>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"

namespace freeturn {

std::array<double, 16> cl_values(const CutterLocation& cl, const AxisRecord& r) {
  return {cl.contact.theta,
          cl.contact.point.x(),
          cl.contact.point.y(),
          cl.contact.point.z(),
          cl.contact.normal.x(),
          cl.contact.normal.y(),
          cl.contact.normal.z(),
          cl.nose_centre.x(),
          cl.nose_centre.y(),
          cl.nose_centre.z(),
          cl.b * 180 / std::numbers::pi,
          r.x,
          r.z,
          r.c,
          r.b,
          cl.contact.chord_error};
}

ClFile::ClFile(AtomicFile& out, double max_bytes) : out_(out), max_bytes_(max_bytes) {
  line_.clear();
  for (const char* name : kClColumns) line_ += std::string(line_.empty() ? "" : ",") + name;
  line_ += '\n';
  bytes_ = static_cast<double>(line_.size());
  out_.write(line_);
}

void ClFile::write(std::span<const CutterLocation> locations, std::span<const AxisRecord> records) {
  for (std::size_t k = 0; k < records.size(); ++k) {
    const std::array<double, 16> values = cl_values(locations[k], records[k]);
    // Shortest round-trip text: nine fixed decimals would put θ alone 2.5 nm off at r = 5 mm.
    line_.clear();
    for (int i = 0; i < 16; ++i) {
      if (i) line_ += ',';
      char buf[32];
      const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, values[i]);
      line_.append(buf, ec == std::errc() ? end : buf);
    }
    line_ += '\n';
    bytes_ += static_cast<double>(line_.size());
    if (bytes_ > max_bytes_)
      throw InputError("limits.max_file_mb",
                       "the CL file would be larger than limits.max_file_mb = " +
                           std::to_string(max_bytes_ / 1048576.0) + " MB; nothing was written");
    out_.write(line_);
  }
}

}  // namespace freeturn
