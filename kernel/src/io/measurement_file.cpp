#include "freeturn/io/measurement_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <string>
#include <string_view>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/input_file.hpp"

namespace freeturn {
namespace {

// The fields of a line split at any of `separators`; empty fields kept when `keep_empty`.
std::vector<std::string_view> split(std::string_view line, std::string_view separators,
                                    bool keep_empty) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find_first_of(separators, start);
    const std::string_view field = line.substr(start, end == std::string_view::npos ? end : end - start);
    if (keep_empty || !field.empty()) fields.push_back(field);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return fields;
}

std::string_view trim(std::string_view s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string_view::npos) return {};
  const std::size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// An invalid-point marker: "nan" in any case, or nothing.
bool is_invalid_marker(std::string_view field) {
  field = trim(field);
  if (field.empty()) return true;
  if (field.size() != 3) return false;
  const auto lower = [](char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c); };
  return lower(field[0]) == 'n' && lower(field[1]) == 'a' && lower(field[2]) == 'n';
}

// An error at `column` (1-based, in bytes) of line `line`; column 0 where the whole file is
// meant (line 0 too).
[[noreturn]] void fail(const std::string& path, int line, int column, const std::string& what) {
  throw InputError(SourceLocation{path, line, line > 0 ? std::max(column, 1) : 0}, what);
}

// The 1-based column where `field` (a view into `line`) starts, after its leading blanks.
int column_of(std::string_view line, std::string_view field) {
  const std::size_t blanks = std::min(field.find_first_not_of(" \t\r"), field.size());
  return static_cast<int>(field.data() - line.data() + static_cast<std::ptrdiff_t>(blanks)) + 1;
}

// `field` (a view into `line`, line number `n`) as a finite number, or an error at its column.
double field_number(const std::string& path, int n, std::string_view line, std::string_view field,
                    const char* what) {
  double v;
  if (!parse_finite(trim(field), v))
    fail(path, n, column_of(line, field),
         std::string(what) + " '" + std::string(trim(field)) + "' is not a finite number");
  return v;
}

// Lines of a text file, '\r' removed.
std::vector<std::string> read_lines(const std::string& path) {
  require_regular_file(path, "the measurement's data file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0, 0}, "cannot open the measurement file");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

Measurement read_zygo_xyz(const std::string& path, double height_scale) {
  const std::vector<std::string> lines = read_lines(path);
  constexpr int kHeaderLines = 14;
  if (lines.empty()) fail(path, 0, 0, "the measurement file is empty");
  if (lines.size() < kHeaderLines + 1)
    fail(path, static_cast<int>(lines.size()), 1,
         "the Zygo XYZ header is truncated: the format's header is 14 lines and a '#' line, and "
         "the file ends after " +
             std::to_string(lines.size()) + (lines.size() == 1 ? " line" : " lines"));
  if (lines[0].rfind("Zygo", 0) != 0)
    fail(path, 1, 1, "not a Zygo XYZ file: the first line must start with 'Zygo'");
  // Line 4: phase origin x, origin y, width, height.
  const std::vector<std::string_view> phase = split(lines[3], " \t", false);
  if (phase.size() != 4) fail(path, 4, 1, "the phase origin and size line must hold 4 numbers");
  const double width = field_number(path, 4, lines[3], phase[2], "the phase width");
  const double height = field_number(path, 4, lines[3], phase[3], "the phase height");
  const double origin_x = field_number(path, 4, lines[3], phase[0], "the phase origin x");
  const double origin_y = field_number(path, 4, lines[3], phase[1], "the phase origin y");
  if (!(width >= 1 && height >= 1 && width == std::floor(width) && height == std::floor(height)))
    fail(path, 4, column_of(lines[3], phase[2]),
         "the phase width and height must be whole numbers of at least 1");
  // Line 8: source, scale factor, wavelength, NA, obliquity, magnification, camera
  // resolution (m per pixel), time stamp.
  const std::vector<std::string_view> optics = split(lines[7], " \t", false);
  if (optics.size() != 8) fail(path, 8, 1, "the optics line must hold 8 numbers");
  const double resolution = field_number(path, 8, lines[7], optics[6], "the camera resolution");
  if (!(resolution > 0))
    fail(path, 8, column_of(lines[7], optics[6]),
         "the camera resolution must be greater than 0 (metres per pixel)");
  if (trim(lines[kHeaderLines]) != "#")
    fail(path, kHeaderLines + 1, 1, "the header must end with a line '#' after its 14 lines");
  const double lateral = resolution * 1000;  // mm per pixel
  Measurement m;
  const long expected = static_cast<long>(width) * static_cast<long>(height);
  long count = 0;
  std::size_t i = kHeaderLines + 1;
  for (; i < lines.size(); ++i) {
    const int n = static_cast<int>(i) + 1;
    const std::string_view line = trim(lines[i]);
    if (line == "#") break;
    if (line.empty())
      fail(path, n, 1, "an empty line inside the data (a pixel is 'x y z' or 'x y No Data')");
    const std::vector<std::string_view> f = split(line, " \t", false);
    const bool no_data = f.size() == 4 && f[2] == "No" && f[3] == "Data";
    if (f.size() != 3 && !no_data) fail(path, n, 1, "a pixel line is 'x y z' or 'x y No Data'");
    const double x = field_number(path, n, lines[i], f[0], "the pixel column");
    const double y = field_number(path, n, lines[i], f[1], "the pixel row");
    if (x < origin_x || x >= origin_x + width || y < origin_y || y >= origin_y + height ||
        x != std::floor(x) || y != std::floor(y))
      fail(path, n, column_of(lines[i], f[0]),
           "pixel (" + shortest_text(x) + ", " + shortest_text(y) +
               ") is outside the header's phase area (line 4)");
    ++count;
    if (no_data) {
      ++m.invalid;
      continue;
    }
    const double z = field_number(path, n, lines[i], f[2], "the height");
    m.points.emplace_back(x * lateral, y * lateral, z * height_scale);
  }
  if (count != expected)
    fail(path, static_cast<int>(std::min(i + 1, lines.size())), 1,
         "the file holds " + std::to_string(count) + " pixels, the header (line 4) says " +
             shortest_text(width) + " × " + shortest_text(height) + " = " +
             std::to_string(expected) + (count < expected ? ": truncated" : ""));
  return m;
}

Measurement read_points(const std::string& path, const MeasurementFileOptions& o) {
  const std::vector<std::string> lines = read_lines(path);
  const bool profile = o.format == MeasurementFormat::kProfile;
  const std::size_t columns = profile ? 2 : 3;
  const std::string_view separators = o.format == MeasurementFormat::kCsv ? ",;" : " \t,;";
  const bool keep_empty = o.format == MeasurementFormat::kCsv;
  Measurement m;
  m.profile = profile;
  bool header_allowed = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int n = static_cast<int>(i) + 1;
    std::string_view line = lines[i];
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    if (trim(line).empty()) continue;
    const std::vector<std::string_view> f = split(trim(line), separators, keep_empty);
    double v[3] = {0, 0, 0};
    bool invalid = false;
    std::size_t not_number = columns;  // the first field that is not a finite number
    for (std::size_t k = 0; f.size() == columns && k < columns; ++k) {
      if (k + 1 == columns && is_invalid_marker(f[k])) {
        invalid = true;
      } else if (!parse_finite(trim(f[k]), v[k])) {
        not_number = k;
        break;
      }
    }
    if (f.size() != columns || not_number < columns) {
      // One line of column names may open the file.
      if (header_allowed && f.size() == columns) {
        header_allowed = false;
        continue;
      }
      const std::string point = std::string("a point is ") + (profile ? "'x z'" : "'x y z'") +
                                " (finite numbers; 'nan' or an empty field marks an invalid one)";
      if (f.size() > columns)
        fail(path, n, column_of(lines[i], f[columns]),
             point + ": field " + std::to_string(columns + 1) + " is one too many");
      if (f.size() < columns)
        fail(path, n, 1,
             point + ": the line holds " + std::to_string(f.size()) + " field" +
                 (f.size() == 1 ? "" : "s"));
      fail(path, n, column_of(lines[i], f[not_number]),
           point + ": '" + std::string(trim(f[not_number])) + "' is not a finite number");
    }
    header_allowed = false;
    if (invalid) {
      ++m.invalid;
      continue;
    }
    if (profile)
      m.points.emplace_back(v[0] * o.lateral_scale, 0.0, v[1] * o.height_scale);
    else
      m.points.emplace_back(v[0] * o.lateral_scale, v[1] * o.lateral_scale, v[2] * o.height_scale);
  }
  return m;
}

Measurement read_grid(const std::string& path, const MeasurementFileOptions& o) {
  const std::vector<std::string> lines = read_lines(path);
  std::size_t first = 0;
  while (first < lines.size() && trim(lines[first]).empty()) ++first;
  if (first == lines.size()) fail(path, 0, 0, "the grid file is empty");
  const std::vector<std::string_view> head = split(lines[first], ",;", true);
  if (head.size() < 2)
    fail(path, static_cast<int>(first) + 1, 1,
         "the first row must hold the x of each column after one empty cell");
  std::vector<double> xs;
  for (std::size_t k = 1; k < head.size(); ++k)
    xs.push_back(
        field_number(path, static_cast<int>(first) + 1, lines[first], head[k], "the column's x"));
  Measurement m;
  for (std::size_t i = first + 1; i < lines.size(); ++i) {
    const int n = static_cast<int>(i) + 1;
    if (trim(lines[i]).empty()) continue;
    const std::vector<std::string_view> f = split(lines[i], ",;", true);
    if (f.size() != head.size())
      fail(path, n, 1,
           "the row has " + std::to_string(f.size()) + " cells, the first row " +
               std::to_string(head.size()) + " (a y and one z per column)");
    const double y = field_number(path, n, lines[i], f[0], "the row's y");
    for (std::size_t k = 1; k < f.size(); ++k) {
      if (is_invalid_marker(f[k])) {
        ++m.invalid;
        continue;
      }
      const double z = field_number(path, n, lines[i], f[k], "the height");
      m.points.emplace_back(xs[k - 1] * o.lateral_scale, y * o.lateral_scale, z * o.height_scale);
    }
  }
  return m;
}

}  // namespace

bool length_unit_scale(const std::string& unit, double& mm_per_unit) {
  if (unit == "mm") mm_per_unit = 1;
  else if (unit == "um" || unit == "µm") mm_per_unit = 1e-3;
  else if (unit == "nm") mm_per_unit = 1e-6;
  else if (unit == "m") mm_per_unit = 1e3;
  else return false;
  return true;
}

Measurement read_measurement(const std::string& path, const MeasurementFileOptions& o) {
  Measurement m;
  switch (o.format) {
    case MeasurementFormat::kZygoXyz: m = read_zygo_xyz(path, o.height_scale); break;
    case MeasurementFormat::kGrid: m = read_grid(path, o); break;
    default: m = read_points(path, o);
  }
  if (m.points.empty())
    throw InputError(SourceLocation{path, 0, 0},
                     "the measurement holds no valid point (" + std::to_string(m.invalid) +
                         " marked invalid)");
  return m;
}

}  // namespace freeturn
