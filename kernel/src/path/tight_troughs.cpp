#include "freeturn/path/tight_troughs.hpp"

#include "freeturn/surface/crease_sink.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "freeturn/surface/section_curvature.hpp"

namespace freeturn {
namespace {

// Samples a tight stretch is looked for at, per placed radius: the first of these that
// resolves the design's tight stretches (TightTroughs' constructor). A stretch narrower
// than a sample that the samples do not resolve may be missed, and the chord search then
// refuses the trough as before (tool.md).
constexpr std::array<int, 3> kSamplesPerRadius = {16, 32, 64};

// The section's curvature at ρ along the line through (x0, y0); −∞ past `limit` or where
// the design is not defined, so that no comparison finds a stretch there.
double curvature_or_none(const Surface& s, double x0, double y0, const RadialLine& line, double rho,
                         double limit) {
  if (!(std::abs(rho) <= limit)) return -std::numeric_limits<double>::infinity();
  const double kappa = line_section_curvature(s, x0, y0, line, rho);
  return std::isnan(kappa) ? -std::numeric_limits<double>::infinity() : kappa;
}

// Where a sample's curvature is a local maximum of the samples but not above 1/R, the
// section's may still rise above 1/R between its neighbours (a trough barely tighter than
// the nose, whose tight stretch is narrower than a sample): the largest curvature over
// [a, b], and where it lies, by Brent's method (golden section with parabolic steps; Brent,
// "Algorithms for Minimization without Derivatives", 1973, ch. 5), to a hundred-thousandth
// of the bracket, from the sample `middle` (its curvature `at_middle`) inside it. The
// bracket holds one maximum: the middle sample is above both ends. Parabolic steps take it
// in about 8 evaluations where golden section alone took 30.
struct CurvaturePeak {
  double kappa, rho;
};
CurvaturePeak peak_curvature_between(const Surface& s, double x0, double y0, const RadialLine& line,
                                     double a, double b, double middle, double at_middle,
                                     double limit) {
  constexpr double kGoldenStep = 0.3819660112501051;  // (3 − √5)/2
  const double tolerance = 1e-5 * (b - a);
  // Minimises g = −κ: x the best point so far, w the second best, v the one before w.
  double x = middle, w = middle, v = middle;
  double gx = -at_middle, gw = gx, gv = gx;
  double step = 0, before_last = 0;
  for (int it = 0; it < 100; ++it) {
    const double centre = 0.5 * (a + b);
    if (std::abs(x - centre) <= 2 * tolerance - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(before_last) > tolerance) {
      // The parabola through x, w and v: its vertex, if it falls inside the bracket and
      // moves less than half the step before last.
      const double r = (x - w) * (gx - gv);
      double q = (x - v) * (gx - gw);
      double p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      const double last = before_last;
      before_last = step;
      if (std::isfinite(p) && std::isfinite(q) && std::abs(p) < std::abs(0.5 * q * last) &&
          p > q * (a - x) && p < q * (b - x)) {
        step = p / q;
        const double u = x + step;
        if (u - a < 2 * tolerance || b - u < 2 * tolerance)
          step = std::copysign(tolerance, centre - x);
        golden = false;
      }
    }
    if (golden) {
      before_last = x >= centre ? a - x : b - x;
      step = kGoldenStep * before_last;
    }
    const double u = std::abs(step) >= tolerance ? x + step : x + std::copysign(tolerance, step);
    const double gu = -curvature_or_none(s, x0, y0, line, u, limit);
    if (gu <= gx) {
      (u >= x ? a : b) = x;
      v = w, gv = gw;
      w = x, gw = gx;
      x = u, gx = gu;
    } else {
      (u < x ? a : b) = u;
      if (gu <= gw || w == x) {
        v = w, gv = gw;
        w = u, gw = gu;
      } else if (gu <= gv || v == x || v == w) {
        v = u, gv = gu;
      }
    }
  }
  return {-gx, x};
}

// Whether the curvature at sample `at`, a local maximum of its neighbours `before` and
// `after` and not above 1/R, is worth the search between them: a peak the samples resolve
// stands no further above `at` than `at` stands above the lower neighbour (TightTroughs'
// constructor), so it can pass 1/R only where 2·at − min(before, after) does.
bool may_peak_between(double before, double at, double after, double R) {
  return before < at && at >= after && at * R <= 1 && (2 * at - std::min(before, after)) * R > 1;
}

}  // namespace

TightTroughs::TightTroughs(const Surface& design, double placed_radius, double outer_radius)
    : s_(design),
      R_(placed_radius),
      step_(placed_radius / kSamplesPerRadius[0]),
      limit_(outer_radius + 2 * placed_radius),
      per_radius_(kSamplesPerRadius[0]) {
  if (!(R_ > 0) || !(outer_radius > 0)) return;
  // A design that bounds its bend under 1/R' has no section tighter than the nose (the
  // curvature g''/(1 + g'²)^{3/2} ≤ g''): the compound eye's scan below cost 90 000
  // evaluations, about 2 % of the demo.
  if (s_.max_section_bend(limit_) * R_ <= 1) return;
  // The polar grid: radial steps those of the sections' own samples, 256 lines. Where most
  // tight stretches on it are narrow (one sample wide, or between two samples) and the
  // samples do not show their bump, the design bends faster than the samples resolve (a
  // 10 µm period under a 0.5 mm nose): their creases would fall anywhere, and the view is
  // not used; the planner then stops at the chord tolerance, naming the radius. A narrow
  // stretch is the design's (a trough barely tighter than the nose, or a section crossing a
  // trough near its tight stretch's edge) where the samples rise over the two before it
  // and fall over the two after, and the curvature between its neighbours peaks no further
  // above the middle sample than that sample stands above them: a period that the samples
  // alias into a slow wave peaks far above its samples between them.
  //
  // Where the samples at one step find tight stretches but do not resolve them, the next,
  // finer step is tried: a sinusoidal grid of 0.4 to 0.55 mm wavelengths under a 1.5 mm
  // nose has 4 to 6 samples a wavelength at R'/16, and its stretches' bumps are too
  // narrow to show; at R'/32 they show. A design that no step resolves (the 10 µm
  // period) is left as before, and one with no tight stretch at the first step is not
  // scanned again.
  for (const int per_radius : kSamplesPerRadius) {
    per_radius_ = per_radius;
    step_ = R_ / per_radius;
    long runs = 0, narrow = 0;
    count_tight_stretches(runs, narrow);
    any_ = runs > 0 && 2 * narrow <= runs;
    if (any_ || runs == 0) return;
  }
}

void TightTroughs::count_tight_stretches(long& runs, long& narrow) const {
  const int circles = std::clamp(static_cast<int>(std::ceil(limit_ / step_)), 2, 4096);
  // The grid's own samples reach the limit and are not cut at it.
  const double unlimited = std::numeric_limits<double>::infinity();
  std::vector<double> kappa(static_cast<std::size_t>(circles) + 1);
  for (int j = 0; j < 256; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / 256);
    for (int i = 0; i <= circles; ++i)
      kappa[static_cast<std::size_t>(i)] =
          curvature_or_none(s_, 0, 0, line, limit_ * i / circles, unlimited);
    const auto at = [&](int i) {
      return i >= 0 && i <= circles ? kappa[static_cast<std::size_t>(i)]
                                    : -std::numeric_limits<double>::infinity();
    };
    const auto peak_about = [&](int i) {
      return peak_curvature_between(s_, 0, 0, line, limit_ * (i - 1) / circles,
                                    limit_ * (i + 1) / circles, limit_ * i / circles, at(i),
                                    unlimited)
          .kappa;
    };
    const auto resolved = [&](int i, double peak) {
      return at(i - 2) < at(i - 1) && at(i + 1) > at(i + 2) &&
             peak - at(i) <= at(i) - std::min(at(i - 1), at(i + 1));
    };
    int run = 0;
    for (int i = 0; i <= circles + 1; ++i) {
      if (at(i) * R_ > 1) {
        ++run;
        continue;
      }
      if (run > 0) ++runs;
      // One sample wide inside the grid (a stretch cut by its ends may be wider).
      if (run == 1 && i > 1 && i <= circles && !resolved(i - 1, peak_about(i - 1))) ++narrow;
      run = 0;
      if (i >= 1 && i < circles && may_peak_between(at(i - 1), at(i), at(i + 1), R_)) {
        const double peak = peak_about(i);
        if (peak * R_ > 1) {
          ++runs;
          if (!resolved(i, peak)) ++narrow;
        }
      }
    }
  }
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
    return curvature_or_none(s_, x0, y0, line, rho, limit_) * R_ > 1;
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
  const auto add = [&](double crease) {
    if (out.count + 1 > static_cast<int>(out.rho.size())) return false;
    out.rho[static_cast<std::size_t>(out.count++)] = crease;
    return true;
  };
  // The curvature at the two samples before the one the loop is at: a local maximum at
  // the sample before it that is not tight may hide a stretch between its neighbours. The
  // samples [first, last] are looked at so, each with its neighbours: a stretch about a
  // sample outside has its creases outside [first, last], and line_creases asks for
  // samples strictly about the query's ends.
  double before = -std::numeric_limits<double>::infinity();
  double previous = curvature_or_none(s_, x0, y0, line, (first - 1) * step_, limit_);
  for (long k = first; k <= last + 1; ++k) {
    const double rho = k * step_;
    const double kappa = curvature_or_none(s_, x0, y0, line, rho, limit_);
    if (k > first && may_peak_between(before, previous, kappa, R_)) {
      // A stretch narrower than a sample: its ends the two samples about it, its middle
      // where the curvature peaks.
      const CurvaturePeak peak = peak_curvature_between(s_, x0, y0, line, (k - 2) * step_, rho,
                                                        (k - 1) * step_, previous, limit_);
      if (peak.kappa * R_ > 1 && !(add((k - 2) * step_) && add(peak.rho) && add(rho))) {
        out.count = -1;
        return;
      }
    }
    before = previous, previous = kappa;
    const bool here = k <= last && kappa * R_ > 1;
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
        if (!add(crease)) {
          out.count = -1;
          return;
        }
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
  // The samples about [lo, hi], strictly: a stretch between two samples has a crease at
  // each, and one at a query's end is found from the sample beyond it.
  long first = static_cast<long>(std::floor(lo / step_));
  long last = static_cast<long>(std::ceil(hi / step_));
  if (first * step_ >= lo) --first;
  if (last * step_ <= hi) ++last;
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
    const long margin = same_line ? 2 * per_radius_ : 0;
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
