#pragma once
// Least-squares approximation by B-splines (The NURBS Book §9.4.1, A9.7 without the
// weights; §9.4.3 for surfaces), with optional smoothing and parameter correction.
//
// Minimised: Σ_k |S(ū_k) − Q_k|² + λ·E, with E = ∫|C''|² du for curves and the thin-plate
// energy ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|² du dv for surfaces. Parameter correction
// re-projects every point onto the fitted curve or surface (warm-started point inversion)
// and fits again, which removes the tangential part of the residual.

#include <vector>

#include "freeturn/nurbs/curve.hpp"
#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

struct CurveFitOptions {
  int degree = 3;
  int count = 0;                  // control points (needed unless `knots` is given)
  std::vector<double> knots;      // clamped knots; empty → Eq. 9.68-9.69 from the parameters
  std::vector<double> params;     // one per point in [0, 1]; empty → chord length
  double smoothing = 0;           // λ ≥ 0
  bool pin_ends = false;          // pass exactly through the first and last points
  int parameter_corrections = 0;  // rounds of re-projection and refit
};

struct CurveFit {
  NurbsCurve curve;
  std::vector<double> params;  // the final parameter of each point
  double max_error = 0;        // max |C(ū_k) − Q_k| (mm)
  double rms_error = 0;
};

// points: #Q points. Throws InputError for too few points, bad knots or parameters, or a
// singular system (a knot span without data and no smoothing).
CurveFit fit_curve(const std::vector<Vector3d>& points, const CurveFitOptions& options);

struct SurfaceFitOptions {
  int degree_u = 3, degree_v = 3;
  int count_u = 0, count_v = 0;  // control points per direction (unless knots are given)
  std::vector<double> knots_u, knots_v;
  double smoothing = 0;           // λ ≥ 0 on the thin-plate energy
  int parameter_corrections = 0;  // scattered fits only
  // Grid fits: the parameters of the rows (u) and columns (v), increasing in [0, 1];
  // empty → averaged chord lengths.
  std::vector<double> params_u, params_v;
};

struct SurfaceFit {
  NurbsSurface surface;
  std::vector<double> u, v;  // final parameters of each point
  double max_error = 0;      // max |S(ū_k, v̄_k) − Q_k| (mm)
  double rms_error = 0;
};

// A rows × cols grid of points (row-major; rows along u), parameters by averaged chord
// lengths (Eq. 9.9-9.10). The problem separates: fits along u for every column, then
// along v, which is the exact least-squares solution for grid data.
SurfaceFit fit_surface_grid(const std::vector<Vector3d>& grid, int rows, int cols,
                            const SurfaceFitOptions& options);

// Scattered points with given parameters (u_k, v_k) in [0, 1]².
SurfaceFit fit_surface_scattered(const std::vector<Vector3d>& points, std::vector<double> u,
                                 std::vector<double> v, const SurfaceFitOptions& options);

}  // namespace freeturn::nurbs
