#include "freeturn/verify/cut_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/core/parallel_for.hpp"
#include "freeturn/path/pvt_rule.hpp"

namespace freeturn {
namespace {

constexpr std::uint16_t kHeldBit = 0x8000;
constexpr double kOffsetSteps = 32767.0;  // the offset's 15 bits


constexpr double kUncut = std::numeric_limits<double>::infinity();
constexpr std::size_t kBatch = 16384;  // segments swept per parallel batch

// The signed position along e_r(θ), in the radial plane at θ, of a point of that plane.
double radial_of(const Eigen::Vector3d& p, double theta) {
  return p.x() * std::cos(theta) + p.y() * std::sin(theta);
}

// The programmed axes (X, Z, B) along the segment from locations[i] to locations[i + 1] as
// the controller interpolates them: linearly, or in PVT (pvt_rule.hpp) along the cubic
// with each block's velocity from its neighbours over their times, one-sided at the path's
// ends. `time(location)`: at one spindle speed, its angle.
class SegmentAxes {
 public:
  template <class Time>
  SegmentAxes(const std::vector<CutterLocation>& locations, std::size_t i, bool cubic, Time time)
      : cubic_(cubic) {
    const CutterLocation& a = locations[i];
    const CutterLocation& b = locations[i + 1];
    qa_ = {a.x, a.z, a.b};
    qb_ = {b.x, b.z, b.b};
    span_ = time(b) - time(a);
    if (!cubic) return;
    const CutterLocation& before = i > 0 ? locations[i - 1] : a;
    const CutterLocation& after = i + 2 < locations.size() ? locations[i + 2] : b;
    const Eigen::Vector3d q_before(before.x, before.z, before.b),
        q_after(after.x, after.z, after.b);
    const double dt_a = time(b) - time(before), dt_b = time(after) - time(a);
    for (int axis = 0; axis < 3; ++axis) {
      va_[axis] = pvt::velocity(q_before[axis], qb_[axis], dt_a);
      vb_[axis] = pvt::velocity(qa_[axis], q_after[axis], dt_b);
    }
  }
  // At the fraction t of the segment's time.
  Eigen::Vector3d at(double t) const {
    if (!cubic_) return qa_ + t * (qb_ - qa_);
    Eigen::Vector3d q;
    for (int axis = 0; axis < 3; ++axis)
      q[axis] = pvt::hermite(qa_[axis], va_[axis], qb_[axis], vb_[axis], span_, t);
    return q;
  }

 private:
  bool cubic_;
  double span_ = 0;
  Eigen::Vector3d qa_, qb_, va_ = Eigen::Vector3d::Zero(), vb_ = Eigen::Vector3d::Zero();
};

// The worst cell of a stretch of rings, and the figures of one ring.
struct RingFigures {
  double sum = 0;
  long cut = 0, uncut = 0;
  double max = -kUncut, min = kUncut;
  int max_col = 0, min_col = 0;
  double worst = 0;  // the largest |residual|
  int worst_col = -1;
};

}  // namespace

const char* to_string(ResidualCause cause) {
  switch (cause) {
    case ResidualCause::kScallop: return "scallop";
    case ResidualCause::kChord: return "chord";
    case ResidualCause::kGouge: return "gouge";
    case ResidualCause::kUncut: return "uncut_residual";
  }
  return "?";
}

const char* prediction_bound_text(double ratio) {
  return ratio < 0.9995 ? "not an upper bound"
         : ratio <= 1.1 ? "an upper bound within 10%"
                        : "an upper bound, loose by more than 10%";
}

CutSimulator::CutSimulator(const Surface& design, double nose_radius, const SimulationOptions& o)
    : design_(design), R_(nose_radius), o_(o), threads_(thread_count(o.threads)) {
  if (!(o.radial_step > 0) || !(o.outer_radius > o.inner_radius) || o.columns < 2 || o.columns % 2)
    throw InputError("simulation", "needs a radial step > 0, outer > inner radius and an even number of columns");
  if (o_.band <= 0 || o_.band > R_) o_.band = R_;
  const double rings = std::floor((o.outer_radius - o.inner_radius) / o.radial_step) + 1;
  // A step as wide as the aperture samples r = 0 alone, and reports a form error of 0.
  if (rings < 3)
    throw InputError("simulation", "a radial step of " + significant_text(o.radial_step, 6) +
                                       " mm leaves " + std::to_string(static_cast<int>(rings)) +
                                       " radii over r = " + significant_text(o.inner_radius, 6) +
                                       " to " + significant_text(o.outer_radius, 6) +
                                       " mm, too few for a form error; give a finer --radial-step");
  const double cells = rings * o.columns;
  if (!(cells <= static_cast<double>(o.max_cells)))
    throw InputError(
        "simulation",
        "the grid would hold " + significant_text(cells, 6) + " cells (over " +
            std::to_string(o.max_cells) +
            "); give a coarser radial step (--radial-step) or fewer columns (--columns)");
  rings_ = static_cast<int>(rings);
  const std::size_t n = static_cast<std::size_t>(rings_) * static_cast<std::size_t>(o.columns);
  machined_.assign(n, kUncut);
  offset_.assign(n, 0);
  pending_.reserve(kBatch + 1);
}

void CutSimulator::lower_column(int column, double c_r, double c_z, double b, double p_r,
                                bool held) {
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
      lower_cell(
          static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(col),
          edge_height(s - c_r, c_z, b), std::abs(s - p_r), held);
    }
  }
}

double CutSimulator::edge_height(double d, double c_z, double b) const {
  const ToolGeometry& tool = o_.compensation.tool;
  if (tool.waviness.empty()) return c_z - std::sqrt(std::max(0.0, R_ * R_ - d * d));
  // The edge point at normal angle ψ lies (R + δ(ψ − B)) from the centre, at offset
  // −(R + δ) sin ψ: ψ from the round nose, once refined with its δ (δ ≪ R, so the rest is
  // second order in δ′).
  const double psi0 = std::asin(std::clamp(-d / R_, -1.0, 1.0));
  const double sin_psi = std::clamp(-d / (R_ + tool.waviness_at(psi0 - b)), -1.0, 1.0);
  const double psi = std::asin(sin_psi);
  return c_z - (R_ + tool.waviness_at(psi - b)) * std::sqrt(1 - sin_psi * sin_psi);
}

void CutSimulator::lower_cell(std::size_t idx, double height, double from_contact, bool held) {
  if (!(height < machined_[idx])) return;
  machined_[idx] = height;
  offset_[idx] =
      static_cast<std::uint16_t>(static_cast<std::uint16_t>(std::min(
                                     kOffsetSteps, from_contact * (kOffsetSteps / o_.band) + 0.5)) |
                                 (held ? kHeldBit : 0));
}

// With the edge h above the spindle line the nose is an arc in the rake plane, machine
// y = h (docs/tool.md, "Centre height"): its point at machine x_e reaches radius
// √(x_e² + h²) at angle C + atan2(h, x_e), which differs along the edge. Ring by ring: the
// edge points that reach ring ρ (x_e = ±√(ρ² − h²)) pass column k where
// C(t) = k·2π/n − atan2(h, x_e), and the axes there place the nose's centre at machine x
// c_x, so the arc's height over them is that of a radial nose at offset x_e − c_x. The
// motion is interpolated in C, the spindle's own angle, as the controller does.
void CutSimulator::sweep_rake_plane(std::size_t end, int pair_begin, int pair_end) {
  const int n = o_.columns, half = n / 2;
  const double per_column = 2 * std::numbers::pi / n;
  const bool cubic = o_.interpolation == Interpolation::kCubic;
  const double h = o_.compensation.tool.centre_height;
  const double offset = programmed_point_offset(o_.compensation);
  for (std::size_t i = first_; i < end; ++i) {
    const CutterLocation& a = pending_[i];
    const CutterLocation& b = pending_[i + 1];
    const double ca = a.c, cb = b.c;
    if (!(cb > ca) || !std::isfinite(a.x) || !std::isfinite(b.x)) continue;
    const double span = cb - ca;
    const SegmentAxes axes(pending_, i, cubic, [](const CutterLocation& l) { return l.c; });
    const double pa = radial_of(a.contact.point, a.contact.theta);
    const double pb = radial_of(b.contact.point, b.contact.theta);
    const bool held = a.contact.uncut_residual > 0 || b.contact.uncut_residual > 0;
    // The edge's machine x over the segment (a cubic stays near its ends' hull; the band
    // bounds what is swept anyway).
    const double ea = a.x - offset * std::sin(a.b), eb = b.x - offset * std::sin(b.b);
    const double x_lo = std::min(ea, eb) - R_, x_hi = std::max(ea, eb) + R_;
    const double r_lo = x_lo <= 0 && x_hi >= 0
                            ? std::abs(h)
                            : std::hypot(std::min(std::abs(x_lo), std::abs(x_hi)), h);
    const double r_hi = std::hypot(std::max(std::abs(x_lo), std::abs(x_hi)), h);
    const int i0 =
        std::max(0, static_cast<int>(std::ceil((r_lo - o_.inner_radius) / o_.radial_step)));
    const int i1 = std::min(
        rings_ - 1, static_cast<int>(std::floor((r_hi - o_.inner_radius) / o_.radial_step)));
    for (int ring = i0; ring <= i1; ++ring) {
      const double rho = o_.inner_radius + ring * o_.radial_step;
      if (!(rho >= std::abs(h))) continue;
      for (const double sign : {1.0, -1.0}) {
        const double x_e = sign * std::sqrt(rho * rho - h * h);
        if (x_e < x_lo || x_e > x_hi) continue;
        const double turn = std::atan2(h, x_e);
        const long first = static_cast<long>(std::ceil((ca + turn) / per_column));
        const long last = static_cast<long>(std::ceil((cb + turn) / per_column)) - 1;
        for (long k = first; k <= last; ++k) {
          const int column = static_cast<int>(((k % n) + n) % n);
          const int pair = column % half;
          if (pair < pair_begin || pair >= pair_end) continue;
          const double t = (k * per_column - turn - ca) / span;
          const Eigen::Vector3d q = axes.at(t);
          const double c_x = q.x() - offset * std::sin(q.z()),
                       c_z = q.y() - offset * std::cos(q.z());
          const double d = x_e - c_x;
          const double from_contact = std::abs(sign * rho - (pa + t * (pb - pa)));
          if (std::abs(d) > R_ || from_contact > o_.band) continue;
          lower_cell(static_cast<std::size_t>(ring) * static_cast<std::size_t>(n) +
                         static_cast<std::size_t>(column),
                     edge_height(d, c_z, q.z()), from_contact, held);
        }
      }
    }
  }
}

// Every segment of the batch, in path order, on the columns whose pair index (column mod
// n/2) lies in [pair_begin, pair_end): this thread owns those columns and their opposites.
// Segment i runs from pending_[i] to pending_[i + 1], for i in [first_, end).
void CutSimulator::sweep_columns(std::size_t end, int pair_begin, int pair_end) {
  const int n = o_.columns, half = n / 2;
  const double per_column = 2 * std::numbers::pi / n;
  const bool cubic = o_.interpolation == Interpolation::kCubic;
  for (std::size_t i = first_; i < end; ++i) {
    const CutterLocation& a = pending_[i];
    const CutterLocation& b = pending_[i + 1];
    const double ta = a.contact.theta, tb = b.contact.theta;
    if (!(tb > ta)) continue;
    const long first = static_cast<long>(std::ceil(ta / per_column));
    const long last = static_cast<long>(std::ceil(tb / per_column)) - 1;
    if (last < first) continue;
    const double h = tb - ta;
    const SegmentAxes axes(pending_, i, cubic,
                           [](const CutterLocation& l) { return l.contact.theta; });
    const double pa = radial_of(a.contact.point, ta), pb = radial_of(b.contact.point, tb);
    const bool held = a.contact.uncut_residual > 0 || b.contact.uncut_residual > 0;
    for (long k = first; k <= last; ++k) {
      const int column = static_cast<int>(((k % n) + n) % n);
      const int pair = column % half;
      if (pair < pair_begin || pair >= pair_end) continue;
      const double t = (k * per_column - ta) / h;
      const Eigen::Vector3d q = axes.at(t);
      const Eigen::Vector2d centre = nose_centre_from_axes(q.x(), q.y(), q.z(), o_.compensation);
      lower_column(column, centre.x(), centre.y(), q.z(), pa + t * (pb - pa), held);
    }
  }
}

// Sweeps the segments whose PVT neighbours have arrived (all of them when `last`), then
// keeps the locations the next segments need.
void CutSimulator::sweep_batch(bool last) {
  if (pending_.size() < 2) return;
  const std::size_t end = last ? pending_.size() - 1 : pending_.size() - 2;
  if (end > first_) {
    const int half = o_.columns / 2;
    const bool rake = o_.compensation.tool.centre_height != 0;
    parallel_for(threads_, half, [&](long begin, long stop) {
      if (rake)
        sweep_rake_plane(end, static_cast<int>(begin), static_cast<int>(stop));
      else
        sweep_columns(end, static_cast<int>(begin), static_cast<int>(stop));
    });
  }
  // Keep the location before the next segment and the rest: [end − 1, size).
  const std::size_t keep_from = end > 0 ? end - 1 : 0;
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(keep_from));
  first_ = end - keep_from;
}

void CutSimulator::write(std::span<const CutterLocation> chunk) {
  const double lo = o_.inner_radius + o_.margin, hi = o_.outer_radius - o_.margin;
  for (const CutterLocation& cl : chunk) {
    const double r = cl.contact.r;
    if (r >= lo && r <= hi) {
      predicted_.max_scallop = std::max(predicted_.max_scallop, cl.contact.scallop);
      predicted_.max_uncut = std::max(predicted_.max_uncut, cl.contact.uncut_residual);
      // Across a jump the nose swings over the crease: it cuts into one flank and leaves
      // the valley, so the jump's error counts on both sides.
      if (cl.contact.chord_below || cl.contact.chord_jump)
        predicted_.max_chord_below = std::max(predicted_.max_chord_below, cl.contact.chord_error);
      if (!cl.contact.chord_below || cl.contact.chord_jump)
        predicted_.max_chord_above = std::max(predicted_.max_chord_above, cl.contact.chord_error);
    }
    pending_.push_back(cl);
    if (pending_.size() > kBatch) sweep_batch(false);
  }
}

SimulationResult CutSimulator::finish() {
  sweep_batch(true);
  // The last location itself: the segments cover [θ_a, θ_b), so a column exactly at the
  // path's last angle is still to cut.
  if (!pending_.empty() && o_.compensation.tool.centre_height == 0) {
    const CutterLocation& cl = pending_.back();
    const double k = cl.contact.theta / (2 * std::numbers::pi / o_.columns);
    if (std::abs(k - std::round(k)) < 1e-9) {
      const Eigen::Vector2d centre = nose_centre_from_axes(cl.x, cl.z, cl.b, o_.compensation);
      lower_column(static_cast<int>((std::llround(k) % o_.columns + o_.columns) % o_.columns),
                   centre.x(), centre.y(), cl.b, radial_of(cl.contact.point, cl.contact.theta),
                   cl.contact.uncut_residual > 0);
    }
    pending_.clear();
  }

  SimulationResult r;
  r.rings = rings_;
  r.columns = o_.columns;
  r.radial_step = o_.radial_step;
  r.predicted = predicted_;
  const int n = o_.columns;
  const double from_offset = o_.band / kOffsetSteps;
  std::vector<RingFigures> rings(static_cast<std::size_t>(rings_));
  // The residual replaces the machined height in place, ring by ring in parallel.
  parallel_for(threads_, rings_, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      RingFigures& f = rings[static_cast<std::size_t>(i)];
      const double rad = o_.inner_radius + static_cast<double>(i) * o_.radial_step;
      const bool counted = rad >= o_.inner_radius + o_.margin && rad <= o_.outer_radius - o_.margin;
      for (int j = 0; j < n; ++j) {
        double& cell = machined_[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
        if (cell == kUncut) {
          ++f.uncut;
          cell = std::numeric_limits<double>::quiet_NaN();
          continue;
        }
        const double phi = 2 * std::numbers::pi * j / n;
        double z, zx, zy;
        design_.sag_gradient(rad * std::cos(phi), rad * std::sin(phi), z, zx, zy);
        const double e = (cell - z) / std::sqrt(1 + zx * zx + zy * zy);
        cell = e;
        if (!counted) continue;
        f.sum += e * e;
        ++f.cut;
        if (e > f.max) f.max = e, f.max_col = j;
        if (e < f.min) f.min = e, f.min_col = j;
        if (std::abs(e) > f.worst) f.worst = std::abs(e), f.worst_col = j;
      }
    }
  });
  // Reduced in ring order: the same sums on any thread count.
  double sum = 0;
  long cut = 0;
  r.max = -kUncut;
  r.min = kUncut;
  for (int i = 0; i < rings_; ++i) {
    const RingFigures& f = rings[static_cast<std::size_t>(i)];
    r.uncut += f.uncut;
    sum += f.sum;
    cut += f.cut;
    const double rad = o_.inner_radius + i * o_.radial_step;
    if (f.cut > 0 && f.max > r.max) r.max = f.max, r.max_r = rad, r.max_phi = 2 * std::numbers::pi * f.max_col / n;
    if (f.cut > 0 && f.min < r.min) r.min = f.min, r.min_r = rad, r.min_phi = 2 * std::numbers::pi * f.min_col / n;
  }
  if (cut > 0) {
    r.pv = r.max - r.min;
    r.rms = std::sqrt(sum / static_cast<double>(cut));
  } else {
    r.max = r.min = 0;
  }

  // The worst place of each twentieth of the radii, the five worst of those, and why.
  constexpr int kStretches = 20;
  std::vector<ResidualPlace> places;
  for (int s = 0; s < kStretches; ++s) {
    const int i0 = rings_ * s / kStretches, i1 = rings_ * (s + 1) / kStretches;
    int best = -1;
    for (int i = i0; i < i1; ++i)
      if (rings[static_cast<std::size_t>(i)].worst_col >= 0 &&
          (best < 0 || rings[static_cast<std::size_t>(i)].worst > rings[static_cast<std::size_t>(best)].worst))
        best = i;
    if (best < 0) continue;
    const int j = rings[static_cast<std::size_t>(best)].worst_col;
    const std::size_t idx = static_cast<std::size_t>(best) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j);
    ResidualPlace p;
    p.r = o_.inner_radius + best * o_.radial_step;
    p.phi = 2 * std::numbers::pi * j / n;
    p.residual = machined_[idx];
    const double d = (offset_[idx] & ~kHeldBit) * from_offset;
    p.scallop_part = R_ - std::sqrt(std::max(0.0, R_ * R_ - d * d));
    if (p.residual < 0)
      p.cause = -p.residual > 1.1 * predicted_.max_chord_below + 1e-6 ? ResidualCause::kGouge : ResidualCause::kChord;
    else if (offset_[idx] & kHeldBit)
      p.cause = ResidualCause::kUncut;
    else
      p.cause = p.scallop_part >= p.residual - p.scallop_part ? ResidualCause::kScallop : ResidualCause::kChord;
    places.push_back(p);
  }
  std::stable_sort(places.begin(), places.end(), [](const ResidualPlace& a, const ResidualPlace& b) {
    return std::abs(a.residual) > std::abs(b.residual);
  });
  if (places.size() > 5) places.resize(5);
  r.worst = std::move(places);
  r.residual = std::move(machined_);
  machined_.clear();
  offset_.clear();
  offset_.shrink_to_fit();
  return r;
}

}  // namespace freeturn
