#pragma once
// The height above which a program may move freely: no cutter location of a cut over the
// annulus rises past it, so an approach or a retract at `retract` above it clears the part
// whatever X and C do meanwhile (the first law: never below the design surface, including
// between the cut and the home position).
//
// The nose centre sits c_z = z_s + (R + δ + stand-off)·n̂_z ≤ max z_s + R + max(δ, 0) +
// stand-off over the contacts (n̂_z ≤ 1), and the programmed point is c_z + L cos B (a B
// pivot), c_z − R cos B (the tip) or c_z (compensation.hpp). The highest sag is found on a
// polar grid and refined by a pattern search from the best samples; the margin covers
// what a grid may still miss between its nodes.

#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/compensation.hpp"

namespace freeturn {

// The margin (mm) added to the sampled ceiling.
inline constexpr double kCeilingMargin = 0.005;

// The highest sag of `surface` over the annulus inner_radius ≤ r ≤ outer_radius (mm).
double highest_sag(const Surface& surface, double inner_radius, double outer_radius);

// A bound on the programmed Z of every cutter location that cuts `surface` over the
// annulus, in the kernel frame (mm): highest_sag + R + max(δ, 0) + stand_off + the
// programmed point's offset + kCeilingMargin. stand_off: the contact's (contact_point.hpp).
double program_z_ceiling(const Surface& surface, double inner_radius, double outer_radius,
                         const CompensationOptions& options, double stand_off);

}  // namespace freeturn
