#pragma once
// The base surface and its axis by least squares on the quasi-revolution angles:
// minimise Σ sin²α_i over the generating curve's coefficients and the axis, by
// Levenberg–Marquardt (Eigen's) on the two components of each design normal that a
// base normal cannot have: along the base's meridian tangent and around the axis
// (revolution_terms.hpp). Smooth and well determined where the minimax is flat, it is
// the start of the minimax axis search (minimax_base_fit.hpp).

#include <vector>

#include "freeturn/core/status.hpp"
#include "freeturn/path/base_axis.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/base_surface_fit.hpp"

namespace freeturn {

struct BaseAxisFit {
  BaseSurface base;  // H about the axis, with the offset that fits the samples' heights
  BaseAxis axis;
  double rms_angle = 0, max_angle = 0;  // rad
  Status status = Status::kNotConverged;
  int iterations = 0;
};

// Starts from `start` (its knots are kept; its domain should cover the samples' radii
// about the axes the fit may reach) and the z axis.
BaseAxisFit fit_base_and_axis_least_squares(const std::vector<SurfaceSample>& samples,
                                            const BaseSurface& start);

// The offset c_0 = c_1 = mean(h − H(ρ)) that puts the base through the samples, for a
// base whose angles were fitted (angles do not see the offset).
BaseSurface with_height_offset(const std::vector<SurfaceSample>& samples, const BaseSurface& base,
                               const BaseAxis& axis);

}  // namespace freeturn
