#pragma once
// The CL data as CSV: one row per cutter location of the finishing pass, in path order,
// with the machine block made of it.
//
// Columns: theta (rad), x y z (contact point, mm), nx ny nz (surface normal), tx ty tz
// (nose centre, mm), b_deg (tool tilt), X Z (mm) C B (deg) as programmed, chord (mm).
// Numbers are the shortest text that reads back as the same double (std::to_chars), so
// the CL data can be checked to the nanometre and no locale changes a byte.

#include <span>

#include "freeturn/io/atomic_file.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

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
