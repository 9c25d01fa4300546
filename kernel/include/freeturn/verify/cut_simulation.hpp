#pragma once
// Simulating the cut (issue 9, first part): the tool nose, a circle of radius R in the
// radial plane at the spindle angle, swept along the motion between cutter locations,
// leaves the machined surface; the residual is machined minus design along the normal.
//
// The machined heights live on a polar grid (radii × angle columns). Each segment between
// two cutter locations passes every column whose angle it spans (once per revolution on
// a spiral); there the nose centre is interpolated linearly in (radial position, θ, z),
// and the nose's lower arc lowers the cells it covers: z_m = min(z_m, c_z − √(R² − (ρ − c_r)²)).
// Only the part of the arc within `band` of the contact point is swept: the rest of the
// edge is cut away again by the neighbouring passes (a gouge there is the tool checks'
// business). Cells on the far side of the axis are reached through the opposite column.

#include <span>
#include <vector>

#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

struct SimulationOptions {
  double inner_radius = 0, outer_radius = 0;  // mm, the grid's extent
  double radial_step = 0;  // mm between grid radii
  int columns = 360;       // angles, evenly spaced over the turn (even, so each has an opposite)
  double band = 0;         // mm, half-width of the swept arc about the contact point; 0: R
  // Cells this close to the inner or outer radius are left out of the figures (still in
  // the grid): the spiral's first turn leaves the outermost ring uncut by any pass
  // beyond it, a part of the cut the aperture does not hold.
  double margin = 0;       // mm
};

struct SimulationResult {
  int rings = 0, columns = 0;
  double radial_step = 0;
  // Residual along the normal (mm), rings × columns (ring-major); NaN where never cut.
  std::vector<double> residual;
  double pv = 0, rms = 0, max = 0, min = 0;
  long uncut = 0;  // cells no pass reached
  double max_r = 0, max_phi = 0, min_r = 0, min_phi = 0;  // where the extremes are
};

class CutSimulator final : public CutterSink {
 public:
  // nose_radius: the radius the tool really has (a wrong compensation shows as the
  // difference from the one the path was planned with).
  CutSimulator(const Surface& design, double nose_radius, const SimulationOptions& options);

  void write(std::span<const CutterLocation> chunk) override;
  // The residual and its figures over the cells that were cut.
  SimulationResult result() const;

 private:
  void sweep(const CutterLocation& a, const CutterLocation& b);
  void lower_column(int column, double c_r, double c_z, double p_r);

  const Surface& design_;
  double R_;
  SimulationOptions o_;
  int rings_ = 0;
  std::vector<double> machined_;  // rings × columns
  bool has_previous_ = false;
  CutterLocation previous_;
};

}  // namespace freeturn
