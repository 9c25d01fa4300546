#pragma once
// How much the radial sections of a height field bend toward the tool.

#include "freeturn/surface/surface.hpp"

namespace freeturn {

// The curvature of the section of `design` along the radial line at angle θ, at ρ from the
// axis (1/mm): g''/(1 + g'²)^{3/2} for g(ρ) = z(ρ cos θ, ρ sin θ), > 0 where the section is
// concave as seen from the tool (+z). NaN where the design is undefined.
double radial_section_curvature(const Surface& design, const RadialLine& line, double rho);

// The same along the line through (x0, y0) in the direction of `line`, at ρ along it.
double line_section_curvature(const Surface& design, double x0, double y0, const RadialLine& line,
                              double rho);

// The largest radial_section_curvature over the annulus inner_radius ≤ ρ ≤ outer_radius,
// sampled on a polar grid of `radial` circles (ρ evenly from inner to outer, both in) and
// `angular` lines each, plus the largest change between two neighbouring samples: what a
// curvature that varies no faster than the grid shows can reach between them (a sphere's
// is its own, exactly). −∞ where no sample is defined.
double largest_section_curvature(const Surface& design, double inner_radius, double outer_radius,
                                 int radial = 256, int angular = 256);

}  // namespace freeturn
