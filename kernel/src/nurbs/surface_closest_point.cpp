// Point inversion on a NURBS surface (The NURBS Book §6.1, with damping and an active
// set for the boundary; see surface_locator.hpp).

#include <algorithm>
#include <array>
#include <cmath>

#include "freeturn/nurbs/surface_locator.hpp"
#include "surface_locator_grid.hpp"

namespace freeturn::nurbs {

SurfacePointResult SurfaceLocator::closest_point(const Vector3d& p, double u, double v) const {
  const double u_lo = surface_.front_u(), u_hi = surface_.back_u();
  const double v_lo = surface_.front_v(), v_hi = surface_.back_v();
  wrap_or_clamp(u, v);
  SurfaceDerivatives d = surface_.evaluate(u, v, 2);
  Vector3d r = d.point - p;
  double f = r.squaredNorm();
  double lambda = 0;  // Levenberg–Marquardt damping, relative to the metric (E + G)/2
  SurfacePointResult res;
  res.status = Status::kNotConverged;
  for (int it = 0; it < options_.max_iterations; ++it) {
    res.iterations = it;
    const double dist = std::sqrt(f);
    if (dist <= options_.point_tolerance) {  // coincidence
      res.status = Status::kOk;
      break;
    }
    double gu = d.su.dot(r), gv = d.sv.dot(r);
    // Active set: a parameter on its bound whose gradient points out of the domain stays
    // there, and the step is taken along the edge in the other parameter.
    const bool free_u = closed_u_ || !((u <= u_lo && gu > 0) || (u >= u_hi && gu < 0));
    const bool free_v = closed_v_ || !((v <= v_lo && gv > 0) || (v >= v_hi && gv < 0));
    // Zero cosine: S − P is normal to the surface in every free direction. A partial that
    // vanishes (a pole) has no direction to test.
    const double nu = d.su.norm(), nv = d.sv.norm();
    const double scale = 1e-9 * (nu + nv);
    const bool ok_u =
        !free_u || nu <= scale || std::abs(gu) <= options_.cosine_tolerance * nu * dist;
    const bool ok_v =
        !free_v || nv <= scale || std::abs(gv) <= options_.cosine_tolerance * nv * dist;
    if (ok_u && ok_v) {
      if (on_pole_edge(u, v) && leave_pole(p, u, v)) {
        d = surface_.evaluate(u, v, 2);
        r = d.point - p;
        f = r.squaredNorm();
        continue;
      }
      res.status = Status::kOk;
      break;
    }
    double huu = d.su.squaredNorm() + d.suu.dot(r);
    double huv = d.su.dot(d.sv) + d.suv.dot(r);
    double hvv = d.sv.squaredNorm() + d.svv.dot(r);
    if (!free_u) {
      huu = 1;
      huv = 0;
      gu = 0;
    }
    if (!free_v) {
      hvv = 1;
      huv = 0;
      gv = 0;
    }
    const double metric = std::max(0.5 * (d.su.squaredNorm() + d.sv.squaredNorm()), 1e-300);
    bool accepted = false;
    double step_length = 0;
    for (int tries = 0; tries < 30; ++tries) {
      const double a = huu + lambda * metric, c = hvv + lambda * metric;
      const double det = a * c - huv * huv;
      if (!(a > 0 && c > 0 && det > 0)) {  // not positive definite: damp harder
        lambda = std::max(4 * lambda, 1e-3);
        continue;
      }
      const double du = (-gu * c + gv * huv) / det;
      const double dv = (-gv * a + gu * huv) / det;
      double un = u + du, vn = v + dv;
      wrap_or_clamp(un, vn);
      const SurfaceDerivatives dn = surface_.evaluate(un, vn, 2);
      const Vector3d rn = dn.point - p;
      const double fn = rn.squaredNorm();
      step_length = (dn.point - d.point).norm();
      // Near the answer f changes by less than its rounding error while the point can
      // still move by 1e-9 mm; there the gradient's size decides instead.
      const double g_old = gu * gu + gv * gv;
      const double gun = free_u ? dn.su.dot(rn) : 0.0, gvn = free_v ? dn.sv.dot(rn) : 0.0;
      const bool flat = fn <= f * (1 + 1e-13) && gun * gun + gvn * gvn < 0.25 * g_old;
      if (fn < f || flat) {
        u = un;
        v = vn;
        d = dn;
        r = rn;
        f = fn;
        lambda *= 0.1;
        if (lambda < 1e-12) lambda = 0;
        accepted = true;
        break;
      }
      if (step_length <= 1e-15 * (1 + d.point.norm())) break;  // no representable progress
      lambda = std::max(4 * lambda, 1e-3);
    }
    // A step that moves the point by nothing representable ends the iteration: the
    // answer is as good as double precision allows.
    const bool stalled = step_length <= 1e-15 * (1 + d.point.norm());
    if (!accepted || stalled) {
      res.status = stalled ? Status::kOk : Status::kNotConverged;
      break;
    }
  }
  res.u = u;
  res.v = v;
  res.point = d.point;
  res.distance = std::sqrt(f);
  return res;
}

SurfacePointResult SurfaceLocator::closest_point(const Vector3d& p) const {
  thread_local std::vector<int> seeds;
  best_grid_minima([&](const Vector3d& q) { return (q - p).squaredNorm(); },
                   [&](const Eigen::AlignedBox3d& box) { return box.squaredExteriorDistance(p); },
                   options_.cold_seeds, seeds);
  const int nv = static_cast<int>(grid_v_.size());
  SurfacePointResult best;
  best.distance = INFINITY;
  // Newton from one seed; the closer answer wins, and iterations add up over all seeds.
  const auto refine_from = [&](double u, double v) {
    const SurfacePointResult r = closest_point(p, u, v);
    const int iterations = best.iterations + r.iterations;
    if (r.distance < best.distance || (r.distance == best.distance && best.status != Status::kOk))
      best = r;
    best.iterations = iterations;
  };
  for (int k : seeds) {
    // Seeds come best first; one too far to beat the answer so far ends the search.
    if ((grid_points_[k] - p).norm() - cell_size_ > best.distance) break;
    refine_from(grid_u_[k / nv], grid_v_[k % nv]);
  }
  // Near a pole, seeds from the fine rings around it: a local minimum along a ring is a
  // direction out of the pole with a basin of its own. Nothing within a pole's reach can
  // be closer than |p − pole| − reach.
  bool near_pole = false;
  for (const Pole& pole : poles_)
    near_pole = near_pole || (pole.point - p).norm() - pole.reach <= best.distance;
  if (!near_pole) return best;
  std::array<std::pair<double, std::pair<int, int>>, 4> minima;  // d², (ring, index)
  minima.fill({INFINITY, {-1, -1}});
  for (int r = 0; r < static_cast<int>(pole_rings_.size()); ++r) {
    const PoleRing& ring = pole_rings_[r];
    const int n = static_cast<int>(ring.points.size());
    for (int k = 0; k < n; ++k) {
      const double d = (ring.points[k] - p).squaredNorm();
      if (d >= minima.back().first || (k > 0 && (ring.points[k - 1] - p).squaredNorm() < d) ||
          (k + 1 < n && (ring.points[k + 1] - p).squaredNorm() < d))
        continue;
      minima.back() = {d, {r, k}};
      std::sort(minima.begin(), minima.end(),
                [](const auto& x, const auto& y) { return x.first < y.first; });
    }
  }
  for (const auto& [d, where] : minima) {
    if (where.first < 0) continue;
    const PoleRing& ring = pole_rings_[where.first];
    refine_from(ring.u[where.second], ring.v[where.second]);
  }
  return best;
}

}  // namespace freeturn::nurbs
