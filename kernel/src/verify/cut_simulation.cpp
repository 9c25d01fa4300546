#include "freeturn/verify/cut_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "freeturn/core/error.hpp"

namespace freeturn {
namespace {

constexpr double kUncut = std::numeric_limits<double>::infinity();

// The signed position along e_r(θ), in the radial plane at θ, of a point of that plane.
double radial_of(const Eigen::Vector3d& p, double theta) {
  return p.x() * std::cos(theta) + p.y() * std::sin(theta);
}

}  // namespace

CutSimulator::CutSimulator(const Surface& design, double nose_radius, const SimulationOptions& o)
    : design_(design), R_(nose_radius), o_(o) {
  if (!(o.radial_step > 0) || !(o.outer_radius > o.inner_radius) || o.columns < 2 || o.columns % 2)
    throw InputError("simulation", "needs a radial step > 0, outer > inner radius and an even number of columns");
  if (o_.band <= 0 || o_.band > R_) o_.band = R_;
  rings_ = static_cast<int>(std::floor((o.outer_radius - o.inner_radius) / o.radial_step)) + 1;
  machined_.assign(static_cast<std::size_t>(rings_) * static_cast<std::size_t>(o.columns), kUncut);
}

void CutSimulator::lower_column(int column, double c_r, double c_z, double p_r) {
  // Signed radial coordinates s within `band` of the contact p_r (and on the nose, within
  // R of its centre): s ≥ 0 in this column, s < 0 in the opposite one at radius −s.
  const int n = o_.columns;
  const double lo = std::max(p_r - o_.band, c_r - R_), hi = std::min(p_r + o_.band, c_r + R_);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    const int col = side == 0 ? column : (column + n / 2) % n;
    // Radii r = sign·s inside [lo, hi].
    const double r_lo = side == 0 ? std::max(lo, 0.0) : std::max(-hi, 0.0);
    const double r_hi = side == 0 ? hi : -lo;
    if (r_hi < r_lo) continue;
    int i0 = static_cast<int>(std::ceil((r_lo - o_.inner_radius) / o_.radial_step));
    int i1 = static_cast<int>(std::floor((r_hi - o_.inner_radius) / o_.radial_step));
    i0 = std::max(i0, 0);
    i1 = std::min(i1, rings_ - 1);
    for (int i = i0; i <= i1; ++i) {
      const double s = sign * (o_.inner_radius + i * o_.radial_step);
      const double d = s - c_r;
      const double h = c_z - std::sqrt(std::max(0.0, R_ * R_ - d * d));
      double& cell = machined_[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(col)];
      cell = std::min(cell, h);
    }
  }
}

void CutSimulator::sweep(const CutterLocation& a, const CutterLocation& b) {
  const double ta = a.contact.theta, tb = b.contact.theta;
  if (!(tb > ta)) return;
  const int n = o_.columns;
  const double per_column = 2 * std::numbers::pi / n;
  const long first = static_cast<long>(std::ceil(ta / per_column));
  const long last = static_cast<long>(std::ceil(tb / per_column)) - 1;
  const double ra = radial_of(a.nose_centre, ta), rb = radial_of(b.nose_centre, tb);
  const double pa = radial_of(a.contact.point, ta), pb = radial_of(b.contact.point, tb);
  for (long k = first; k <= last; ++k) {
    const double t = (k * per_column - ta) / (tb - ta);
    const double c_r = ra + t * (rb - ra);
    const double c_z = a.nose_centre.z() + t * (b.nose_centre.z() - a.nose_centre.z());
    lower_column(static_cast<int>(((k % n) + n) % n), c_r, c_z, pa + t * (pb - pa));
  }
}

void CutSimulator::write(std::span<const CutterLocation> chunk) {
  for (const CutterLocation& cl : chunk) {
    if (has_previous_) sweep(previous_, cl);
    previous_ = cl;
    has_previous_ = true;
  }
  // The last location itself (a closed interval at the end of the path).
  if (!chunk.empty()) {
    const CutterLocation& cl = chunk.back();
    const double per_column = 2 * std::numbers::pi / o_.columns;
    const double k = cl.contact.theta / per_column;
    if (std::abs(k - std::round(k)) < 1e-9)
      lower_column(static_cast<int>((static_cast<long>(std::llround(k)) % o_.columns + o_.columns) % o_.columns),
                   radial_of(cl.nose_centre, cl.contact.theta), cl.nose_centre.z(),
                   radial_of(cl.contact.point, cl.contact.theta));
  }
}

SimulationResult CutSimulator::result() const {
  SimulationResult r;
  r.rings = rings_;
  r.columns = o_.columns;
  r.radial_step = o_.radial_step;
  r.residual.assign(machined_.size(), std::numeric_limits<double>::quiet_NaN());
  double sum = 0;
  long cut = 0;
  r.max = -kUncut;
  r.min = kUncut;
  for (int i = 0; i < rings_; ++i)
    for (int j = 0; j < o_.columns; ++j) {
      const std::size_t idx = static_cast<std::size_t>(i) * static_cast<std::size_t>(o_.columns) + static_cast<std::size_t>(j);
      if (machined_[idx] == kUncut) {
        ++r.uncut;
        continue;
      }
      const double rad = o_.inner_radius + i * o_.radial_step, phi = 2 * std::numbers::pi * j / o_.columns;
      double z, zx, zy;
      design_.sag_gradient(rad * std::cos(phi), rad * std::sin(phi), z, zx, zy);
      const double e = (machined_[idx] - z) / std::sqrt(1 + zx * zx + zy * zy);
      r.residual[idx] = e;
      if (rad < o_.inner_radius + o_.margin || rad > o_.outer_radius - o_.margin) continue;
      sum += e * e;
      ++cut;
      if (e > r.max) {
        r.max = e;
        r.max_r = rad;
        r.max_phi = phi;
      }
      if (e < r.min) {
        r.min = e;
        r.min_r = rad;
        r.min_phi = phi;
      }
    }
  if (cut > 0) {
    r.pv = r.max - r.min;
    r.rms = std::sqrt(sum / static_cast<double>(cut));
  } else {
    r.max = r.min = 0;
  }
  return r;
}

}  // namespace freeturn
