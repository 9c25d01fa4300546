#pragma once
// The CL data as CSV: one row per cutter location of the finishing pass, in path order,
// with the machine block made of it.
//
// Columns (kClColumns), each named with its unit: theta_rad (the path's angle, counting
// turns), x_mm y_mm z_mm (contact point), nx ny nz (surface normal), tx_mm ty_mm tz_mm
// (nose centre), b_deg (tool tilt), X_mm Z_mm C_deg B_deg as programmed, chord_mm (the
// predicted chord error of the segment ending at the row).
// Numbers are the shortest text that reads back as the same double (std::to_chars), so
// the CL data can be checked to the nanometre and no locale changes a byte.

#include <array>
#include <span>

#include "freeturn/io/atomic_file.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

inline constexpr std::array<const char*, 16> kClColumns = {
    "theta_rad", "x_mm",  "y_mm",  "z_mm", "nx",   "ny",    "nz",    "tx_mm",
    "ty_mm",     "tz_mm", "b_deg", "X_mm", "Z_mm", "C_deg", "B_deg", "chord_mm"};

// One row's values, in kClColumns' order.
std::array<double, 16> cl_values(const CutterLocation& location, const AxisRecord& record);

class ClFile {
 public:
  // Writes the header into `out`. Past max_bytes (limits.max_file_mb) a row throws
  // InputError at "limits.max_file_mb".
  ClFile(AtomicFile& out, double max_bytes);

  // locations[k] with records[k]; the spans have one length.
  void write(std::span<const CutterLocation> locations, std::span<const AxisRecord> records);

 private:
  AtomicFile& out_;
  double max_bytes_;
  double bytes_ = 0;
  std::string line_;  // reused: no allocation per row
};

}  // namespace freeturn
