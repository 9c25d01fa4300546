#pragma once
// Parameters and knots for fitting (The NURBS Book §9.2.1 and §9.4.1).

#include <vector>

#include "freeturn/nurbs/curve.hpp"

namespace freeturn::nurbs {

// Parameters ū_k in [0, 1] for #Q points by chord length (Eq. 9.5) or, with
// centripetal = true, by the square roots of the chord lengths (Eq. 9.6). Coincident
// consecutive points are refused with an InputError naming them.
std::vector<double> chord_length_parameters(const std::vector<Vector3d>& points,
                                            bool centripetal = false);

// Parameters of a rows × cols grid of points (row-major, rows along u): the chord-length
// parameters of every column (row) averaged (Eq. 9.9-9.10). Throws InputError when the
// points do not form the grid.
struct GridParameters {
  std::vector<double> u, v;  // rows and cols values in [0, 1]
};
GridParameters grid_parameters(const std::vector<Vector3d>& grid, int rows, int cols);

// Clamped knots for interpolating at `params` with degree p, by averaging (Eq. 9.8).
std::vector<double> averaged_knots(const std::vector<double>& params, int degree);

// Clamped knots for a least-squares fit of `count` control points to data at `params`
// (Eq. 9.68-9.69): each knot span holds about the same number of parameters.
std::vector<double> approximation_knots(const std::vector<double>& params, int degree, int count);

}  // namespace freeturn::nurbs
