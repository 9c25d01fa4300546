#include "freeturn/surface/qbfs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "freeturn/core/error.hpp"

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
