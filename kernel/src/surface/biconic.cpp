#include "freeturn/surface/biconic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace freeturn {

double Biconic::defined_radius() const {
  // 1 − a_x x² − a_y y² > 0 on the whole disk of radius r when r² · max(a_x, a_y) < 1.
  const double g = std::max((1 + kx_) * cx_ * cx_, (1 + ky_) * cy_ * cy_);
  return g > 0 ? 1.0 / std::sqrt(g) : Surface::defined_radius();
}

// z = N·φ(Q), N = c_x x² + c_y y², Q = a_x x² + a_y y² (a = (1 + k)c²), φ(Q) = 1/(1 + t),
// t = √(1 − Q). Along a unit direction u,
//   z'' = φ·2(c_x u_x² + c_y u_y²) + 2φ'(∇N·u)(∇Q·u) + N(φ'·2(a_x u_x² + a_y u_y²) + φ''(∇Q·u)²),
// with φ' = 1/(2t(1 + t)²) and φ'' = (1 + 3t)/(4t³(1 + t)³), both positive and growing with Q
// (so largest at Q's largest, max(a_x, a_y, 0)·r² within the radius r). With C = max|c| and
// A = max|a|: |∇N·u| ≤ 2Cr, |∇Q·u| ≤ 2Ar and |N| ≤ Cr², so
//   z'' ≤ 2 max(c_x, c_y, 0)φ + 10CA r² φ' + 4CA² r⁴ φ''.
// For the rotationally symmetric conic at the vertex it is c, the conic's own bend there.
double Biconic::max_bend(double radius) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(radius >= 0) || !std::isfinite(radius)) return kInfinity;
  const double ax = (1 + kx_) * cx_ * cx_, ay = (1 + ky_) * cy_ * cy_, r2 = radius * radius;
  const double t2 = 1 - std::max({ax, ay, 0.0}) * r2;
  if (!(t2 > 0)) return kInfinity;
  const double t = std::sqrt(t2), c = std::max(std::abs(cx_), std::abs(cy_)),
               a = std::max(std::abs(ax), std::abs(ay));
  const double phi = 1 / (1 + t), phi1 = 0.5 * phi * phi / t,
               phi2 = 0.25 * (1 + 3 * t) * phi * phi * phi / (t * t * t);
  const double bend =
      2 * std::max({cx_, cy_, 0.0}) * phi + 10 * c * a * r2 * phi1 + 4 * c * a * a * r2 * r2 * phi2;
  return std::isfinite(bend) ? bend : kInfinity;
}

}  // namespace freeturn
