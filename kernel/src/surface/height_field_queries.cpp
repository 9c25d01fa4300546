#include "freeturn/surface/height_field_queries.hpp"

#include <cmath>

namespace freeturn {

HeightFieldHit intersect_ray(const Surface& surface, const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& direction, double t) {
  HeightFieldHit hit;
  const double len = direction.norm();
  if (!(len > 0)) {
    hit.status = Status::kDegenerate;
    return hit;
  }
  const Eigen::Vector3d d = direction / len;
  // The surface at the last point evaluated, and at the accepted one (the answer's: not
  // evaluated again).
  double z_last = 0, zx_last = 0, zy_last = 0, z_at = 0;
  const auto g = [&](double s, double& slope) {
    const Eigen::Vector3d q = origin + s * d;
    surface.sag_gradient(q.x(), q.y(), z_last, zx_last, zy_last);
    slope = d.z() - zx_last * d.x() - zy_last * d.y();
    return q.z() - z_last;
  };
  const auto accept = [&] {
    z_at = z_last;
    hit.zx = zx_last;
    hit.zy = zy_last;
  };
  if (std::isnan(t)) {
    const double z0 = surface.sag(origin.x(), origin.y());
    t = std::abs(d.z()) > 1e-12 ? (origin.z() - z0) / -d.z() : 0.0;
    if (!std::isfinite(t)) t = 0.0;
  } else {
    t *= len;
  }
  double slope;
  double value = g(t, slope);
  accept();
  const double tolerance = 1e-14 * (1 + origin.norm() + std::abs(t));
  hit.status = Status::kNotConverged;
  for (int it = 0; it < 60; ++it) {
    hit.iterations = it;
    if (!std::isfinite(value)) {
      hit.status = Status::kMissed;
      break;
    }
    if (std::abs(value) <= tolerance) {
      hit.status = Status::kOk;
      break;
    }
    if (!(std::abs(slope) > 1e-12)) {
      hit.status = Status::kDegenerate;
      break;
    }
    // Newton, halved until |g| decreases (or the step leaves the defined region).
    double step = -value / slope;
    bool improved = false;
    for (int k = 0; k < 40; ++k, step *= 0.5) {
      double slope_new;
      const double value_new = g(t + step, slope_new);
      if (std::isfinite(value_new) && std::abs(value_new) < std::abs(value)) {
        t += step;
        value = value_new;
        slope = slope_new;
        accept();
        improved = true;
        break;
      }
    }
    if (!improved) {
      hit.status = std::abs(value) <= 1e3 * tolerance ? Status::kOk : Status::kMissed;
      break;
    }
  }
  const Eigen::Vector3d q = origin + t * d;
  hit.point = {q.x(), q.y(), z_at};
  hit.t = t / len;
  return hit;
}

HeightFieldPoint closest_point(const Surface& surface, const Eigen::Vector3d& p, double x,
                               double y) {
  HeightFieldPoint res;
  HeightDerivatives h = surface.height_derivatives(x, y);
  const auto objective = [&](double xx, double yy, double zz) {
    return 0.5 * ((xx - p.x()) * (xx - p.x()) + (yy - p.y()) * (yy - p.y()) +
                  (zz - p.z()) * (zz - p.z()));
  };
  double f = objective(x, y, h.z);
  double lambda = 0;
  for (int it = 0; it < 60; ++it) {
    res.iterations = it;
    if (!std::isfinite(f)) {
      res.status = Status::kMissed;
      break;
    }
    const double e = h.z - p.z();
    const double gx = x - p.x() + e * h.zx, gy = y - p.y() + e * h.zy;
    // Zero cosine: the offset p − S is along the normal (−zx, −zy, 1).
    const double dist = std::sqrt(2 * f);
    if (dist <= 1e-13 ||
        std::hypot(gx, gy) <= 1e-14 * dist * std::sqrt(1 + h.zx * h.zx + h.zy * h.zy)) {
      res.status = Status::kOk;
      break;
    }
    const double hxx = 1 + h.zx * h.zx + e * h.zxx, hxy = h.zx * h.zy + e * h.zxy,
                 hyy = 1 + h.zy * h.zy + e * h.zyy;
    bool accepted = false;
    double moved = 0;
    for (int tries = 0; tries < 40; ++tries) {
      const double a = hxx + lambda, c = hyy + lambda, det = a * c - hxy * hxy;
      if (!(a > 0 && det > 0)) {
        lambda = std::max(4 * lambda, 1e-3);
        continue;
      }
      const double dx = (-gx * c + gy * hxy) / det, dy = (-gy * a + gx * hxy) / det;
      const HeightDerivatives hn = surface.height_derivatives(x + dx, y + dy);
      const double fn = objective(x + dx, y + dy, hn.z);
      moved = std::hypot(dx, dy);
      const double en = hn.z - p.z();
      const double gn = std::hypot(x + dx - p.x() + en * hn.zx, y + dy - p.y() + en * hn.zy);
      if (std::isfinite(fn) &&
          (fn < f || (fn <= f * (1 + 1e-13) && gn < 0.5 * std::hypot(gx, gy)))) {
        x += dx;
        y += dy;
        h = hn;
        f = fn;
        lambda *= 0.1;
        if (lambda < 1e-12) lambda = 0;
        accepted = true;
        break;
      }
      if (moved <= 1e-15 * (1 + std::abs(x) + std::abs(y))) break;
      lambda = std::max(4 * lambda, 1e-3);
    }
    if (!accepted || moved <= 1e-15 * (1 + std::abs(x) + std::abs(y))) {
      res.status = accepted || moved <= 1e-15 * (1 + std::abs(x) + std::abs(y))
                       ? Status::kOk
                       : Status::kNotConverged;
      break;
    }
  }
  res.point = {x, y, h.z};
  res.distance = (res.point - p).norm();
  return res;
}

}  // namespace freeturn
