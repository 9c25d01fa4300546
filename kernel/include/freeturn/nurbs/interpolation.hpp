#pragma once
// Global interpolation (The NURBS Book §9.2.1, A9.1; §9.2.5, A9.4).

#include <vector>

#include "freeturn/nurbs/curve.hpp"
#include "freeturn/nurbs/parameterization.hpp"
#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

// The non-rational curve of degree p through #Q points, at the given parameters (one
// per point, increasing in [0, 1]) or, when params is empty, at chord-length ones;
// knots by averaging (Eq. 9.8). A9.1.
NurbsCurve interpolate_curve(const std::vector<Vector3d>& points, int degree,
                             std::vector<double> params = {});

// The non-rational surface through a rows × cols grid of points (row-major; the row index
// runs along u). Parameters are the chord-length ones averaged over rows and columns
// (Eq. 9.9-9.10) unless given (`params`: rows values in u, cols in v, increasing in
// [0, 1]); knots by averaging. A9.4: curves through each column, then each row.
NurbsSurface interpolate_surface(const std::vector<Vector3d>& grid, int rows, int cols,
                                 int degree_u, int degree_v,
                                 const GridParameters* params = nullptr);

}  // namespace freeturn::nurbs
