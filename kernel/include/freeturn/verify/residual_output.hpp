#pragma once
// The simulated residual as files: the grid as CSV (r, phi_deg, residual_nm; empty where
// no pass reached) and a PLY mesh of the design coloured by the residual (blue below the
// design, white on it, red above), both written atomically.

#include <string>

#include "freeturn/surface/surface.hpp"
#include "freeturn/verify/cut_simulation.hpp"

namespace freeturn {

void write_residual_csv(const SimulationResult& r, double inner_radius, const std::string& path);

// At most about 200 × 360 vertices: the grid is decimated for viewing.
void write_residual_ply(const SimulationResult& r, const Surface& design, double inner_radius,
                        const std::string& path);

}  // namespace freeturn
