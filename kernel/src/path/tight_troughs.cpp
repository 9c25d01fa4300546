#include "freeturn/path/tight_troughs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace freeturn {
namespace {

// Samples a tight stretch is looked for at, per placed radius: a stretch narrower than
// this may be missed, and the chord search then refuses the trough as before (path.md).
constexpr int kSamplesPerRadius = 16;

// The curvature of the design's section along the line through (x0, y0) in the direction
// `line`, at ρ along it (1/mm, > 0 concave as seen from the tool); NaN where undefined.
double line_curvature(const Surface& s, double x0, double y0, const RadialLine& line, double rho) {
  const HeightDerivatives h = s.height_derivatives(x0 + rho * line.cos, y0 + rho * line.sin);
  const double slope = h.zx * line.cos + h.zy * line.sin;
  const double bend =
      (h.zxx * line.cos + 2 * h.zxy * line.sin) * line.cos + h.zyy * line.sin * line.sin;
  const double stretch = 1 + slope * slope;
  return bend / (stretch * std::sqrt(stretch));
}

}  // namespace

TightTroughs::TightTroughs(const Surface& design, double placed_radius, double outer_radius)
    : s_(design),
      R_(placed_radius),
      step_(placed_radius / kSamplesPerRadius),
      limit_(outer_radius + 2 * placed_radius) {
  if (!(R_ > 0) || !(outer_radius > 0)) return;
  // The polar grid: radial steps as fine as the sections' own sampling, 256 lines.
  const int circles = std::clamp(static_cast<int>(std::ceil(limit_ / step_)), 2, 4096);
  for (int j = 0; j < 256 && !any_; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / 256);
    for (int i = 0; i <= circles && !any_; ++i)
      any_ = line_curvature(s_, 0, 0, line, limit_ * i / circles) * R_ > 1;
  }
}

int TightTroughs::section_creases(const RadialLine& line, double lo, double hi,
                                  std::span<double> out) const {
  return line_creases(0, 0, line, lo, hi, out);
}

int TightTroughs::line_creases(double x0, double y0, const RadialLine& line, double lo, double hi,
                               std::span<double> out) const {
  std::array<double, 64> found;
  int count = 0;
  if (s_.has_creases()) {
    count = s_.line_creases(x0, y0, line, lo, hi, std::span<double>(found.data(), 32));
    if (count < 0) return -1;
  }
  const auto tight = [&](double rho) {
    return std::abs(rho) <= limit_ && line_curvature(s_, x0, y0, line, rho) * R_ > 1;
  };
  // Samples at whole steps of ρ, so that every query of a line finds the same creases; a
  // stretch that runs past the query is followed to its end.
  long first = static_cast<long>(std::floor(lo / step_));
  long last = static_cast<long>(std::ceil(hi / step_));
  const long most = static_cast<long>(std::ceil(2 * limit_ / step_));
  while (first > last - most && tight(first * step_)) --first;
  while (last < first + most && tight(last * step_)) ++last;
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
                      (kappa = line_curvature(s_, x0, y0, line, rho)) * R_ > 1;
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
      for (const double crease : {(run_start - 1) * step_, middle, k * step_})
        if (crease >= lo && crease <= hi && count < static_cast<int>(found.size()))
          found[static_cast<std::size_t>(count++)] = crease;
    }
  }
  std::sort(found.begin(), found.begin() + count);
  int written = 0;
  for (int i = 0; i < count && written < static_cast<int>(out.size()); ++i)
    if (written == 0 || found[static_cast<std::size_t>(i)] > out[written - 1] + 1e-9)
      out[static_cast<std::size_t>(written++)] = found[static_cast<std::size_t>(i)];
  return written;
}

}  // namespace freeturn
