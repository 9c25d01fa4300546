#pragma once
// An independent check of chord errors: the machine's linear motion in (X, C, Z) between
// consecutive contact points, sampled densely, against the design surface.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "freeturn/path/contact_point.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::test {

// The largest distance from the surface over every segment, 200 samples each.
inline double densest_chord_error(const Surface& s, const std::vector<ContactPoint>& path,
                                  int samples = 200) {
  double worst = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const ContactPoint &a = path[k - 1], &b = path[k];
    for (int j = 1; j < samples; ++j) {
      const double t = static_cast<double>(j) / samples;
      const double r = a.r + t * (b.r - a.r), c = a.theta + t * (b.theta - a.theta),
                   z = a.point.z() + t * (b.point.z() - a.point.z());
      double f, fx, fy;
      s.sag_gradient(r * std::cos(c), r * std::sin(c), f, fx, fy);
      worst = std::max(worst, std::abs(z - f) / std::sqrt(1 + fx * fx + fy * fy));
    }
  }
  return worst;
}

}  // namespace freeturn::test

#include "freeturn/tool/compensation.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn::test {

// The same for the tool: the nose centre moving linearly in (radial position, C, z)
// between cutter locations, its lower arc of radius R in the radial plane, against the
// design's section there. At each of `samples` points of each segment the arc's overlap
// with the section, max over ρ of f(ρ) − (c_z − √(R² − (ρ − c_ρ)²)), is found by brute
// force (`grid` values of ρ across the nose, then golden section about the best), and
// scaled to the normal by 1/√(1 + |∇f|²). Returns the largest |overlap|. With `axes`, the
// programmed axes X, Z, B are interpolated instead and the centre found from them (a B
// pivot swinging the nose on an arc). With `pvt`, the controller's cubics instead of lines:
// each block's velocity the central difference of its neighbours over their times (Δθ on a
// spiral at one speed, the X-Z chord at one feed in profile mode), one-sided at the ends,
// and a cubic Hermite in time through each block, for every coordinate. With
// `only_segment` = k > 0, the segment that ends at block k alone, its cubics' velocities
// still from the whole path. With `section_normal`, the overlap is scaled to the normal of
// the radial section, 1/√(1 + f_ρ²), as the planner measures it, instead of the surface's.
struct DenseNoseFigures {
  double worst = 0;  // the largest |overlap| (mm, normal): the chord error
  double gouge = 0;  // the largest overlap > 0 (mm, normal): how deep the nose cuts into the design
  // The nose's distance above the design (mm, normal; < 0 below it), least and largest.
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -std::numeric_limits<double>::infinity();
};

inline DenseNoseFigures dense_nose_figures(const Surface& s,
                                           const std::vector<CutterLocation>& path, double R,
                                           int samples = 50, int grid = 400,
                                           const CompensationOptions* axes = nullptr,
                                           bool pvt = false, std::size_t only_segment = 0,
                                           bool section_normal = false) {
  DenseNoseFigures figures;
  const auto radial = [](const Eigen::Vector3d& p, double c) { return p.x() * std::cos(c) + p.y() * std::sin(c); };
  // Per block: the coordinates that move (C, the centre's radial position and z, and the
  // axes X, Z, B), their times and, for PVT, their velocities.
  const std::size_t n = path.size();
  constexpr int kCoordinates = 6;
  std::vector<std::array<double, kCoordinates>> q(n), v(n);
  std::vector<double> time(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const CutterLocation& cl = path[k];
    q[k] = {cl.contact.theta, radial(cl.nose_centre, cl.contact.theta), cl.nose_centre.z(), cl.x, cl.z, cl.b};
    if (k > 0) {
      const double dc = q[k][0] - q[k - 1][0];
      time[k] = time[k - 1] + (dc != 0 ? dc : std::hypot(cl.x - path[k - 1].x, cl.z - path[k - 1].z));
    }
  }
  for (std::size_t k = 0; k < n && pvt; ++k) {
    const std::size_t lo = k > 0 ? k - 1 : 0, hi = k + 1 < n ? k + 1 : n - 1;
    const double dt = time[hi] - time[lo];
    for (int i = 0; i < kCoordinates; ++i) v[k][i] = dt > 0 ? (q[hi][i] - q[lo][i]) / dt : 0.0;
  }
  const auto motion = [&](std::size_t k, int i, double t) {
    const double qa = q[k - 1][i], qb = q[k][i];
    if (!pvt) return qa + t * (qb - qa);
    const double h = time[k] - time[k - 1], t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * qa + (t3 - 2 * t2 + t) * h * v[k - 1][i] + (-2 * t3 + 3 * t2) * qb +
           (t3 - t2) * h * v[k][i];
  };
  for (std::size_t k = 1; k < path.size(); ++k) {
    if (only_segment != 0 && k != only_segment) continue;  // the one ending at block k
    // The blocks themselves too (j = 0, and the last block): the nose must clear the
    // design there as well as between them.
    const int last = k + 1 == path.size() ? samples : samples - 1;
    for (int j = 0; j <= last; ++j) {
      const double t = static_cast<double>(j) / samples;
      const double c = motion(k, 0, t);
      double cr = motion(k, 1, t), cz = motion(k, 2, t);
      if (axes) {
        const Eigen::Vector2d centre = nose_centre_from_axes(motion(k, 3, t), motion(k, 4, t), motion(k, 5, t), *axes);
        cr = centre.x();
        cz = centre.y();
      }
      const double ct = std::cos(c), st = std::sin(c);
      const auto overlap = [&](double rho) {
        const double d = rho - cr;
        return s.sag(rho * ct, rho * st) - (cz - std::sqrt(std::max(0.0, R * R - d * d)));
      };
      double best_rho = cr, best = -1e300;
      for (int i = 0; i <= grid; ++i) {
        const double rho = cr - 0.98 * R + 1.96 * R * i / grid;
        const double v = overlap(rho);
        if (v > best) best = v, best_rho = rho;
      }
      double lo = best_rho - 1.96 * R / grid, hi = best_rho + 1.96 * R / grid;
      for (int it = 0; it < 60; ++it) {  // ternary search for the maximum
        const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (overlap(m1) > overlap(m2)) hi = m2;
        else lo = m1;
      }
      const double rho = 0.5 * (lo + hi);
      double f, fx, fy;
      s.sag_gradient(rho * ct, rho * st, f, fx, fy);
      const double slope_r = fx * ct + fy * st;
      const double normal =
          overlap(rho) / std::sqrt(1 + (section_normal ? slope_r * slope_r : fx * fx + fy * fy));
      figures.worst = std::max(figures.worst, std::abs(normal));
      figures.gouge = std::max(figures.gouge, normal);
      figures.lowest = std::min(figures.lowest, -normal);
      figures.highest = std::max(figures.highest, -normal);
    }
  }
  return figures;
}

// The material a spiral leaves, cut by brute force: at each of `columns` angles φ every
// pass's nose centre is interpolated linearly in (C, radial position, z) between the
// cutter locations whose C brackets φ (mod 2π), and at radii r_lo, r_lo + step, … ≤ r_hi
// the lowest of the noses' lower arcs (radius R) is compared with the design's sag, the
// difference scaled to the normal by 1/√(1 + |∇f|²). Returns the largest such residual
// (mm, > 0: material left) over the cells some nose reaches.
inline double dense_spiral_residual(const Surface& s, const std::vector<CutterLocation>& path,
                                    double R, int columns, double r_lo, double r_hi,
                                    double step) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  double worst = -1e300;
  std::vector<std::array<double, 2>> centres;  // (radial, z) of each pass at φ
  for (int j = 0; j < columns; ++j) {
    const double phi = kTwoPi * j / columns;
    centres.clear();
    for (std::size_t k = 1; k < path.size(); ++k) {
      const double ta = path[k - 1].contact.theta, tb = path[k].contact.theta;
      // The turn whose φ lies in [ta, tb): both candidates either side of (ta − φ)/2π, so
      // that a block on φ itself (equal angles, or steps of a cap that divides a turn) is
      // met by exactly one of its two segments: both compute the same t for the same turn,
      // where ceil((ta − φ)/2π) alone can round to different turns on either side.
      const double first = std::floor((ta - phi) / kTwoPi);
      double t = phi + first * kTwoPi;
      if (!(t >= ta && t < tb)) t = phi + (first + 1) * kTwoPi;
      if (!(t >= ta && t < tb)) continue;
      const double u = (t - ta) / (tb - ta);
      const auto radial = [&](const CutterLocation& cl) {
        return cl.nose_centre.x() * std::cos(cl.contact.theta) + cl.nose_centre.y() * std::sin(cl.contact.theta);
      };
      centres.push_back({radial(path[k - 1]) + u * (radial(path[k]) - radial(path[k - 1])),
                         path[k - 1].nose_centre.z() + u * (path[k].nose_centre.z() - path[k - 1].nose_centre.z())});
    }
    const double cp = std::cos(phi), sp = std::sin(phi);
    for (double rho = r_lo; rho <= r_hi; rho += step) {
      double lowest = 1e300;
      for (const auto& c : centres) {
        const double d = rho - c[0];
        if (std::abs(d) < R) lowest = std::min(lowest, c[1] - std::sqrt(R * R - d * d));
      }
      if (lowest == 1e300) continue;
      double f, fx, fy;
      s.sag_gradient(rho * cp, rho * sp, f, fx, fy);
      worst = std::max(worst, (lowest - f) / std::sqrt(1 + fx * fx + fy * fy));
    }
  }
  return worst;
}

inline double densest_nose_error(const Surface& s, const std::vector<CutterLocation>& path,
                                 double R, int samples = 50, int grid = 400,
                                 const CompensationOptions* axes = nullptr, bool pvt = false) {
  return dense_nose_figures(s, path, R, samples, grid, axes, pvt).worst;
}

}  // namespace freeturn::test
