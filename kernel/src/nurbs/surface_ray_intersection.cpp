// Ray–surface intersection: Newton on F(u, v, t) = S(u, v) − (O + t·D) = 0 with the
// Jacobian [S_u, S_v, −D], backtracking on |F|, and the domain enforced by clamping (or
// wrapping on closed directions).

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "freeturn/nurbs/surface_locator.hpp"
#include "surface_locator_grid.hpp"

namespace freeturn::nurbs {

RayHit SurfaceLocator::intersect_ray(const Vector3d& origin, const Vector3d& direction, double u,
                                     double v) const {
  RayHit hit;
  const double len = direction.norm();
  if (!(len > 0)) {
    hit.status = Status::kDegenerate;
    return hit;
  }
  const Vector3d dir = direction / len;
  wrap_or_clamp(u, v);
  SurfaceDerivatives d = surface_.evaluate(u, v, 1);
  double t = (d.point - origin).dot(dir);
  Vector3d F = d.point - origin - t * dir;
  double fn = F.norm();
  const double tolerance = std::max(options_.point_tolerance, 4e-16 * (1 + d.point.norm()));
  int stuck = 0, nudges = 0;
  hit.status = Status::kNotConverged;
  for (int it = 0; it < options_.max_iterations; ++it) {
    hit.iterations = it;
    if (fn <= tolerance) {
      hit.status = Status::kOk;
      break;
    }
    Eigen::Matrix3d J;
    J << d.su, d.sv, -dir;
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(J);
    const double scale = d.su.norm() * d.sv.norm();
    if (!(std::abs(J.determinant()) > 1e-14 * scale)) {
      if (on_pole_edge(u, v) && nudges++ < 3) {
        // At a pole the Jacobian is singular whatever the ray; start again just inside.
        if (pole_u_front_ && u <= surface_.front_u())
          u += 1e-3 * (surface_.back_u() - surface_.front_u());
        if (pole_u_back_ && u >= surface_.back_u())
          u -= 1e-3 * (surface_.back_u() - surface_.front_u());
        if (pole_v_front_ && v <= surface_.front_v())
          v += 1e-3 * (surface_.back_v() - surface_.front_v());
        if (pole_v_back_ && v >= surface_.back_v())
          v -= 1e-3 * (surface_.back_v() - surface_.front_v());
        d = surface_.evaluate(u, v, 1);
        F = d.point - origin - t * dir;
        fn = F.norm();
        continue;
      }
      hit.status = Status::kDegenerate;  // the ray is tangent to the surface
      break;
    }
    Vector3d delta = lu.solve(-F);
    // Fraction to the boundary: a step that would leave the domain of an open direction
    // is shortened to stop short of the edge (0.9 of the way), so that the iteration
    // creeps toward an edge it must reach and is not thrown onto a pole. On the edge and
    // pushed outward, the step slides along the edge instead.
    double alpha_max = 1.0;
    bool limited = false, pinned = false;
    const auto limit = [&](double x, double& dx, double lo, double hi, bool closed) {
      if (closed || dx == 0) return;
      const double room = dx > 0 ? hi - x : lo - x;  // same sign as dx, or 0
      if (std::abs(dx) <= std::abs(room)) return;
      limited = true;
      if (room == 0) {
        dx = 0;
        pinned = true;
      } else {
        alpha_max = std::min(alpha_max, 0.9 * room / dx);
      }
    };
    limit(u, delta.x(), surface_.front_u(), surface_.back_u(), closed_u_);
    limit(v, delta.y(), surface_.front_v(), surface_.back_v(), closed_v_);
    // Pinned to a corner: the hit is outside the domain. A step of zero in u and v that
    // no edge made is Newton's own, where only t is left to settle (S_x and S_y met
    // exactly, as on a surface whose x and y are affine in u and v): that is no miss.
    if (pinned && delta.x() == 0 && delta.y() == 0) {
      hit.status = Status::kMissed;
      break;
    }
    // Backtracking: halve the step until |F| decreases.
    double alpha = alpha_max;
    bool improved = false;
    double un = u, vn = v, tn = t;
    SurfaceDerivatives dn;
    Vector3d Fn;
    for (int k = 0; k < 30; ++k, alpha *= 0.5) {
      un = u + alpha * delta.x();
      vn = v + alpha * delta.y();
      wrap_or_clamp(un, vn);
      dn = surface_.evaluate(un, vn, 1);
      tn = t + alpha * delta.z();
      Fn = dn.point - origin - tn * dir;
      if (Fn.norm() < fn) {
        improved = true;
        break;
      }
    }
    if (!improved) {
      hit.status = fn <= 1e3 * tolerance ? Status::kOk : Status::kMissed;
      break;
    }
    // Held back by an edge without closing in: the ray passes outside the domain.
    stuck = (limited && Fn.norm() > 0.5 * fn) ? stuck + 1 : 0;
    u = un;
    v = vn;
    t = tn;
    d = dn;
    F = Fn;
    fn = F.norm();
    if (stuck >= 8) {
      hit.status = Status::kMissed;
      break;
    }
  }
  if (hit.status == Status::kNotConverged && fn > 1e-6) hit.status = Status::kMissed;
  hit.u = u;
  hit.v = v;
  hit.t = t / len;
  hit.point = d.point;
  return hit;
}

RayHit SurfaceLocator::intersect_ray(const Vector3d& origin, const Vector3d& direction) const {
  RayHit best;
  const double len = direction.norm();
  if (!(len > 0)) {
    best.status = Status::kDegenerate;
    return best;
  }
  const Vector3d dir = direction / len;
  thread_local std::vector<int> seeds;
  // Seeds: samples closest to the line, each a local minimum of that distance.
  best_grid_minima(
      [&](const Vector3d& q) {
        const Vector3d w = q - origin;
        return (w - w.dot(dir) * dir).squaredNorm();
      },
      [&](const Eigen::AlignedBox3d& box) {  // through the box's bounding sphere
        const Vector3d w = box.center() - origin;
        const double gap =
            std::max(0.0, (w - w.dot(dir) * dir).norm() - 0.5 * box.diagonal().norm());
        return gap * gap;
      },
      options_.cold_seeds, seeds);
  const int nv = static_cast<int>(grid_v_.size());
  int iterations = 0;
  for (int k : seeds) {
    const RayHit h = intersect_ray(origin, direction, grid_u_[k / nv], grid_v_[k % nv]);
    iterations += h.iterations;
    if (h.status != Status::kOk) continue;
    if (best.status != Status::kOk || std::abs(h.t) < std::abs(best.t)) best = h;
  }
  best.iterations = iterations;
  return best;
}

}  // namespace freeturn::nurbs
