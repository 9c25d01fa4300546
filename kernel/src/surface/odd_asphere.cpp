#include "freeturn/surface/odd_asphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/surface/conic.hpp"

namespace freeturn {

OddAsphere::OddAsphere(double curvature, double conic, std::vector<double> coefficients)
    : c_(curvature), k_(conic), beta_(std::move(coefficients)) {
  if (beta_.size() > 30)
    throw InputError("coefficients", "has " + std::to_string(beta_.size()) +
                                         " terms; an odd asphere takes at most 30");
}

double OddAsphere::defined_radius() const { return conic_defined_radius(c_, k_); }

// A surface of revolution z = p(r) bends p''(r) along the radius and p'(r)/r along the circle
// (its Hessian's eigenvalues), and the largest eigenvalue of a sum is at most the sum of the
// parts' largest (Weyl). β r^i bends β·i(i − 1)r^{i−2} and β·i·r^{i−2}: for i ≥ 2 at most
// max(β, 0)·i(i − 1)·radius^{i−2} within the radius (both of β's sign, and growing with r);
// for i = 1, 0 along the radius and β/r along the circle: no larger than 0 where β < 0 (a
// cone pointing up, as a dome's tip), and without bound near the vertex where β > 0.
double OddAsphere::max_bend(double radius) const {
  if (!beta_.empty() && beta_[0] > 0) return std::numeric_limits<double>::infinity();
  return max_section_bend(radius);
}

// Along a radial section the cone β₁|ρ| bends 0 (its kink at the vertex is a crease), and
// every other term as max_bend counts it; the conic's bound is its largest eigenvalue.
double OddAsphere::max_section_bend(double radius) const {
  double bend = conic_max_bend(c_, k_, radius);
  if (!std::isfinite(bend)) return std::numeric_limits<double>::infinity();
  double power = 1.0;  // radius^{i−2}
  for (std::size_t n = 1; n < beta_.size(); ++n, power *= radius) {
    const double i = static_cast<double>(n + 1);
    bend += std::max(beta_[n], 0.0) * i * (i - 1) * power;
  }
  return bend;
}

// β_i r^i rises β_i·i·r^{i−1}, at most |β_i|·i·radius^{i−1} steep within the radius.
double OddAsphere::max_slope(double radius) const {
  double slope = conic_max_slope(c_, k_, radius);
  if (!std::isfinite(slope)) return std::numeric_limits<double>::infinity();
  double power = 1.0;  // radius^{i−1}
  for (std::size_t n = 0; n < beta_.size(); ++n, power *= radius)
    slope += std::abs(beta_[n]) * static_cast<double>(n + 1) * power;
  return slope;
}

void OddAsphere::radial(double x, double y, double& z, double& g1, double& g2) const {
  const double s = x * x + y * y;
  const double r = std::sqrt(s);
  // Conic in s = r² (as EvenAsphere): F = c s/(1+q), F' = c/(2q), F'' = (1+k)c³/(4q³);
  // then z'/r = 2F' and (z'' − z'/r)/r² = 4F''.
  const double q = std::sqrt(1.0 - (1.0 + k_) * c_ * c_ * s);
  z = c_ * s / (1.0 + q);
  g1 = c_ / q;
  g2 = (1.0 + k_) * c_ * c_ * c_ / (q * q * q);
  // β_i r^i: z'/r = i β_i r^(i−2), (z'' − z'/r)/r² = i(i−2) β_i r^(i−4). At the vertex
  // the terms with negative powers are dropped: they multiply x, y or xy, which vanish
  // faster (i ≥ 3) or are the cone's undefined gradient (i = 1).
  double power = 1.0;  // r^i
  for (std::size_t n = 0; n < beta_.size(); ++n) {
    const int i = static_cast<int>(n) + 1;
    power *= r;
    const double b = beta_[n];
    if (b == 0) continue;
    z += b * power;
    if (r > 0) {
      g1 += i * b * power / s;
      g2 += i * (i - 2) * b * power / (s * s);
    } else if (i == 2) {
      g1 += 2 * b;
    } else if (i == 4) {
      g2 += 8 * b;
    }
  }
}

void OddAsphere::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  double g1, g2;
  radial(x, y, z, g1, g2);
  zx = g1 * x;
  zy = g1 * y;
}

HeightDerivatives OddAsphere::height_derivatives(double x, double y) const {
  HeightDerivatives h;
  double g1, g2;
  radial(x, y, h.z, g1, g2);
  h.zx = g1 * x;
  h.zy = g1 * y;
  h.zxx = g1 + g2 * x * x;
  h.zxy = g2 * x * y;
  h.zyy = g1 + g2 * y * y;
  return h;
}

}  // namespace freeturn
