#include "freeturn/io/xyz_points.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "freeturn/core/error.hpp"

namespace freeturn {

std::vector<Eigen::Vector3d> read_xyz_points(const std::string& path) {
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
    double v[3];
    const char* p = line.c_str();
    int count = 0;
    bool ok = true;
    while (true) {
      while (*p == ' ') ++p;
      if (*p == '\0') break;
      char* end = nullptr;
      const double x = std::strtod(p, &end);
      if (end == p || !(*end == ' ' || *end == '\0') || !std::isfinite(x) || count == 3) {
        ok = false;
        break;
      }
      v[count++] = x;
      p = end;
    }
    if (ok && count == 3) {
      points.emplace_back(v[0], v[1], v[2]);
      header_allowed = false;
      continue;
    }
    if (header_allowed && count == 0) {  // a header of column names
      header_allowed = false;
      continue;
    }
    throw InputError(SourceLocation{path, n, 0}, "expected three numbers x y z (mm)");
  }
  if (points.empty()) throw InputError(SourceLocation{path, n, 0}, "the file has no points");
  return points;
}

}  // namespace freeturn
