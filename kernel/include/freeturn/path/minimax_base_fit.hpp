#pragma once
// The minimax base surface (paper 000, Eq. 10-11): the generating curve, and optionally
// the axis, that minimise the largest quasi-revolution angle max_i α_i.
//
// Minimises max_i (1 − cos α_i) (1 − cos α is monotone in α and smooth where α is not)
// by a trust-region SQP on the epigraph whose QPs are solved densely by a dual active-set
// method (core/minimax_sqp.hpp): a few variables, thousands of samples, a handful of them
// active at a time. The gradients are analytic in the coefficients of H and by
// forward-mode automatic differentiation (Eigen's AutoDiffScalar) in the axis parameters. The paper leaves the axis to the user;
// with `search_axis` it is searched too, starting from the least-squares fit of base and
// axis (base_axis_fit.hpp), because the minimax alone is flat along directions that trade
// the largest angle of one place for another's.

#include <Eigen/Core>
#include <vector>

#include "freeturn/core/status.hpp"
#include "freeturn/path/base_axis.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/base_surface_fit.hpp"

namespace freeturn {

struct MinimaxBaseOptions {
  // Also search the axis: its tilt (about x, then y, as TransformedSurface's tilts) and
  // where it crosses the plane z = 0.
  bool search_axis = false;
  double max_tilt = 0.1;    // rad, bound on each tilt
  double max_shift = 1.0;   // mm, bound on each coordinate of the crossing
  int max_iterations = 300;
};

struct MinimaxBaseResult {
  BaseSurface base;             // H about the axis (ρ measured from it)
  BaseAxis axis;                // the z axis unless searched
  double max_angle = 0;         // max α at the solution (rad)
  double start_max_angle = 0;   // max α of `start` about the z axis
  double least_squares_max_angle = 0;  // max α after the least-squares axis stage
  Status status = Status::kNotConverged;
  int iterations = 0;  // SQP iterations
};

// Starts from `start` (e.g. the least-squares base, whose knots are kept; its domain
// should cover the samples' radii about any axis the search may reach).
MinimaxBaseResult fit_base_minimax(const std::vector<SurfaceSample>& samples,
                                   const BaseSurface& start, const MinimaxBaseOptions& options = {});

}  // namespace freeturn
