#include "freeturn/surface/projected_rims.hpp"

#include "freeturn/surface/crease_sink.hpp"

#include <algorithm>
#include <cmath>

namespace freeturn {

bool ProjectedRims::build(std::span<const CreaseCircle> circles, const Eigen::Matrix3d& rotation,
                          const Eigen::Vector3d& origin) {
  rims_.clear();
  start_.clear();
  items_.clear();
  if (circles.empty()) return true;
  rims_.reserve(circles.size());
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY, widest = 0;
  for (const CreaseCircle& c : circles) {
    const Eigen::Vector3d a = c.axis.normalized();
    // Any unit e₁ normal to a (from the coordinate axis least along it), e₂ = a × e₁.
    Eigen::Index least;
    a.cwiseAbs().minCoeff(&least);
    const Eigen::Vector3d e1 = a.cross(Eigen::Vector3d::Unit(least)).normalized();
    const Eigen::Vector3d e2 = a.cross(e1);
    const Eigen::Vector3d u = rotation * e1, v = rotation * e2;
    const Eigen::Vector3d p = rotation * (c.centre - origin);
    const double det = u.x() * v.y() - u.y() * v.x();
    // |det| is the circle's normal's z part seen from the world: 0 edge-on.
    if (!(std::abs(det) > 1e-9) || !p.allFinite() || !(c.radius > 0) || !std::isfinite(c.radius)) {
      rims_.clear();
      return false;
    }
    Rim r;
    r.px = p.x(), r.py = p.y();
    r.m00 = v.y() / det, r.m01 = -v.x() / det, r.m10 = -u.y() / det, r.m11 = u.x() / det;
    r.radius = c.radius;
    r.half_x = c.radius * std::hypot(u.x(), v.x());
    r.half_y = c.radius * std::hypot(u.y(), v.y());
    x_lo = std::min(x_lo, r.px - r.half_x), x_hi = std::max(x_hi, r.px + r.half_x);
    y_lo = std::min(y_lo, r.py - r.half_y), y_hi = std::max(y_hi, r.py + r.half_y);
    widest = std::max({widest, 2 * r.half_x, 2 * r.half_y});
    rims_.push_back(r);
  }
  // Cells about as wide as the widest ellipse, at most 2048 a side.
  cell_ = std::max({widest, (x_hi - x_lo) / 2048, (y_hi - y_lo) / 2048, 1e-9});
  inverse_cell_ = 1 / cell_;
  x0_ = x_lo, y0_ = y_lo;
  per_side_x_ = static_cast<int>((x_hi - x_lo) * inverse_cell_) + 1;
  per_side_y_ = static_cast<int>((y_hi - y_lo) * inverse_cell_) + 1;
  const auto cell_x = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - x0_) * inverse_cell_)), 0, per_side_x_ - 1);
  };
  const auto cell_y = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - y0_) * inverse_cell_)), 0, per_side_y_ - 1);
  };
  std::vector<int> count(static_cast<std::size_t>(per_side_x_) * per_side_y_ + 1, 0);
  const auto visit = [&](const Rim& r, auto&& f) {
    for (int b = cell_y(r.py - r.half_y); b <= cell_y(r.py + r.half_y); ++b)
      for (int a = cell_x(r.px - r.half_x); a <= cell_x(r.px + r.half_x); ++a)
        f(static_cast<std::size_t>(b) * per_side_x_ + a);
  };
  for (const Rim& r : rims_) visit(r, [&](std::size_t k) { ++count[k + 1]; });
  for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  start_ = count;
  items_.resize(static_cast<std::size_t>(start_.back()));
  for (int i = 0; i < static_cast<int>(rims_.size()); ++i)
    visit(rims_[static_cast<std::size_t>(i)],
          [&](std::size_t k) { items_[static_cast<std::size_t>(count[k]++)] = i; });
  return true;
}

int ProjectedRims::crossings(double x0, double y0, const RadialLine& line, double t_lo, double t_hi,
                             std::span<double> out) const {
  if (rims_.empty() || !(t_lo <= t_hi) || !std::isfinite(t_lo) || !std::isfinite(t_hi)) return 0;
  const double dx = line.cos, dy = line.sin;
  const double ax = x0 + t_lo * dx, ay = y0 + t_lo * dy, bx = x0 + t_hi * dx, by = y0 + t_hi * dy;
  const auto cell = [&](double v, double lo, int n) {
    return std::clamp(static_cast<int>(std::floor((v - lo) * inverse_cell_)), 0, n - 1);
  };
  // A stretch wholly beside the grid crosses nothing; else its bounding box's cells.
  if (std::max(ax, bx) < x0_ || std::min(ax, bx) > x0_ + per_side_x_ * cell_ ||
      std::max(ay, by) < y0_ || std::min(ay, by) > y0_ + per_side_y_ * cell_)
    return 0;
  const int a_lo = cell(std::min(ax, bx), x0_, per_side_x_),
            a_hi = cell(std::max(ax, bx), x0_, per_side_x_);
  const int b_lo = cell(std::min(ay, by), y0_, per_side_y_),
            b_hi = cell(std::max(ay, by), y0_, per_side_y_);
  // One rim listed in two cells, or two rims through one point, is one crease.
  CreaseSink found(out, t_lo, t_hi);
  for (int b = b_lo; b <= b_hi; ++b)
    for (int a = a_lo; a <= a_hi; ++a) {
      const int k = b * per_side_x_ + a;
      for (int idx = start_[k]; idx < start_[k + 1]; ++idx) {
        const Rim& r = rims_[static_cast<std::size_t>(items_[static_cast<std::size_t>(idx)])];
        // |w + t e|² = ρ², w = M⁻¹(q₀ − p₀), e = M⁻¹d.
        const double qx = x0 - r.px, qy = y0 - r.py;
        const double wx = r.m00 * qx + r.m01 * qy, wy = r.m10 * qx + r.m11 * qy;
        const double ex = r.m00 * dx + r.m01 * dy, ey = r.m10 * dx + r.m11 * dy;
        const double A = ex * ex + ey * ey, B = wx * ex + wy * ey;
        const double C = (wx - r.radius) * (wx + r.radius) + wy * wy;
        const double disc = B * B - A * C;
        if (!(disc >= 0) || !(A > 0)) continue;
        // The roots without cancellation: q = −(B + sgn(B)√disc), t = q/A and C/q.
        const double q = -(B + std::copysign(std::sqrt(disc), B));
        found.add(q / A);
        if (q != 0) found.add(C / q);
      }
    }
  return found.finish();
}

}  // namespace freeturn
