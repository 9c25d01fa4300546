#pragma once
// Rational B-spline (NURBS) surfaces of any degree (The NURBS Book, ch. 3-5).
// Control net: count_u × count_v homogeneous points P^w_{i,j} = (w·x, w·y, w·z, w), stored
// row-major with i (the u direction) as the row: index i·count_v + j.

#include <Eigen/Core>
#include <vector>

#include "freeturn/nurbs/curve.hpp"
#include "freeturn/nurbs/knot_vector.hpp"

namespace freeturn::nurbs {

// A surface point with its partial derivatives up to second order.
struct SurfaceDerivatives {
  Vector3d point = Vector3d::Zero();
  Vector3d su = Vector3d::Zero(), sv = Vector3d::Zero();
  Vector3d suu = Vector3d::Zero(), suv = Vector3d::Zero(), svv = Vector3d::Zero();
};

class NurbsSurface {
 public:
  NurbsSurface() = default;

  // points: count_u × count_v control points, row-major (index i·count_v + j).
  // weights: as many positive weights, or empty for a non-rational surface.
  // Throws InputError naming the bad knot, point or weight.
  NurbsSurface(int degree_u, int degree_v, const std::vector<double>& knots_u,
               const std::vector<double>& knots_v, const std::vector<Vector3d>& points,
               const std::vector<double>& weights = {});
  NurbsSurface(KnotVector knots_u, KnotVector knots_v, std::vector<Vector4d> homogeneous_points);

  int degree_u() const { return knots_u_.degree(); }
  int degree_v() const { return knots_v_.degree(); }
  const KnotVector& knots_u() const { return knots_u_; }
  const KnotVector& knots_v() const { return knots_v_; }
  int count_u() const { return knots_u_.count(); }
  int count_v() const { return knots_v_.count(); }
  const std::vector<Vector4d>& homogeneous_points() const { return points_; }
  const Vector4d& homogeneous_point(int i, int j) const { return points_[i * count_v() + j]; }
  Vector3d control_point(int i, int j) const {
    const Vector4d& p = homogeneous_point(i, j);
    return p.head<3>() / p.w();
  }
  bool is_rational() const { return rational_; }

  double front_u() const { return knots_u_.front(); }
  double back_u() const { return knots_u_.back(); }
  double front_v() const { return knots_v_.front(); }
  double back_v() const { return knots_v_.back(); }

  // S(u, v); parameters are clamped to the domain.
  Vector3d point(double u, double v) const;
  // S and its partials up to `order` (0, 1 or 2): A3.6 on P^w, then the quotient rule A4.4.
  SurfaceDerivatives evaluate(double u, double v, int order = 1) const;

  // Unit normal Su × Sv / |Su × Sv|; on a degenerate edge (a pole, where Su or Sv
  // vanishes) its limit from inside the domain. Zero only if the surface is degenerate
  // in both directions.
  Vector3d normal(double u, double v) const;

  // The same surface with a knot inserted `times` times in u (or v) (A5.1 applied to each
  // column (row) of the net, as in A5.3); the shape is unchanged.
  NurbsSurface insert_knot_u(double u, int times = 1) const;
  NurbsSurface insert_knot_v(double v, int times = 1) const;

  // Isoparametric curves: v fixed (a curve in u), u fixed (a curve in v).
  NurbsCurve curve_at_v(double v) const;
  NurbsCurve curve_at_u(double u) const;

 private:
  KnotVector knots_u_, knots_v_;
  std::vector<Vector4d> points_;
  bool rational_ = false;
};

}  // namespace freeturn::nurbs
