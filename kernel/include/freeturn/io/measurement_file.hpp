#pragma once
// A measured surface read from an instrument's export (docs/metrology.md): points in mm,
// the invalid ones (dropouts, NaN, the format's no-data marker) masked out and counted,
// never read as zero.
//
// Formats:
//   zygo_xyz  Zygo's ASCII XYZ export (MetroPro / Mx "XYZ Data File"): 14 header lines,
//             a line "#", then one line per pixel "x y z" (x, y the pixel's column and row,
//             z the height) or "x y No Data", then "#". Lateral = index × the header's
//             camera resolution (line 8, 7th field, metres per pixel); z in `height_unit`
//             (µm unless the job says otherwise). The pixel count must be the header's
//             phase width × height (line 4).
//   xyz, csv  x y z per line (white space; commas or semicolons for csv), an optional
//             header line of names, '#' comments; "nan", "NaN" or an empty field marks an
//             invalid point.
//   grid      a height grid as CSV: the first row is the x of each column (its first cell
//             empty or a label), each following row a y and one z per column; an empty or
//             "nan" cell is invalid.
//   profile   a stylus profile, x z per line (y = 0): for rotationally symmetric parts.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace freeturn {

enum class MeasurementFormat { kZygoXyz, kXyz, kCsv, kGrid, kProfile };

struct MeasurementFileOptions {
  MeasurementFormat format = MeasurementFormat::kXyz;
  double lateral_scale = 1;  // mm per file unit of x and y (not for zygo_xyz: its header says)
  double height_scale = 1;   // mm per file unit of z
};

struct Measurement {
  std::vector<Eigen::Vector3d> points;  // the valid points (mm)
  long invalid = 0;                     // points marked invalid in the file
  bool profile = false;                 // a 2-D profile (every y = 0)
};

// Throws InputError at "file:line" (and column where it helps) for what the format does
// not allow: a truncated or inconsistent header, a line that is not the format's, a file
// with no valid point.
Measurement read_measurement(const std::string& path, const MeasurementFileOptions& options);

// The scale to mm of a unit name ("mm", "um", "µm", "nm", "m"); false for any other.
bool length_unit_scale(const std::string& unit, double& mm_per_unit);

}  // namespace freeturn
