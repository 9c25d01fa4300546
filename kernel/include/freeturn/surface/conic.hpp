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

}  // namespace freeturn
