#pragma once
// The simulated residual as files: the grid as CSV (r_mm, phi_deg, residual_nm; empty where
// no pass reached) and a PLY mesh of the design coloured by the residual (blue below the
// design, white on it, red above), both written atomically.

#include <functional>
#include <string>
#include <vector>

#include "freeturn/io/atomic_file.hpp"
#include "freeturn/surface/surface.hpp"
#include "freeturn/verify/cut_simulation.hpp"

namespace freeturn {

// The residual seen from above on a square raster over [−outer, outer]², outer = the
// grid's outer radius: each pixel the mean of the cut cells of the column nearest its
// centre's angle whose radii lie within the pixel's width of its centre's radius. Radially
// a mean (a scallop finer than a pixel shows as its mean height, not as moiré); around the
// turn the nearest column (columns may lie farther apart than pixels at the rim).
struct ResidualHeatMap {
  int size = 0;              // pixels per side
  double half_width = 0;     // mm, the raster spans [−half_width, half_width] in x and y
  std::vector<double> mean;  // size × size, row-major from +y down (image order); NaN: no cell
  double low = 0, high = 0;  // the smallest and largest pixel means (mm)
};
ResidualHeatMap residual_heat_map(const SimulationResult& r, double inner_radius, int size);
// The same raster from any polar grid laid out as SimulationResult::residual (rings ×
// columns, ring-major, ring i at inner_radius + i·radial_step); value(k) is cell k, NaN
// where there is nothing to show.
ResidualHeatMap polar_heat_map(int rings, int columns, double inner_radius, double radial_step,
                               const std::function<double(std::size_t)>& value, int size);

// Both write into an AtomicFile the caller commits (with the rest of a run,
// io/output_set.hpp).
void write_residual_csv(const SimulationResult& r, double inner_radius, AtomicFile& out);

// At most about 200 × 360 vertices: the grid is decimated for viewing.
void write_residual_ply(const SimulationResult& r, const Surface& design, double inner_radius,
                        AtomicFile& out);

}  // namespace freeturn
