#pragma once
// Design-surface samples as CSV: what the surface looks like over the aperture, for a
// quick look in a spreadsheet or ParaView before any path is planned.

#include <string>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct SampleSummary {
  long points = 0;       // rows written
  double z_min = 0;      // mm
  double z_max = 0;      // mm
  double max_slope = 0;  // radians, largest angle between normal and +z
};

// Writes the samples of `surface` on a grid_n × grid_n square grid over
// [−outer_radius, outer_radius]², keeping the points with inner_radius ≤ r ≤ outer_radius.
// Columns: x, y, z, nx, ny, nz (mm; unit normal). Written atomically (AtomicFile).
// max_mb bounds the file (the job's limits.max_file_mb): a grid whose rows cannot fit (at
// the 12 bytes the shortest row takes) is refused before anything is evaluated, and one
// that grows past it while written is refused then; either way nothing is left. Throws
// InputError at "limits.max_file_mb".
SampleSummary write_surface_samples_csv(const Surface& surface, double inner_radius,
                                        double outer_radius, int grid_n, const std::string& path,
                                        double max_mb = 2048);

}  // namespace freeturn
