#pragma once
// The conic section every optical sag starts from (shared/notes/optical-surfaces.md):
//   z = c r² / (1 + √(1 − (1+k) c² r²)),
// written for plain numbers and for jets alike.

#include <cmath>
#include <limits>

#include "freeturn/surface/jet.hpp"

namespace freeturn {

// Sag of the conic of curvature c (1/mm) and conic constant k at r² = x² + y².
template <typename T>
T conic_sag(double c, double k, const T& r2) {
  return c * r2 / (1.0 + sqrt(1.0 - (1 + k) * c * c * r2));
}

// The radius beyond which the conic's square root goes negative (infinity if never).
inline double conic_defined_radius(double c, double k) {
  const double g = (1.0 + k) * c * c;
  return g > 0 ? 1.0 / std::sqrt(g) : std::numeric_limits<double>::infinity();
}

// The largest second derivative of the conic along any line in (x, y) at the points within
// `radius` of its axis (the Hessian's largest eigenvalue; Surface::max_bend), +∞ where the
// conic is not defined out to `radius`. The conic bends c/q³ along the radius and c/q along
// the circle, q = √(1 − (1 + k)c²r²). Where (1 + k) > 0, q falls with r: for c > 0 the
// larger, c/q³, is largest at the rim of the disc, and for c < 0 both are at most c (at the
// axis). Where (1 + k) ≤ 0, q ≥ 1 grows with r: for c > 0 both are at most c, and for c < 0
// the larger, c/q³, is largest at the rim.
inline double conic_max_bend(double c, double k, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  const double q2 = 1 - (1 + k) * c * c * radius * radius;
  if (!(q2 > 0)) return std::numeric_limits<double>::infinity();
  return (1 + k > 0) == (c > 0) ? c / (q2 * std::sqrt(q2)) : c;
}

// The conic's largest slope within `radius` of its axis: |c|r/q, which grows with r whatever
// the sign of (1 + k); +∞ where the conic is not defined out to `radius`.
inline double conic_max_slope(double c, double k, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  const double q2 = 1 - (1 + k) * c * c * radius * radius;
  if (!(q2 > 0)) return std::numeric_limits<double>::infinity();
  return std::abs(c) * radius / std::sqrt(q2);
}

}  // namespace freeturn
