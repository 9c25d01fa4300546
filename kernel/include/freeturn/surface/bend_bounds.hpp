#pragma once
// Term-by-term bounds of a height's second derivative along any line in (x, y) at the points
// within a radius of the axis (Surface::max_bend). The largest eigenvalue of a sum of
// Hessians is at most the sum of the parts' largest eigenvalues, and a part's is at most its
// spectral norm: each surface adds its base's bound (conic_max_bend) to these.

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace freeturn {

// The even polynomial Σ A_2i r^{2i}, i = 2 … 10 (coefficients A4 … A20, as EvenAsphere and
// Zernike take them). A surface of revolution bends p''(r) along the radius and p'(r)/r along
// the circle; a term bends A·2i(2i − 1)r^{2i−2} and A·2i·r^{2i−2} along them, both at most
// |A|·2i(2i − 1)·radius^{2i−2} within the radius.
inline double even_terms_max_bend(const std::array<double, 9>& a, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  double bend = 0;
  for (int i = 10; i >= 2; --i)  // Horner in radius²
    bend = bend * radius * radius +
           std::abs(a[static_cast<std::size_t>(i - 2)]) * (2 * i) * (2 * i - 1);
  return bend * radius * radius;
}

// The same terms' largest slope within the radius: |A|·2i·radius^{2i−1} each.
inline double even_terms_max_slope(const std::array<double, 9>& a, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  double slope = 0;
  for (int i = 10; i >= 2; --i)  // Horner in radius²
    slope = slope * radius * radius + std::abs(a[static_cast<std::size_t>(i - 2)]) * (2 * i);
  return slope * radius * radius * radius;
}

// The polynomial Σ c_ab (x/R_n)^a (y/R_n)^b, given Σ |c_ab| over each order n = a + b
// (abs_by_order[n]). A term along a unit direction u bends
//   c/R_nⁿ (a(a−1)x^{a−2}y^b u_x² + 2ab x^{a−1}y^{b−1}u_x u_y + b(b−1)x^a y^{b−2}u_y²),
// at most |c|/R_nⁿ · n(n−1) r^{n−2} where |x|, |y| ≤ r: the bracket is at most a(a−1) for
// b = 0, and (a|u_x| + b|u_y|)² − a u_x² − b u_y² ≤ a² + b² − min(a, b) ≤ n(n−1) otherwise.
inline double power_terms_max_bend(std::span<const double> abs_by_order,
                                   double normalization_radius, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  const double t = radius / normalization_radius;
  double bend = 0;
  for (std::size_t n = abs_by_order.size(); n-- > 2;)  // Horner in t
    bend = bend * t + abs_by_order[n] * static_cast<double>(n * (n - 1));
  return bend / (normalization_radius * normalization_radius);
}

// The same polynomial's largest slope: a term's gradient c/R_nⁿ (a x^{a−1}y^b, b x^a y^{b−1})
// is at most |c|/R_nⁿ · n r^{n−1} long where |x|, |y| ≤ r.
inline double power_terms_max_slope(std::span<const double> abs_by_order,
                                    double normalization_radius, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  const double t = radius / normalization_radius;
  double slope = 0;
  for (std::size_t n = abs_by_order.size(); n-- > 1;)  // Horner in t
    slope = slope * t + abs_by_order[n] * static_cast<double>(n);
  return slope / normalization_radius;
}

}  // namespace freeturn
