#include "freeturn/path/tight_troughs.hpp"

#include "freeturn/surface/crease_sink.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>

#include "freeturn/surface/section_curvature.hpp"

namespace freeturn {
namespace {

// Samples a tight stretch is looked for at, per placed radius: a stretch narrower than
// this may be missed, and the chord search then refuses the trough as before (path.md).
constexpr int kSamplesPerRadius = 16;

}  // namespace

TightTroughs::TightTroughs(const Surface& design, double placed_radius, double outer_radius)
    : s_(design),
      R_(placed_radius),
      step_(placed_radius / kSamplesPerRadius),
      limit_(outer_radius + 2 * placed_radius) {
  if (!(R_ > 0) || !(outer_radius > 0)) return;
  // A design that bounds its bend under 1/R' has no section tighter than the nose (the
  // curvature g''/(1 + g'²)^{3/2} ≤ g''): the compound eye's scan below cost 90 000
  // evaluations, about 2 % of the demo.
  if (s_.max_bend(limit_) * R_ <= 1) return;
  // The polar grid: radial steps those of the sections' own samples, 256 lines. Where most
  // tight stretches on it are one sample wide, the design bends faster than the samples
  // resolve (a 10 µm period under a 0.5 mm nose): their creases would fall anywhere, and
  // the view is not used; the planner then stops at the chord tolerance, naming the
  // radius. (A section crossing a trough near its tight stretch's edge is one sample wide
  // too, on a freeform: a few such are the design's, not the samples'.)
  const int circles = std::clamp(static_cast<int>(std::ceil(limit_ / step_)), 2, 4096);
  long runs = 0, narrow = 0;
  for (int j = 0; j < 256; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / 256);
    int run = 0;
    for (int i = 0; i <= circles + 1; ++i) {
      const bool tight =
          i <= circles && line_section_curvature(s_, 0, 0, line, limit_ * i / circles) * R_ > 1;
      if (tight) {
        ++run;
        continue;
      }
      if (run > 0) ++runs;
      // One sample wide inside the grid (a stretch cut by its ends may be wider).
      if (run == 1 && i > 1 && i <= circles) ++narrow;
      run = 0;
    }
  }
  any_ = runs > 0 && 2 * narrow <= runs;
}

int TightTroughs::section_creases(const RadialLine& line, double lo, double hi,
                                  std::span<double> out) const {
  return line_creases(0, 0, line, lo, hi, out);
}

namespace detail {

// The troughs' creases along one line over its samples [first, last] (whole steps of ρ),
// each tight stretch that reaches into them followed to its ends.
struct LineTroughs {
  std::uint64_t view = 0;
  double x0 = 0, y0 = 0, cos = 2, sin = 2;
  long first = 1, last = 0;
  int count = 0;  // −1: more than rho holds
  std::array<double, 192> rho;
};

}  // namespace detail

namespace {

// A thread's last line: the searches about one nose ask one line many times (a hold found
// by the section's overhang, dozens), and its samples are taken once. On the heap, made
// once a thread: the static TLS block a library loaded at run time (the Python module) may
// take is a few kilobytes, and this is one and a half.
thread_local std::unique_ptr<detail::LineTroughs> last_line;

}  // namespace

void TightTroughs::sample(double x0, double y0, const RadialLine& line, long first, long last,
                          detail::LineTroughs& out) const {
  const auto tight = [&](double rho) {
    return std::abs(rho) <= limit_ && line_section_curvature(s_, x0, y0, line, rho) * R_ > 1;
  };
  // A stretch that runs past the samples asked for is followed to its end, so that every
  // query of a line finds the same creases.
  const long most = static_cast<long>(std::ceil(2 * limit_ / step_));
  while (first > last - most && tight(first * step_)) --first;
  while (last < first + most && tight(last * step_)) ++last;
  out.view = id_.value;
  out.x0 = x0, out.y0 = y0, out.cos = line.cos, out.sin = line.sin;
  out.first = first, out.last = last;
  out.count = 0;
  long run_start = 0;
  double peak = 0, peak_rho = 0;
  bool in_run = false;
  // The trough's bottom within the stretch: where the section's slope turns from falling to
  // rising, by the secant between the two samples that bracket it; NaN where it does not
  // turn (a tight bend on a slope). The held nose leaves the most material about there.
  double bottom = std::numeric_limits<double>::quiet_NaN(), last_slope = 0;
  const auto slope_at = [&](double rho) {
    double z, zx, zy;
    s_.sag_gradient(x0 + rho * line.cos, y0 + rho * line.sin, z, zx, zy);
    return zx * line.cos + zy * line.sin;
  };
  for (long k = first; k <= last + 1; ++k) {
    const double rho = k * step_;
    double kappa = 0;
    const bool here = k <= last && std::abs(rho) <= limit_ &&
                      (kappa = line_section_curvature(s_, x0, y0, line, rho)) * R_ > 1;
    if (here) {
      const double slope = slope_at(rho);
      if (!in_run) {
        in_run = true;
        run_start = k;
        peak = kappa;
        peak_rho = rho;
        bottom = std::numeric_limits<double>::quiet_NaN();
      } else {
        if (kappa > peak) peak = kappa, peak_rho = rho;
        if (std::isnan(bottom) && last_slope < 0 && slope >= 0)
          bottom = rho - step_ * slope / (slope - last_slope);
      }
      last_slope = slope;
    }
    if (!here && in_run) {
      in_run = false;
      // The stretch's ends are its last samples that do not bend tightly, so that the
      // pieces beyond them are the nose's to follow; between them its bottom, or else its
      // tightest sample.
      const double middle = std::isnan(bottom) ? peak_rho : bottom;
      for (const double crease : {(run_start - 1) * step_, middle, k * step_}) {
        if (out.count + 1 > static_cast<int>(out.rho.size())) {
          out.count = -1;
          return;
        }
        out.rho[static_cast<std::size_t>(out.count++)] = crease;
      }
    }
  }
}

int TightTroughs::line_creases(double x0, double y0, const RadialLine& line, double lo, double hi,
                               std::span<double> out) const {
  // The design's own creases, the lowest of them where there are more than this holds.
  std::array<double, 256> own;
  int own_count = 0;
  if (s_.has_creases()) {
    own_count = s_.line_creases(x0, y0, line, lo, hi, own);
    if (own_count < 0) return -1;
  }
  const long first = static_cast<long>(std::floor(lo / step_));
  const long last = static_cast<long>(std::ceil(hi / step_));
  if (!last_line) last_line = std::make_unique<detail::LineTroughs>();
  detail::LineTroughs& line_troughs = *last_line;
  const bool same_line = line_troughs.view == id_.value && line_troughs.x0 == x0 &&
                         line_troughs.y0 == y0 && line_troughs.cos == line.cos &&
                         line_troughs.sin == line.sin;
  const bool known = same_line && line_troughs.count >= 0 && line_troughs.first <= first &&
                     last <= line_troughs.last;
  detail::LineTroughs narrow;
  const detail::LineTroughs* troughs = &line_troughs;
  if (!known) {
    // A line asked again (the searches about one nose): two nose widths either side, for
    // its next queries. A line asked once (each path state of an equal-angle plan has its
    // own) is sampled where asked: the margins had been two thirds of an equal-angle
    // plan's samples. The creases in [lo, hi] are the same either way: every stretch is
    // followed to its ends.
    const long margin = same_line ? 2 * kSamplesPerRadius : 0;
    sample(x0, y0, line, first - margin, last + margin, line_troughs);
    if (line_troughs.count < 0) {
      sample(x0, y0, line, first, last, narrow);
      troughs = &narrow;
    }
  }
  // More troughs than a line's record holds: not known (listing none had placed the nose as
  // if the troughs were not there).
  if (troughs->count < 0) return -1;
  // Where the design listed only its lowest creases, the merged list is complete only up
  // to the last of them.
  const bool own_cut = own_count > static_cast<int>(own.size());
  const double top = own_cut ? own.back() : hi;
  CreaseSink merged(out, lo, top, 1e-9);
  for (int i = 0; i < std::min(own_count, static_cast<int>(own.size())); ++i)
    merged.add(own[static_cast<std::size_t>(i)]);
  for (int i = 0; i < troughs->count; ++i) merged.add(troughs->rho[static_cast<std::size_t>(i)]);
  const int found = merged.finish();
  return own_cut ? std::max(found, static_cast<int>(out.size()) + 1) : found;
}

}  // namespace freeturn
