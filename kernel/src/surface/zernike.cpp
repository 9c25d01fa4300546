#include "freeturn/surface/zernike.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/surface/bend_bounds.hpp"

namespace freeturn {
namespace {

double factorial(int n) {
  double f = 1;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

// Coefficient of ρ^{n−2k} in R_n^|m|.
double radial_coefficient(int n, int am, int k) {
  const double sign = (k % 2) ? -1.0 : 1.0;
  return sign * factorial(n - k) /
         (factorial(k) * factorial((n + am) / 2 - k) * factorial((n - am) / 2 - k));
}

double normalization(int n, int m) {
  return m == 0 ? std::sqrt(n + 1.0) : std::sqrt(2.0 * (n + 1));
}

}  // namespace

std::vector<double> zernike_power_coefficients(const std::vector<double>& a, int& degree) {
  degree = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != 0) degree = std::max(degree, noll_to_nm(static_cast<int>(i) + 1).n);
  const int d = degree, w = d + 1;
  std::vector<double> c(static_cast<std::size_t>(w * w), 0.0);
  const auto binomial = [](int n, int k) { return factorial(n) / (factorial(k) * factorial(n - k)); };
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == 0) continue;
    const ZernikeIndex z = noll_to_nm(static_cast<int>(i) + 1);
    const int am = std::abs(z.m);
    const double scale = a[i] * normalization(z.n, z.m);
    // {Re, Im}((X + iY)^|m|) = Σ_t C(|m|, t) X^{|m|−t} (iY)^t: even t for the real part,
    // odd for the imaginary, with i^t's sign.
    for (int t = 0; t <= am; ++t) {
      const bool real = t % 2 == 0;
      if (real != (z.m >= 0)) continue;
      const double angular = binomial(am, t) * ((real ? t / 2 : (t - 1) / 2) % 2 ? -1.0 : 1.0);
      for (int k = 0; k <= (z.n - am) / 2; ++k) {
        const int s = (z.n - 2 * k - am) / 2;  // the power of X² + Y²
        const double radial = radial_coefficient(z.n, am, k);
        for (int u = 0; u <= s; ++u) {
          const int px = am - t + 2 * u, py = t + 2 * (s - u);
          c[static_cast<std::size_t>(px * w + py)] += scale * angular * radial * binomial(s, u);
        }
      }
    }
  }
  return c;
}

ZernikeIndex noll_to_nm(int j) {
  if (j < 1 || j > 231)
    throw InputError("term " + std::to_string(j), "Zernike terms are numbered 1 to 231 (Noll)");
  // j = n(n+1)/2 + |m| + c, c = 0 when (m > 0 and n mod 4 ∈ {0,1}) or (m < 0 and
  // n mod 4 ∈ {2,3}), else 1; |m| ≡ n (mod 2).
  for (int n = 0; n <= 20; ++n)
    for (int am = n % 2; am <= n; am += 2)
      for (int sign : {1, -1}) {
        if (am == 0 && sign < 0) continue;
        const int m = sign * am;
        const bool c0 =
            (m > 0 && (n % 4 == 0 || n % 4 == 1)) || (m < 0 && (n % 4 == 2 || n % 4 == 3));
        if (n * (n + 1) / 2 + am + (c0 ? 0 : 1) == j) return {n, m};
      }
  throw InputError("term " + std::to_string(j), "has no (n, m)");  // unreachable for 1..231
}

double zernike_polar(int j, double rho, double phi) {
  const ZernikeIndex z = noll_to_nm(j);
  const int am = std::abs(z.m);
  double r = 0;
  for (int k = 0; k <= (z.n - am) / 2; ++k)
    r += radial_coefficient(z.n, am, k) * std::pow(rho, z.n - 2 * k);
  const double angular = z.m < 0 ? std::sin(am * phi) : std::cos(am * phi);
  return normalization(z.n, z.m) * r * angular;
}

Zernike::Zernike(double curvature, double conic, const std::array<double, 9>& asphere,
                 double normalization_radius, const std::vector<double>& coefficients)
    : c_(curvature), k_(conic), rn_(normalization_radius), asphere_(asphere) {
  if (!(rn_ > 0)) throw InputError("normalization_radius", "must be greater than 0");
  if (coefficients.size() > 231) throw InputError("coefficients", "at most 231 Zernike terms");
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    if (coefficients[i] == 0) continue;
    const ZernikeIndex z = noll_to_nm(static_cast<int>(i) + 1);
    const int am = std::abs(z.m);
    const int k = (z.n - am) / 2;
    auto it =
        std::find_if(orders_.begin(), orders_.end(), [&](const Order& o) { return o.m == am; });
    if (it == orders_.end()) {
      orders_.push_back(Order{});
      it = std::prev(orders_.end());
      it->m = am;
    }
    it->k_max = std::max(it->k_max, k);
    const double c = coefficients[i] * normalization(z.n, z.m) * (k % 2 ? -1.0 : 1.0);
    (z.m < 0 ? it->sin_coefficient : it->cos_coefficient)[k] += c;
    max_m_ = std::max(max_m_, am);
  }
  int degree = 0;
  const std::vector<double> powers = zernike_power_coefficients(coefficients, degree);
  abs_by_order_.assign(static_cast<std::size_t>(degree) + 1, 0.0);
  for (int a = 0; a <= degree; ++a)
    for (int b = 0; a + b <= degree; ++b)
      abs_by_order_[static_cast<std::size_t>(a + b)] +=
          std::abs(powers[static_cast<std::size_t>(a * (degree + 1) + b)]);
}

double Zernike::max_bend(double radius) const {
  return conic_max_bend(c_, k_, radius) + even_terms_max_bend(asphere_, radius) +
         power_terms_max_bend(abs_by_order_, rn_, radius);
}

double Zernike::max_slope(double radius) const {
  return conic_max_slope(c_, k_, radius) + even_terms_max_slope(asphere_, radius) +
         power_terms_max_slope(abs_by_order_, rn_, radius);
}

}  // namespace freeturn
