#include "freeturn/path/cutter_points.hpp"

#include <algorithm>
#include <cmath>

#include "freeturn/surface/section_curvature.hpp"

namespace freeturn {

double smooth_wavy_edge_reach(const ToolMotion& tool, const Surface& design, double inner_radius,
                              double outer_radius) {
  if (!(tool.waviness_span > 0) || !(tool.nose_radius > 0)) return 0.0;
  const double R = tool.nose_radius, L = tool.waviness_slope;
  // A section convex everywhere (κ ≤ 0) leaves the nose the most room at κ = 0 that counts
  // here (more is not needed: L²/2R is a fraction of a nanometre for any real edge).
  const double kappa = std::max(0.0, largest_section_curvature(design, inner_radius, outer_radius));
  const double room = R * (1 - kappa * R);  // the nose's clearance grows as room·Δφ²/2
  if (!(room > 0)) return tool.waviness_span;
  return std::min(tool.waviness_span, L * L / (2 * room));
}

}  // namespace freeturn
