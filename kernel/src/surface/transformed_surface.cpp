#include "freeturn/surface/transformed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace freeturn {

TransformedSurface::TransformedSurface(std::unique_ptr<Surface> parent, double decentre_x,
                                       double decentre_y, const Eigen::Matrix3d& rotation)
    : parent_(std::move(parent)), r_(rotation), rt_(rotation.transpose()) {
  origin_ = {decentre_x, decentre_y, parent_->sag(decentre_x, decentre_y)};
  untilted_ = r_ == Eigen::Matrix3d::Identity();
  // The rims' ellipses, where the parent's own lines cannot give the sections' creases.
  if (parent_->has_creases()) {
    double probe[1];
    const bool lines_known =
        untilted_ &&
        parent_->line_creases(origin_.x(), origin_.y(), RadialLine(0.0), 0.0, 0.0, probe) >= 0;
    std::vector<CreaseCircle> circles;
    if (!lines_known && parent_->crease_circles(circles)) rims_.build(circles, r_, origin_);
  }
}

int TransformedSurface::section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                                        std::span<double> out) const {
  if (untilted_) {
    const int count = parent_->line_creases(origin_.x(), origin_.y(), line, rho_lo, rho_hi, out);
    if (count >= 0) return count;
  }
  // The rims seen along z; none known: none reported.
  return rims_.crossings(0.0, 0.0, line, rho_lo, rho_hi, out);
}

int TransformedSurface::creases_near(double x, double y, double radius,
                                     std::span<NearbyCrease> out) const {
  if (!untilted_) return Surface::creases_near(x, y, radius, out);
  return parent_->creases_near(x + origin_.x(), y + origin_.y(), radius, out);
}

double TransformedSurface::max_slope(double radius) const {
  if (!untilted_) return Surface::max_slope(radius);
  return parent_->max_slope(radius + std::hypot(origin_.x(), origin_.y()));
}

// Tilted, from the parent's slope and bend. A graph z(x, y) bends along a unit direction u
// by uᵀHu = κ_n·√(1 + |∇z|²)·(1 + (∇z·u)²), κ_n the normal curvature along the surface's
// tangent over u (the second fundamental form over the first). κ_n is the surface's own,
// the same in either frame while both normals point up, and in the parent's frame
// κ_n ≤ max(λ_max(H_parent), 0) (its denominators are at least 1). So the world bends at
// most max(B_parent, 0)/cos³θ, θ the world normal's largest angle from z: at most the
// parent normal's angle from its z, atan(S_parent), plus the tilt τ between the two z axes
// (the angles of a triangle on the sphere).
//
// Where on the parent: a world point w = (x, y, z) within r of the axis lands at
// Rᵀw + o, within |w| of the decentred point, and |z| ≤ r·tan θ (the sag is 0 at the
// axis), so within ρ_o + r/cos θ of the parent's axis, ρ_o = |o_xy|. A reach ρ with
// ρ_o + r/cos θ(ρ) < ρ holds the whole disc: a path out from the axis that first met ρ
// would have met it within that sum. Such a reach is found by iterating the sum upward.
double TransformedSurface::max_bend(double radius) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double from_axis = std::hypot(origin_.x(), origin_.y());
  if (untilted_) return parent_->max_bend(radius + from_axis);
  if (!(radius >= 0) || !std::isfinite(radius)) return kInfinity;
  const double tilt = std::acos(std::clamp(rt_(2, 2), -1.0, 1.0));
  double reach = from_axis + radius;
  for (int it = 0; it < 64; ++it) {
    const double angle = tilt + std::atan(parent_->max_slope(reach));
    if (!(angle < 0.49 * std::numbers::pi)) return kInfinity;
    const double cos_angle = std::cos(angle);
    const double needed = from_axis + radius / cos_angle;
    if (needed < reach) {
      const double bend = std::max(parent_->max_bend(reach), 0.0);
      if (!(bend < kInfinity)) return kInfinity;
      return bend / (cos_angle * cos_angle * cos_angle) * (1 + 1e-12);
    }
    reach = needed * (1 + 1e-3) + 1e-9;
  }
  return kInfinity;
}

Eigen::Matrix3d TransformedSurface::rotation_aligning_normal(const Surface& parent, double x,
                                                             double y) {
  const Eigen::Vector3d n = parent.normal(x, y);
  // The rotation taking n to +z, about the axis n × z.
  return Eigen::Quaterniond::FromTwoVectors(n, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d TransformedSurface::rotation_from_tilts(double angle_x, double angle_y) {
  return (Eigen::AngleAxisd(angle_y, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(angle_x, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double TransformedSurface::solve(double x, double y, HeightDerivatives& h, int order) const {
  // Newton on g(z) = F(X(z)), X(z) = Rᵀ(x, y, z) + o, dX/dz = Rᵀ e_z.
  const Eigen::Vector3d dx_dz = rt_.col(2);
  double z = 0;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector3d X = to_parent({x, y, z});
    if (order >= 2) {
      h = parent_->height_derivatives(X.x(), X.y());
    } else {
      parent_->sag_gradient(X.x(), X.y(), h.z, h.zx, h.zy);
    }
    const double g = X.z() - h.z;
    const double gz = dx_dz.z() - h.zx * dx_dz.x() - h.zy * dx_dz.y();
    if (!std::isfinite(g) || !(std::abs(gz) > 1e-12)) break;
    const double step = g / gz;
    z -= step;
    // The parent coordinates carry the decentre, so rounding limits z to about
    // 1e-16 of their size; Newton's step settles there.
    if (std::abs(step) <= 1e-14 * (1 + origin_.norm() + std::abs(x) + std::abs(y) + std::abs(z))) {
      // One more evaluation at the final z keeps h consistent with the answer; where the
      // last step left the parent point where it was (a third of the calls on an
      // off-axis paraboloid), h is already its evaluation there.
      const Eigen::Vector3d Xf = to_parent({x, y, z});
      if (Xf.x() == X.x() && Xf.y() == X.y()) return z;
      if (order >= 2)
        h = parent_->height_derivatives(Xf.x(), Xf.y());
      else
        parent_->sag_gradient(Xf.x(), Xf.y(), h.z, h.zx, h.zy);
      return z;
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void TransformedSurface::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  HeightDerivatives h;
  z = solve(x, y, h, 1);
  const Eigen::Vector3d grad = r_ * Eigen::Vector3d(-h.zx, -h.zy, 1.0);  // ∇_W G
  zx = -grad.x() / grad.z();
  zy = -grad.y() / grad.z();
}

HeightDerivatives TransformedSurface::height_derivatives(double x, double y) const {
  HeightDerivatives h;
  HeightDerivatives out;
  out.z = solve(x, y, h, 2);
  const Eigen::Vector3d g = r_ * Eigen::Vector3d(-h.zx, -h.zy, 1.0);
  Eigen::Matrix3d hf = Eigen::Matrix3d::Zero();  // ∇²F = −∇²f in the xy block
  hf(0, 0) = -h.zxx;
  hf(0, 1) = hf(1, 0) = -h.zxy;
  hf(1, 1) = -h.zyy;
  const Eigen::Matrix3d hg = r_ * hf * rt_;
  out.zx = -g.x() / g.z();
  out.zy = -g.y() / g.z();
  out.zxx = -(hg(0, 0) + 2 * hg(0, 2) * out.zx + hg(2, 2) * out.zx * out.zx) / g.z();
  out.zxy =
      -(hg(0, 1) + hg(0, 2) * out.zy + hg(1, 2) * out.zx + hg(2, 2) * out.zx * out.zy) / g.z();
  out.zyy = -(hg(1, 1) + 2 * hg(1, 2) * out.zy + hg(2, 2) * out.zy * out.zy) / g.z();
  return out;
}

}  // namespace freeturn
