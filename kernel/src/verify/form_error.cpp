#include "freeturn/verify/form_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace freeturn {

FormErrorSplit split_figure_finish(const SimulationResult& r, double inner, double outer,
                                   double margin, double pitch, int bands) {
  FormErrorSplit s;
  s.rings = r.rings;
  s.columns = r.columns;
  s.inner_radius = inner;
  s.radial_step = r.radial_step;
  const int per_pitch =
      r.radial_step > 0 ? static_cast<int>(std::lround(pitch / r.radial_step)) : 1;
  // Exactly one pitch of cells: when the step divides the pitch, every window holds the
  // same phases of the cusp, and their mean is the same in every window.
  s.window = std::max(1, per_pitch);
  s.resolved = s.window >= 3;
  const std::size_t n = static_cast<std::size_t>(r.columns);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  s.figure.assign(r.residual.size(), nan);
  // Cell i's window is [i − w/2, i − w/2 + w): centred, or half a cell early when w is even.
  const int before = s.window / 2, after = s.window - before - 1;
  // A running sum down each column: O(1) per cell whatever the window.
  for (std::size_t j = 0; j < n; ++j) {
    double sum = 0;
    long count = 0;
    const auto cell = [&](int i) { return r.residual[static_cast<std::size_t>(i) * n + j]; };
    for (int i = 0; i < std::min(after, r.rings); ++i)
      if (!std::isnan(cell(i))) sum += cell(i), ++count;
    for (int i = 0; i < r.rings; ++i) {
      const int enter = i + after, leave = i - before - 1;
      if (enter < r.rings && !std::isnan(cell(enter))) sum += cell(enter), ++count;
      if (leave >= 0 && !std::isnan(cell(leave))) sum -= cell(leave), --count;
      if (!std::isnan(cell(i)) && count > 0)
        s.figure[static_cast<std::size_t>(i) * n + j] = static_cast<float>(sum / count);
    }
  }
  const auto counted = [&](int i) {
    const double rad = inner + i * r.radial_step;
    return rad >= inner + margin && rad <= outer - margin;
  };
  double mean = 0;
  long cells = 0;
  for (int i = 0; i < r.rings; ++i) {
    if (!counted(i)) continue;
    for (std::size_t j = 0; j < n; ++j) {
      const float f = s.figure[static_cast<std::size_t>(i) * n + j];
      if (!std::isnan(f)) mean += f, ++cells;
    }
  }
  s.piston = cells > 0 ? mean / static_cast<double>(cells) : 0.0;
  s.band_inner = inner + margin;
  s.band_width = std::max(outer - margin - s.band_inner, 0.0) / bands;
  s.finish_pv_by_band.assign(static_cast<std::size_t>(bands), 0.0);
  std::vector<double> band_max(static_cast<std::size_t>(bands), -1e300),
      band_min(static_cast<std::size_t>(bands), 1e300);
  double fig_sq = 0, fin_sq = 0, fin_max = -1e300, fin_min = 1e300;
  s.figure_max = -1e300;
  s.figure_min = 1e300;
  for (int i = 0; i < r.rings; ++i) {
    const bool count_it = counted(i);
    const double rad = inner + i * r.radial_step;
    const int band = s.band_width > 0
                         ? std::clamp(static_cast<int>((rad - s.band_inner) / s.band_width), 0,
                                      bands - 1)
                         : 0;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * n + j;
      float& f = s.figure[k];
      if (std::isnan(f)) continue;
      const double finish = r.residual[k] - f;
      f = static_cast<float>(f - s.piston);
      if (!count_it) continue;
      fig_sq += static_cast<double>(f) * f;
      fin_sq += finish * finish;
      s.figure_max = std::max(s.figure_max, static_cast<double>(f));
      s.figure_min = std::min(s.figure_min, static_cast<double>(f));
      fin_max = std::max(fin_max, finish);
      fin_min = std::min(fin_min, finish);
      band_max[static_cast<std::size_t>(band)] = std::max(band_max[static_cast<std::size_t>(band)], finish);
      band_min[static_cast<std::size_t>(band)] = std::min(band_min[static_cast<std::size_t>(band)], finish);
    }
  }
  if (cells > 0) {
    s.figure_pv = s.figure_max - s.figure_min;
    s.finish_pv = fin_max - fin_min;
    s.figure_rms = std::sqrt(fig_sq / static_cast<double>(cells));
    s.finish_rms = std::sqrt(fin_sq / static_cast<double>(cells));
    for (int b = 0; b < bands; ++b)
      if (band_max[static_cast<std::size_t>(b)] >= band_min[static_cast<std::size_t>(b)])
        s.finish_pv_by_band[static_cast<std::size_t>(b)] =
            band_max[static_cast<std::size_t>(b)] - band_min[static_cast<std::size_t>(b)];
  } else {
    s.figure_max = s.figure_min = 0;
  }
  return s;
}

}  // namespace freeturn
