#include "freeturn/nurbs/surface_locator.hpp"

#include <algorithm>
#include <cmath>

namespace freeturn::nurbs {
namespace {

// Sample parameters: `per_span` intervals in every non-empty knot span, so that the grid
// follows the knots (where the shape can change) rather than the parameter range.
std::vector<double> knot_aware_samples(const KnotVector& knots, int per_span) {
  const std::vector<double> b = knots.breakpoints();
  std::vector<double> s;
  for (std::size_t k = 0; k + 1 < b.size(); ++k)
    for (int i = 0; i < per_span; ++i) s.push_back(b[k] + (b[k + 1] - b[k]) * i / per_span);
  s.push_back(b.back());
  return s;
}

}  // namespace

SurfaceLocator::SurfaceLocator(NurbsSurface surface, LocatorOptions options)
    : surface_(std::move(surface)), options_(options) {
  const int per_span = std::max(2, options_.samples_per_span);
  per_span_u_ = std::max(per_span, surface_.degree_u());
  per_span_v_ = std::max(per_span, surface_.degree_v());
  grid_u_ = knot_aware_samples(surface_.knots_u(), per_span_u_);
  grid_v_ = knot_aware_samples(surface_.knots_v(), per_span_v_);
  const std::vector<double> bu = surface_.knots_u().breakpoints();
  const std::vector<double> bv = surface_.knots_v().breakpoints();
  patches_u_ = static_cast<int>(bu.size()) - 1;
  patches_v_ = static_cast<int>(bv.size()) - 1;
  for (int a = 0; a < patches_u_; ++a) {
    const int su = surface_.knots_u().find_span(0.5 * (bu[a] + bu[a + 1]));
    for (int b = 0; b < patches_v_; ++b) {
      const int sv = surface_.knots_v().find_span(0.5 * (bv[b] + bv[b + 1]));
      Eigen::AlignedBox3d box;
      for (int i = su - surface_.degree_u(); i <= su; ++i)
        for (int j = sv - surface_.degree_v(); j <= sv; ++j)
          box.extend(surface_.control_point(i, j));
      patch_boxes_.push_back(box);
    }
  }
  grid_points_.reserve(grid_u_.size() * grid_v_.size());
  Eigen::AlignedBox3d box;
  for (double u : grid_u_)
    for (double v : grid_v_) {
      grid_points_.push_back(surface_.point(u, v));
      box.extend(grid_points_.back());
    }
  // A direction is closed when its two end curves coincide (checked on every sample).
  const double tolerance = 1e-10 * (1.0 + box.diagonal().norm());
  const int nu = static_cast<int>(grid_u_.size()), nv = static_cast<int>(grid_v_.size());
  closed_u_ = closed_v_ = true;
  for (int j = 0; j < nv; ++j)
    if ((grid_points_[j] - grid_points_[(nu - 1) * nv + j]).norm() > tolerance) closed_u_ = false;
  for (int i = 0; i < nu; ++i)
    if ((grid_points_[i * nv] - grid_points_[i * nv + nv - 1]).norm() > tolerance)
      closed_v_ = false;
  for (int i = 0; i + 1 < nu; ++i)
    for (int j = 0; j + 1 < nv; ++j) {
      const Vector3d& a = grid_points_[i * nv + j];
      const Vector3d& b = grid_points_[i * nv + j + 1];
      const Vector3d& c = grid_points_[(i + 1) * nv + j];
      const Vector3d& e = grid_points_[(i + 1) * nv + j + 1];
      // Corner distances bound the cell; doubled for the bulge of a curved cell.
      cell_size_ = std::max({cell_size_, 2 * (a - e).norm(), 2 * (b - c).norm()});
    }
  // An edge is a pole when all its samples coincide.
  const auto collapsed = [&](int first, int stride, int count) {
    for (int k = 1; k < count; ++k)
      if ((grid_points_[first + k * stride] - grid_points_[first]).norm() > tolerance) return false;
    return true;
  };
  pole_u_front_ = collapsed(0, 1, nv);
  pole_u_back_ = collapsed((nu - 1) * nv, 1, nv);
  pole_v_front_ = collapsed(0, nv, nu);
  pole_v_back_ = collapsed(nv - 1, nv, nu);
  const auto add_rings = [&](bool in_u, bool at_front) {
    const std::vector<double>& across = in_u ? grid_u_ : grid_v_;
    const std::vector<double>& along = in_u ? grid_v_ : grid_u_;
    const double edge = at_front ? across.front() : across.back();
    const double step =
        at_front ? across[1] - across[0] : across[across.size() - 2] - across.back();
    Pole pole{in_u ? surface_.point(edge, along.front()) : surface_.point(along.front(), edge), 0};
    const double first_row = at_front ? across[1] : across[across.size() - 2];
    for (double t : along)
      pole.reach = std::max(
          pole.reach,
          ((in_u ? surface_.point(first_row, t) : surface_.point(t, first_row)) - pole.point)
              .norm());
    poles_.push_back(pole);
    for (double fraction : {1.0 / 32, 1.0 / 16, 1.0 / 8, 1.0 / 4, 1.0 / 2}) {
      PoleRing ring;
      for (std::size_t k = 0; k + 1 < along.size(); ++k)
        for (int sub = 0; sub < 4; ++sub) {
          const double t = along[k] + (along[k + 1] - along[k]) * sub / 4.0;
          const double a = edge + fraction * step;
          ring.u.push_back(in_u ? a : t);
          ring.v.push_back(in_u ? t : a);
          ring.points.push_back(surface_.point(ring.u.back(), ring.v.back()));
        }
      pole_rings_.push_back(std::move(ring));
    }
  };
  if (pole_u_front_) add_rings(true, true);
  if (pole_u_back_) add_rings(true, false);
  if (pole_v_front_) add_rings(false, true);
  if (pole_v_back_) add_rings(false, false);
}

bool SurfaceLocator::on_pole_edge(double u, double v) const {
  return (pole_u_front_ && u <= surface_.front_u()) || (pole_u_back_ && u >= surface_.back_u()) ||
         (pole_v_front_ && v <= surface_.front_v()) || (pole_v_back_ && v >= surface_.back_v());
}

bool SurfaceLocator::leave_pole(const Vector3d& p, double& u, double& v) const {
  // Directions out of a pole are the non-vanishing partials along the edge's samples: for
  // a pole at u = const these are ±S_u(u_pole, v) over v. Take the steepest descent of
  // |S − p|², then back off along it until the distance really drops.
  const bool pole_in_u =
      (pole_u_front_ && u <= surface_.front_u()) || (pole_u_back_ && u >= surface_.back_u());
  const Vector3d r = surface_.point(u, v) - p;
  const double f = r.squaredNorm();
  const std::vector<double>& along = pole_in_u ? grid_v_ : grid_u_;
  double best_slope = 0, best_param = 0;
  for (double s : along) {
    const SurfaceDerivatives d =
        pole_in_u ? surface_.evaluate(u, s, 1) : surface_.evaluate(s, v, 1);
    const Vector3d inward = pole_in_u ? Vector3d(u <= surface_.front_u() ? d.su : -d.su)
                                      : Vector3d(v <= surface_.front_v() ? d.sv : -d.sv);
    const double n = inward.norm();
    if (n == 0) continue;
    const double slope = inward.dot(r) / n;
    if (slope < best_slope) {
      best_slope = slope;
      best_param = s;
    }
  }
  if (!(best_slope < -options_.cosine_tolerance * std::sqrt(f))) return false;
  const double range =
      pole_in_u ? surface_.back_u() - surface_.front_u() : surface_.back_v() - surface_.front_v();
  for (double h = 0.05 * range; h > 1e-12 * range; h *= 0.5) {
    double un = u, vn = v;
    if (pole_in_u) {
      un = u <= surface_.front_u() ? u + h : u - h;
      vn = best_param;
    } else {
      vn = v <= surface_.front_v() ? v + h : v - h;
      un = best_param;
    }
    if ((surface_.point(un, vn) - p).squaredNorm() < f) {
      u = un;
      v = vn;
      return true;
    }
  }
  return false;
}

void SurfaceLocator::wrap_or_clamp(double& u, double& v) const {
  const auto fix = [](double& x, double lo, double hi, bool closed) {
    if (closed) {
      const double period = hi - lo;
      if (x < lo || x > hi) x = lo + (x - lo) - period * std::floor((x - lo) / period);
    } else {
      x = std::clamp(x, lo, hi);
    }
  };
  fix(u, surface_.front_u(), surface_.back_u(), closed_u_);
  fix(v, surface_.front_v(), surface_.back_v(), closed_v_);
}

}  // namespace freeturn::nurbs
