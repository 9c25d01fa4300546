#include "freeturn/io/xyz_points.hpp"

#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/input_file.hpp"

namespace freeturn {
namespace {

// The next space-separated field of `rest`, removed from it; empty at the end.
std::string_view next_field(std::string_view& rest) {
  const std::size_t start = rest.find_first_not_of(' ');
  if (start == std::string_view::npos) return {};
  rest.remove_prefix(start);
  const std::string_view field = rest.substr(0, rest.find(' '));
  rest.remove_prefix(field.size());
  return field;
}

// The 1-based column where `field`, a view into `line`, starts.
int column_of(const std::string& line, std::string_view field) {
  return static_cast<int>(field.data() - line.data()) + 1;
}

}  // namespace


std::vector<Eigen::Vector3d> read_xyz_points(const std::string& path) {
  require_regular_file(path, "a point file (x y z a line)");
  std::ifstream in(path);
  if (!in) throw InputError(SourceLocation{path, 0, 0}, "cannot open the point file");
  std::vector<Eigen::Vector3d> points;
  std::string line;
  int n = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++n;
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    for (char& ch : line)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    if (line.find_first_not_of(' ') == std::string::npos) continue;
    // Fields parsed whole with from_chars (core/number_text.hpp): locale-free, and a NUL or
    // any other stray byte makes the line an error instead of ending it early.
    double v[3];
    int count = 0;
    bool ok = true;
    std::string_view bad;  // the field that ended the row, if one did
    std::string_view rest(line);
    for (std::string_view field = next_field(rest); !field.empty(); field = next_field(rest)) {
      double x;
      // NaN or infinity is a number that is not finite, not a column name: a first row of
      // them must not pass for a header and vanish.
      if (parse_number(field, x) && !std::isfinite(x))
        throw InputError(SourceLocation{path, n, column_of(line, field)},
                         "'" + std::string(field) + "' is not a finite number (x y z in mm)");
      if (count == 3 || !parse_finite(field, x)) {
        ok = false;
        bad = field;
        break;
      }
      v[count++] = x;
    }
    if (ok && count == 3) {
      points.emplace_back(v[0], v[1], v[2]);
      header_allowed = false;
      continue;
    }
    if (header_allowed && count == 0) {  // a header of column names, none a number
      std::string_view fields(line);
      for (std::string_view field = next_field(fields); !field.empty(); field = next_field(fields)) {
        double x;
        if (parse_number(field, x))
          throw InputError(SourceLocation{path, n, column_of(line, field)},
                           "'" + std::string(field) +
                               "' is not a finite number, and a header "
                               "row names the columns: a row of points has three finite numbers");
      }
      header_allowed = false;
      continue;
    }
    if (bad.empty())
      throw InputError(SourceLocation{path, n, 1},
                       "expected three numbers x y z (mm); the line holds " +
                           std::to_string(count) + (count == 1 ? " number" : " numbers"));
    throw InputError(SourceLocation{path, n, column_of(line, bad)},
                     count == 3 ? "expected three numbers x y z (mm); '" + std::string(bad) +
                                      "' is a fourth field"
                                : "expected three numbers x y z (mm); '" + std::string(bad) +
                                      "' is not a finite number");
  }
  if (points.empty()) throw InputError(SourceLocation{path, 0, 0}, "the file has no points");
  return points;
}

}  // namespace freeturn
