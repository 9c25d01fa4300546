#include "freeturn/surface/toroidal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace freeturn {

// The profile z_p(y) and the surface turned about the axis parallel to y at R: with
// d = R − z_p(y), W = √(d² − x²) and σ = sgn R (z = R − σW),
//   z_xx = σd²/W³,  z_xy = σ x d z_p'/W³,  z_yy = σ((d z_p'' − z_p'²)/W + d² z_p'²/W³).
// Within the radius r (|x|, |y| ≤ r) the profile gives |z_p| ≤ Z, |z_p'| ≤ F₁ and
// |z_p''| ≤ F₂ (its conic's sag, slope c·y/q and bend c/q³ at the largest q⁻¹, and each term
// α_i y^{2i}'s at r), so |d| lies within |R| ∓ Z where |R| > Z, and W ≥ W₀ = √((|R| − Z)² − r²)
// where that is positive. The largest eigenvalue is at most the larger diagonal entry plus
// |z_xy| (Gershgorin), z_xx at most 0 where σ < 0 (a dome across the profile).
double Toroidal::max_bend(double radius) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(radius >= 0) || !std::isfinite(radius)) return kInfinity;
  const double r2 = radius * radius, g = (1 + k_) * c_ * c_;
  const double q2 = 1 - std::max(g, 0.0) * r2;  // the least q on the profile within the radius
  if (!(q2 > 0)) return kInfinity;
  const double q = std::sqrt(q2);
  double z = std::abs(c_) * r2 / (1 + std::sqrt(1 - g * r2));
  double f1 = std::abs(c_) * radius / q, f2 = std::abs(c_) / (q2 * q);
  double power = 1;  // r^{2i−2}
  for (std::size_t n = 0; n < alpha_.size(); ++n, power *= r2) {
    const double i2 = 2.0 * static_cast<double>(n + 1), a = std::abs(alpha_[n]);
    z += a * power * r2;
    f1 += a * i2 * power * radius;
    f2 += a * i2 * (i2 - 1) * power;
  }
  if (r_ == 0) return f2 * (1 + 1e-12);  // a cylinder: z = z_p(y) bends z_p'' at most
  const double d_low = std::abs(r_) - z, d_high = std::abs(r_) + z;
  const double w2 = d_low * d_low - r2;
  if (!(d_low > 0) || !(w2 > 0)) return kInfinity;
  const double w = std::sqrt(w2), w3 = w2 * w;
  const double xx = r_ > 0 ? d_high * d_high / w3 : 0.0;
  const double xy = radius * d_high * f1 / w3;
  const double yy = (d_high * f2 + f1 * f1) / w + d_high * d_high * f1 * f1 / w3;
  const double bend = (std::max(xx, yy) + xy) * (1 + 1e-12);
  return std::isfinite(bend) ? bend : kInfinity;
}

}  // namespace freeturn
