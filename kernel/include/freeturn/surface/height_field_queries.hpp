#pragma once
// Ray intersection and closest point for any height-field surface, by Newton's method on
// the sag (the NURBS kernel's locator does the same for parametric surfaces).

#include <limits>

#include "freeturn/core/status.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct HeightFieldHit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the surface
  double zx = 0, zy = 0;  // the surface's gradient at point (its last evaluation)
  double t = 0;  // origin + t·direction = point (t in units of |direction|)
  Status status = Status::kMissed;
  int iterations = 0;
};

// The hit of the ray origin + t·direction with z = f(x, y), Newton on
// g(t) = o_z + t d_z − f(o_x + t d_x, o_y + t d_y) from t_start (warm) or, when t_start is
// NaN, from where the ray meets the height of the surface under its origin. kMissed when
// the ray leaves the region where the surface is defined or Newton finds no root;
// kDegenerate for a zero direction or a ray tangent to the surface.
HeightFieldHit intersect_ray(const Surface& surface, const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& direction,
                             double t_start = std::numeric_limits<double>::quiet_NaN());

struct HeightFieldPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // (x, y, f(x, y))
  double distance = 0;
  Status status = Status::kNotConverged;
  int iterations = 0;
};

// The closest point of z = f(x, y) to p near (x_start, y_start): damped Newton on
// |(x, y, f) − p|²/2 (Levenberg–Marquardt where the Hessian is not positive definite).
HeightFieldPoint closest_point(const Surface& surface, const Eigen::Vector3d& p, double x_start,
                               double y_start);
// The same, started under p.
inline HeightFieldPoint closest_point(const Surface& surface, const Eigen::Vector3d& p) {
  return closest_point(surface, p, p.x(), p.y());
}

}  // namespace freeturn
