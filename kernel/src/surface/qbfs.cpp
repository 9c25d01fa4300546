#include "freeturn/surface/qbfs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/surface/conic.hpp"

namespace freeturn {

void Qbfs::recurrence(std::size_t n, std::vector<double>& f, std::vector<double>& g,
                      std::vector<double>& h) {
  // Forbes (2007), Appendix A: f_0 = 2, g_0 = −1/2, f_1 = √19/2, and for m ≥ 2
  //   h_{m−2} = −m(m−1)/(2 f_{m−2}), g_{m−1} = −(1 + g_{m−2} h_{m−2})/f_{m−1},
  //   f_m = √(m(m+1) + 3 − g_{m−1}² − h_{m−2}²).
  // f_0 is folded into Q_0 = P_0/f_0 = 1.
  n = std::max<std::size_t>(n, 2);
  f.assign(n, 0.0);
  g.assign(n, 0.0);
  h.assign(n, 0.0);
  f[0] = 2.0;
  g[0] = -0.5;
  f[1] = std::sqrt(19.0) / 2.0;
  for (std::size_t m = 2; m < n; ++m) {
    const double md = static_cast<double>(m);
    h[m - 2] = -md * (md - 1.0) / (2.0 * f[m - 2]);
    g[m - 1] = -(1.0 + g[m - 2] * h[m - 2]) / f[m - 1];
    f[m] = std::sqrt(md * (md + 1.0) + 3.0 - g[m - 1] * g[m - 1] - h[m - 2] * h[m - 2]);
  }
}

Qbfs::Qbfs(double curvature, double normalization_radius, std::vector<double> coefficients)
    : c_(curvature), inv_r2_(1.0 / (normalization_radius * normalization_radius)),
      a_(std::move(coefficients)) {
  if (!(normalization_radius > 0))
    throw InputError("normalization_radius", "must be > 0");
  if (a_.size() > 31)
    throw InputError("coefficients", "has " + std::to_string(a_.size()) +
                                         " terms; Q-bfs takes at most 31 (a_0 … a_30)");
  recurrence(std::max<std::size_t>(a_.size(), 2), f_, g_, h_);
  unit_series_bounds_ = series_bounds(1.0);
}

// Each Q_m's sup norm and its two derivatives' over [0, w_max], by the triangle inequality
// through the recurrence of Q_m (series()) from those of the P_m:
// - P_m = 2(U_m(x) + U_{m−1}(x)), x = 1 − 2w, U the Chebyshev polynomials of the second
//   kind (P_0 = 2, P_1 = 2(2x + 1) = 6 − 8w, and P_m = 2x·P_{m−1} − P_{m−2} is U's
//   recurrence). |U_k(x)| ≤ U_k(X) for |x| ≤ X = 2w_max − 1 ≥ 1 (|U_k| ≤ k + 1 = U_k(1)
//   on [−1, 1], and |U_k(±y)| = U_k(y) grows on [1, ∞)).
// - A polynomial of degree n on an interval of half-length L has |p'| ≤ n²/L·max|p| and
//   |p''| ≤ n²(n² − 1)/(3L²)·max|p| (the Markov brothers' inequalities, T_n'(1) and
//   T_n''(1) on [−1, 1]).
std::array<double, 3> Qbfs::series_bounds(double w_max) const {
  const double x = 2 * w_max - 1, half = 0.5 * w_max;
  std::array<double, 3> sum{}, previous{}, before{}, q{1.0, 0.0, 0.0};  // Q_0 = 1
  double u_before = 0, u = 1;                                           // U_{−1}(X), U_0(X)
  for (std::size_t m = 0; m < a_.size(); ++m) {
    if (m > 0) {
      const double u_next = 2 * x * u - u_before;
      u_before = u;
      u = u_next;
      const double n = static_cast<double>(m);
      const double p = 2 * (u + u_before);
      const std::array<double, 3> pm{p, n * n / half * p,
                                     n * n * (n * n - 1) / (3 * half * half) * p};
      before = previous;
      previous = q;
      for (int j = 0; j < 3; ++j) {
        const double older = m >= 2 ? std::abs(h_[m - 2]) * before[j] : 0.0;
        q[j] = (pm[j] + std::abs(g_[m - 1]) * previous[j] + older) / f_[m];
      }
    }
    for (int j = 0; j < 3; ++j) sum[j] += std::abs(a_[m]) * q[j];
  }
  return sum;
}

// The departure D(s) = P(w)·γ(s), with P = w(1 − w)S(w), w = s/r_max² and
// γ = (1 − c²s)^{−1/2}, whose γ, γ' = c²γ³/2 and γ'' = 3c⁴γ⁵/4 are positive and grow with s:
// |D'| ≤ |P'|γ/r_max² + |P|γ' and |D''| ≤ |P''|γ/r_max⁴ + 2|P'|γ'/r_max² + |P|γ'' at
// s = radius², with |P|, |P'|, |P''| from w(1 − w)'s (at most max(1/4, w(w − 1)), 2w − 1 and
// 2 on [0, w ≥ 1]) and S's. False where the sphere does not reach the radius.
bool Qbfs::departure_bounds(double radius, double& d1, double& d2) const {
  const double s = radius * radius;
  if (!(radius >= 0) || !std::isfinite(radius) || !(c_ * c_ * s < 1)) return false;
  d1 = d2 = 0;
  if (a_.empty()) return true;
  const double w = std::max(1.0, s * inv_r2_);
  const std::array<double, 3> series = w <= 1 ? unit_series_bounds_ : series_bounds(w);
  const double e0 = std::max(0.25, w * (w - 1)), e1 = 2 * w - 1;
  const double p0 = e0 * series[0], p1 = e1 * series[0] + e0 * series[1],
               p2 = 2 * series[0] + 2 * e1 * series[1] + e0 * series[2];
  const double gamma = 1 / std::sqrt(1 - c_ * c_ * s), c2 = c_ * c_;
  const double gamma1 = 0.5 * c2 * gamma * gamma * gamma,
               gamma2 = 0.75 * c2 * c2 * gamma * gamma * gamma * gamma * gamma;
  // The sums round by parts in 10¹⁵ of terms all positive.
  d1 = (p1 * inv_r2_ * gamma + p0 * gamma1) * (1 + 1e-12);
  d2 = (p2 * inv_r2_ * inv_r2_ * gamma + 2 * p1 * inv_r2_ * gamma1 + p0 * gamma2) * (1 + 1e-12);
  return std::isfinite(d1) && std::isfinite(d2);
}

// p(r) = F(s), s = r², bends p'' = 2F' + 4sF'' along the radius and p'/r = 2F' along the
// circle: the departure at most 2|D'| + 4s|D''| either way, the sphere conic_max_bend's.
double Qbfs::max_bend(double radius) const {
  double d1, d2;
  if (!departure_bounds(radius, d1, d2)) return std::numeric_limits<double>::infinity();
  return conic_max_bend(c_, 0.0, radius) + 2 * d1 + 4 * radius * radius * d2;
}

// p'(r) = 2r F'(s): the departure at most 2r|D'| steep, the sphere conic_max_slope's.
double Qbfs::max_slope(double radius) const {
  double d1, d2;
  if (!departure_bounds(radius, d1, d2)) return std::numeric_limits<double>::infinity();
  return conic_max_slope(c_, 0.0, radius) + 2 * radius * d1;
}

double Qbfs::defined_radius() const {
  return c_ == 0 ? std::numeric_limits<double>::infinity() : 1.0 / std::abs(c_);
}

std::vector<double> Qbfs::polynomials(double x, int count) {
  std::vector<double> f, g, h, q;
  recurrence(static_cast<std::size_t>(std::max(count, 2)), f, g, h);
  double p_prev = 2.0, p = 6.0 - 8.0 * x;
  for (int m = 0; m < count; ++m) {
    if (m == 0) {
      q.push_back(1.0);
    } else if (m == 1) {
      q.push_back((p - g[0] * q[0]) / f[1]);
    } else {
      const double p_next = (2.0 - 4.0 * x) * p - p_prev;
      p_prev = p;
      p = p_next;
      q.push_back((p - g[m - 1] * q[m - 1] - h[m - 2] * q[m - 2]) / f[m]);
    }
  }
  return q;
}

}  // namespace freeturn
