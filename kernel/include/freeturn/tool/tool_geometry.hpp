#pragma once
// A diamond turning tool (paper 002, Fig. 2-6): a circular cutting edge of nose radius R
// in the radial plane, bounded by the included angle, with a clearance angle under it.

#include <utility>
#include <vector>

namespace freeturn {

enum class ProgramPoint {
  kNoseCentre,  // the controller is told where the nose centre is
  kTip,         // … where the tip is, as touched off on a face: the centre − R along the tool axis
};

struct ToolGeometry {
  double nose_radius = 0.5;        // R (mm)
  double included_angle = 1.0472;  // rad (60°): the edge spans ±half of it about the axis
  double clearance_angle = 0.1745; // rad (10°)
  ProgramPoint program_point = ProgramPoint::kNoseCentre;
  // The measured nose-radius error δ(ψ) (mm) as (contact angle ψ in rad, δ) pairs sorted
  // by ψ, interpolated linearly: the edge at angle ψ lies R + δ(ψ) from the centre.
  std::vector<std::pair<double, double>> waviness;
  // The edge's height above the spindle centre line (machine Y, mm).
  double centre_height = 0;

  // δ(ψ), 0 without a table; constant beyond its ends.
  double waviness_at(double psi) const;
  // max δ − min δ over the edge (ψ within ±half the included angle; the whole table if
  // that is 0): the most one point of the edge reaches past the round nose compensated at
  // another (path/cutter_points.hpp, stand_off_for). 0 without a table.
  double waviness_span() const;
  // The steepest |dδ/dψ| over the edge (mm/rad; the same range as waviness_span): how fast
  // the edge can reach past the round nose away from the contact (path/cutter_points.hpp,
  // smooth_wavy_edge_reach). 0 without a table.
  double waviness_slope() const;
};

}  // namespace freeturn
