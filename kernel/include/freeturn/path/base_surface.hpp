#pragma once
// The base surface of revolution about the z axis (paper 000, §3): z = H(ρ), with the
// generating curve H a cubic (or any degree) B-spline in ρ over [0, ρ_max] and H'(0) = 0.
// A plane is H ≡ 0. The space Archimedean spiral lives on it, parameterised by the arc
// length s of the generating curve from the axis (paper 000, Eq. 3-7).
//
// The curve is held as a non-rational NurbsCurve (ρ(u), H(u), 0) whose ρ control
// coordinates are the Greville abscissae, so ρ = u exactly and s(ρ) comes from the
// kernel's ArcLengthTable. Its inverse ρ(s), which a spiral needs for every trial point,
// is a quintic Hermite table on a uniform grid in s built once from exact values and the
// exact derivatives ρ' = 1/√(1 + H'²), ρ'' = −H'H''/(1 + H'²)²: O(1) per query,
// interpolation error below 1e-13 mm.

#include <Eigen/Core>
#include <vector>

#include "freeturn/nurbs/arc_length.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct BasePoint {
  double rho = 0;    // distance from the axis (mm)
  double h = 0;      // H(ρ)
  double slope = 0;  // H'(ρ)
  double curvature = 0;  // H''(ρ)
};

class BaseSurface {
 public:
  // The plane z = 0 out to rho_max.
  static BaseSurface plane(double rho_max);
  // H as the B-spline of the given degree with clamped `knots` on [0, rho_max] and one
  // coefficient per basis function. Throws InputError for inconsistent sizes.
  BaseSurface(int degree, std::vector<double> knots, std::vector<double> coefficients);

  double rho_max() const { return rho_max_; }
  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  const std::vector<double>& coefficients() const { return coefficients_; }
  bool is_plane() const { return plane_; }

  // H and its first two derivatives at ρ in [0, ρ_max] (clamped).
  BasePoint at_radius(double rho) const;
  // The point at arc length s from the axis along the generating curve.
  // Past the edge (s > total_arc_length) the curve continues along its edge tangent.
  BasePoint at_arc_length(double s) const;
  // Arc length from the axis to ρ.
  double arc_length(double rho) const;
  double total_arc_length() const { return table_.total(); }

  // On the surface at (ρ, θ): the point (ρ cos θ, ρ sin θ, H) and the unit normal
  // (−H' cos θ, −H' sin θ, 1)/√(1 + H'²).
  static Eigen::Vector3d point(const BasePoint& b, const RadialLine& line);
  static Eigen::Vector3d normal(const BasePoint& b, const RadialLine& line);

 private:
  BasePoint from_parameter(double u) const;
  void build_inverse_table();

  int degree_ = 1;
  std::vector<double> knots_, coefficients_;
  double rho_max_ = 0;
  bool plane_ = false;
  nurbs::ArcLengthTable table_;
  // The knot spans' starts t_k (non-empty spans, ascending) and, p + 1 per span, the
  // Taylor coefficients of H about t_k (from_parameter).
  std::vector<double> span_start_, span_taylor_;
  // ρ, dρ/ds, d²ρ/ds² at s_k = k·ds_ (k = 0 … n).
  double ds_ = 0;
  std::vector<double> inverse_rho_, inverse_d1_, inverse_d2_;
};

}  // namespace freeturn
