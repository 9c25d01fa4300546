#include "freeturn/nurbs/arc_length.hpp"

#include <algorithm>
#include <cmath>

#include "freeturn/nurbs/gauss_legendre.hpp"

namespace freeturn::nurbs {
namespace {

constexpr int kOrder = 12;

double gauss(const NurbsCurve& c, double a, double b) {
  const QuadratureRule rule = gauss_legendre(kOrder);
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  double sum = 0;
  Vector3d d[2];
  for (int i = 0; i < kOrder; ++i) {
    c.derivatives(mid + half * rule.nodes[i], 1, d);
    sum += rule.weights[i] * d[1].norm();
  }
  return sum * half;
}

double adaptive(const NurbsCurve& c, double a, double b, double whole, int depth) {
  const double m = 0.5 * (a + b);
  const double left = gauss(c, a, m), right = gauss(c, m, b);
  const double halves = left + right;
  if (depth >= 40 || std::abs(halves - whole) <= 1e-15 * std::abs(halves) + 1e-300) return halves;
  return adaptive(c, a, m, left, depth + 1) + adaptive(c, m, b, right, depth + 1);
}

}  // namespace

ArcLengthTable::ArcLengthTable(NurbsCurve curve) : curve_(std::move(curve)) {
  breaks_ = curve_.knots().breakpoints();
  cumulative_.assign(breaks_.size(), 0.0);
  for (std::size_t k = 1; k < breaks_.size(); ++k)
    cumulative_[k] = cumulative_[k - 1] + integrate(breaks_[k - 1], breaks_[k]);
}

double ArcLengthTable::integrate(double a, double b) const {
  if (b <= a) return 0.0;
  return adaptive(curve_, a, b, gauss(curve_, a, b), 0);
}

double ArcLengthTable::length_to(double u) const {
  u = std::clamp(u, breaks_.front(), breaks_.back());
  const auto it = std::upper_bound(breaks_.begin(), breaks_.end(), u);
  const std::size_t k =
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - breaks_.begin() - 1, 0));
  if (k + 1 >= breaks_.size()) return cumulative_.back();
  return cumulative_[k] + integrate(breaks_[k], u);
}

double ArcLengthTable::parameter_at(double s) const {
  if (s <= 0) return breaks_.front();
  if (s >= total()) return breaks_.back();
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const std::size_t k = static_cast<std::size_t>(it - cumulative_.begin() - 1);
  double lo = breaks_[k], hi = breaks_[k + 1];
  const double target = s - cumulative_[k];
  // Newton from the linear guess, kept inside the bracket [lo, hi] by bisection.
  const double span_length = cumulative_[k + 1] - cumulative_[k];
  double u = lo + (hi - lo) * target / span_length;
  const double tolerance = 1e-14 * total();
  Vector3d d[2];
  for (int it = 0; it < 100; ++it) {
    const double err = integrate(breaks_[k], u) - target;
    if (std::abs(err) <= tolerance) break;
    if (err > 0)
      hi = u;
    else
      lo = u;
    curve_.derivatives(u, 1, d);
    const double speed = d[1].norm();
    double next = speed > 0 ? u - err / speed : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == u) break;
    u = next;
  }
  return u;
}

}  // namespace freeturn::nurbs
