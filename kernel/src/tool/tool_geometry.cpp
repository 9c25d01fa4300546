#include "freeturn/tool/tool_geometry.hpp"

#include <algorithm>

namespace freeturn {

double ToolGeometry::waviness_at(double psi) const {
  if (waviness.empty()) return 0.0;
  if (psi <= waviness.front().first) return waviness.front().second;
  if (psi >= waviness.back().first) return waviness.back().second;
  const auto hi = std::lower_bound(waviness.begin(), waviness.end(), psi,
                                   [](const auto& entry, double v) { return entry.first < v; });
  const auto lo = hi - 1;
  const double t = (psi - lo->first) / (hi->first - lo->first);
  return lo->second + t * (hi->second - lo->second);
}

}  // namespace freeturn
