#pragma once
// A parent surface decentred and tilted: off-axis segments (an off-axis parabola first).
//
// A world point W (workpiece frame) and the parent-frame point X are related by
//   X = Rᵀ W + o,
// where o is the parent point placed on the spindle axis at the world origin (the
// decentre, with its sag, so the segment's vertex sits at z = 0) and R the tilt. The world
// sag z(x, y) solves G(x, y, z) = F(Rᵀ(x, y, z) + o) = 0 with F(X) = X_z − f(X_x, X_y), by
// Newton in z; its gradient and Hessian follow from implicit differentiation:
//   z_x = −G_x / G_z,   z_xx = −(G_xx + 2 G_xz z_x + G_zz z_x²) / G_z,   …
// with ∇G = R ∇F and ∇²G = R ∇²F Rᵀ.

#include <Eigen/Geometry>
#include <memory>

#include "freeturn/surface/projected_rims.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

class TransformedSurface final : public Surface {
 public:
  // decentre_x/y: parent coordinates (mm) of the point that lands on the axis.
  // rotation: R (tilt) from the parent frame to the world frame.
  TransformedSurface(std::unique_ptr<Surface> parent, double decentre_x, double decentre_y,
                     const Eigen::Matrix3d& rotation);

  // The tilt that makes the parent's normal at the decentred point the world +z axis (a
  // segment cut "on its own axis").
  static Eigen::Matrix3d rotation_aligning_normal(const Surface& parent, double x, double y);
  // Rotation about x by angle_x, then about y by angle_y (radians).
  static Eigen::Matrix3d rotation_from_tilts(double angle_x, double angle_y);

  const char* type() const override { return parent_->type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;
  bool has_creases() const override { return parent_->has_creases(); }
  bool may_have_ridges() const override { return parent_->may_have_ridges(); }
  // Decentred without a tilt, the world is the parent moved in (x, y) (and down by the
  // decentred point's sag): a radial section is the parent's line through the decentred
  // point, whose creases the parent may know (Surface::line_creases: a microlens array's
  // rims), and the creases near a point and the bend are the parent's there. Tilted (or
  // where the parent knows no line off its axis: a compound eye's sphere), a parent whose
  // creases are circles in space (Surface::crease_circles: lenslet rims) has them moved
  // and seen along z as ellipses (ProjectedRims), and a section's crossings are found in
  // closed form. Otherwise no crease is reported: the planner neither holds nor rolls the
  // nose there, counts the jumps it finds (UNSAFE), and the global gouge check judges
  // those places. Tilted, the creases near a point are not known, and the bend is bounded
  // from the parent's slope and bend where the parent bounds both (max_bend).
  int section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                      std::span<double> out) const override;
  int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const override;
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;

  const Surface& parent() const { return *parent_; }
  // The parent-frame point of world point w.
  Eigen::Vector3d to_parent(const Eigen::Vector3d& w) const { return rt_ * w + origin_; }

 private:
  // Solves for the world sag at (x, y); returns the parent derivatives at the answer and
  // G_z, or NaN in z if Newton fails (the vertical line misses the parent).
  double solve(double x, double y, HeightDerivatives& parent_at, int order) const;

  std::unique_ptr<Surface> parent_;
  Eigen::Vector3d origin_;
  Eigen::Matrix3d r_, rt_;
  bool untilted_ = false;  // R is the identity: a translation alone
  // The parent's crease circles as the world sees them, where line_creases cannot serve.
  ProjectedRims rims_;
};

}  // namespace freeturn
