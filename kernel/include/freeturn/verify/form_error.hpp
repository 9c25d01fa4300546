#pragma once
// The residual of a cut split into figure and finish (docs/report.md).
//
// A spiral's cusps repeat once a pitch along the radius, whatever their shape; the mean of
// the residual over one pitch of radius removes them and leaves the surface's form: the
// figure. The finish is what the mean removed: the cusps (scallop). The figure's mean
// (the cusps' own mean height, and any offset) is a piston a part is mounted through, so
// it is removed from the figure and reported alone.

#include <vector>

#include "freeturn/verify/cut_simulation.hpp"

namespace freeturn {

struct FormErrorSplit {
  int rings = 0, columns = 0;
  double inner_radius = 0, radial_step = 0;  // mm, as the simulation's grid
  int window = 1;         // rings averaged: the pitch in rings
  bool resolved = false;  // window ≥ 3: the grid resolves the cusps it separates
  // Figure residual less the piston, rings × columns as SimulationResult::residual (mm, NaN
  // where never cut). Float: nanometres on millimetre-sized values need 7 digits, not 16.
  std::vector<float> figure;
  double piston = 0;                                           // mm, the figure's mean
  double figure_pv = 0, figure_rms = 0, figure_max = 0, figure_min = 0;  // mm, counted cells
  double finish_pv = 0, finish_rms = 0;                        // mm, counted cells
  // The largest finish PV per radial band of the figures' radii, `bands` of them.
  std::vector<double> finish_pv_by_band;
  double band_inner = 0, band_width = 0;  // mm: band k covers band_inner + [k, k + 1)·band_width
};

// r: a finished simulation; inner/outer/margin: its SimulationOptions (cells within
// margin of either edge are left out of the figures, as in the simulation's own);
// pitch: the spiral's radial feed per turn (mm).
FormErrorSplit split_figure_finish(const SimulationResult& r, double inner_radius,
                                   double outer_radius, double margin, double pitch,
                                   int bands = 64);

}  // namespace freeturn
