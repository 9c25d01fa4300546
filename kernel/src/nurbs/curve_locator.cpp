#include "freeturn/nurbs/curve_locator.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace freeturn::nurbs {

CurveLocator::CurveLocator(NurbsCurve curve, LocatorOptions options)
    : curve_(std::move(curve)), options_(options) {
  const std::vector<double> b = curve_.knots().breakpoints();
  const int per_span = std::max({2, options_.samples_per_span, curve_.degree()}) * 2;
  for (std::size_t k = 0; k + 1 < b.size(); ++k)
    for (int i = 0; i < per_span; ++i) params_.push_back(b[k] + (b[k + 1] - b[k]) * i / per_span);
  params_.push_back(b.back());
  Eigen::AlignedBox3d box;
  for (double u : params_) {
    samples_.push_back(curve_.point(u));
    box.extend(samples_.back());
  }
  closed_ = curve_.is_closed(1e-10 * (1.0 + box.diagonal().norm()));
}

double CurveLocator::wrap_or_clamp(double u) const {
  const double lo = curve_.front(), hi = curve_.back();
  if (!closed_) return std::clamp(u, lo, hi);
  const double period = hi - lo;
  return (u < lo || u > hi) ? lo + (u - lo) - period * std::floor((u - lo) / period) : u;
}

CurvePointResult CurveLocator::closest_point(const Vector3d& p, double u) const {
  u = wrap_or_clamp(u);
  CurveDerivatives d = curve_.evaluate(u, 2);
  Vector3d r = d.point - p;
  double f = r.squaredNorm();
  CurvePointResult res;
  for (int it = 0; it < options_.max_iterations; ++it) {
    res.iterations = it;
    const double dist = std::sqrt(f);
    if (dist <= options_.point_tolerance) {
      res.status = Status::kOk;
      break;
    }
    const double g = d.d1.dot(r);
    const double speed = d.d1.norm();
    // An end of an open curve is the answer when the curve leads away from p there.
    const bool pinned =
        !closed_ && ((u <= curve_.front() && g > 0) || (u >= curve_.back() && g < 0));
    if (pinned || speed == 0 || std::abs(g) <= options_.cosine_tolerance * speed * dist) {
      res.status = Status::kOk;
      break;
    }
    // Newton (Eq. 6.3) where f is convex along the curve, Gauss–Newton where it is not.
    double h = d.d1.squaredNorm() + d.d2.dot(r);
    if (!(h > 0)) h = d.d1.squaredNorm();
    double step = -g / h;
    bool accepted = false;
    for (int k = 0; k < 40; ++k, step *= 0.5) {
      const double un = wrap_or_clamp(u + step);
      const CurveDerivatives dn = curve_.evaluate(un, 2);
      const Vector3d rn = dn.point - p;
      const double fn = rn.squaredNorm();
      const double gn = dn.d1.dot(rn);
      // As for surfaces: where f no longer resolves the change, a smaller gradient counts.
      if (fn < f || (fn <= f * (1 + 1e-13) && std::abs(gn) < 0.5 * std::abs(g))) {
        accepted = (dn.point - d.point).norm() > 1e-15 * (1 + d.point.norm());
        u = un;
        d = dn;
        r = rn;
        f = fn;
        break;
      }
    }
    if (!accepted) {  // no representable progress: as good as double precision allows
      res.status = Status::kOk;
      break;
    }
  }
  res.u = u;
  res.point = d.point;
  res.distance = std::sqrt(f);
  return res;
}

CurvePointResult CurveLocator::closest_point(const Vector3d& p) const {
  // Seeds: local minima of the sampled distance (an end counts when it is below its
  // neighbour); the best three are refined.
  const int n = static_cast<int>(samples_.size());
  std::array<std::pair<double, int>, 3> best;
  best.fill({INFINITY, -1});
  for (int i = 0; i < n; ++i) {
    const double d = (samples_[i] - p).squaredNorm();
    const double prev = i > 0 ? (samples_[i - 1] - p).squaredNorm()
                              : (closed_ ? (samples_[n - 2] - p).squaredNorm() : INFINITY);
    const double next = i + 1 < n ? (samples_[i + 1] - p).squaredNorm()
                                  : (closed_ ? (samples_[1] - p).squaredNorm() : INFINITY);
    if (d > prev || d > next) continue;
    if (d < best.back().first) {
      best.back() = {d, i};
      std::sort(best.begin(), best.end());
    }
  }
  CurvePointResult out;
  out.distance = INFINITY;
  for (const auto& [d, i] : best) {
    if (i < 0) continue;
    const CurvePointResult r = closest_point(p, params_[i]);
    if (r.distance < out.distance) out = r;
  }
  return out;
}

}  // namespace freeturn::nurbs
