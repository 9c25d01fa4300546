#include "freeturn/tool/tool_geometry.hpp"

#include <algorithm>
#include <cmath>

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

double ToolGeometry::waviness_span() const {
  if (waviness.empty()) return 0.0;
  const double half = 0.5 * included_angle;
  const bool bounded = half > 0;
  // δ is piecewise linear: its extremes over [−half, half] lie at the table's angles
  // inside it or at the ends.
  double lo = bounded ? std::min(waviness_at(-half), waviness_at(half)) : waviness.front().second;
  double hi = bounded ? std::max(waviness_at(-half), waviness_at(half)) : waviness.front().second;
  for (const auto& [psi, delta] : waviness)
    if (!bounded || std::abs(psi) <= half) lo = std::min(lo, delta), hi = std::max(hi, delta);
  return hi - lo;
}

double ToolGeometry::waviness_slope() const {
  const double half = 0.5 * included_angle;
  const bool bounded = half > 0;
  double steepest = 0;
  // δ is linear between the table's angles and constant beyond its ends: the steepest
  // slope is a segment's, of the segments that overlap the edge.
  for (std::size_t k = 1; k < waviness.size(); ++k) {
    const auto& [psi0, delta0] = waviness[k - 1];
    const auto& [psi1, delta1] = waviness[k];
    if (!(psi1 > psi0) || (bounded && (psi1 <= -half || psi0 >= half))) continue;
    steepest = std::max(steepest, std::abs(delta1 - delta0) / (psi1 - psi0));
  }
  return steepest;
}

}  // namespace freeturn
