#pragma once
// Rational B-spline (NURBS) curves of any degree in 3D (The NURBS Book, ch. 3-5).
// Control points are stored in homogeneous form P^w = (w·x, w·y, w·z, w).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "freeturn/nurbs/knot_vector.hpp"

namespace freeturn::nurbs {

using Eigen::Vector3d;
using Eigen::Vector4d;

// A point of a curve with its first and second derivatives with respect to u.
struct CurveDerivatives {
  Vector3d point = Vector3d::Zero();
  Vector3d d1 = Vector3d::Zero();
  Vector3d d2 = Vector3d::Zero();
};

class NurbsCurve {
 public:
  NurbsCurve() = default;

  // degree: p ≥ 1. knots: n + p + 2 values. points: n + 1 control points.
  // weights: n + 1 positive weights, or empty for a non-rational curve.
  // Throws InputError naming the bad item (knot, point or weight index).
  NurbsCurve(int degree, std::vector<double> knots, const std::vector<Vector3d>& points,
             const std::vector<double>& weights = {});

  // From homogeneous control points (w·x, w·y, w·z, w); validated as above.
  NurbsCurve(KnotVector knots, std::vector<Vector4d> homogeneous_points);

  int degree() const { return knots_.degree(); }
  const KnotVector& knots() const { return knots_; }
  int count() const { return static_cast<int>(points_.size()); }
  const std::vector<Vector4d>& homogeneous_points() const { return points_; }
  Vector3d control_point(int i) const { return points_[i].head<3>() / points_[i].w(); }
  double weight(int i) const { return points_[i].w(); }
  bool is_rational() const { return rational_; }

  // Parameter domain [front, back].
  double front() const { return knots_.front(); }
  double back() const { return knots_.back(); }

  // C(u); u is clamped to the domain.
  Vector3d point(double u) const;
  // C, C', C'' at u (order 0, 1 or 2 fills that many derivatives).
  CurveDerivatives evaluate(double u, int order = 2) const;
  // Derivatives 0…n of C at u into out[0…n] (A3.2 on P^w, then the quotient rule A4.2).
  void derivatives(double u, int n, Vector3d* out) const;

  // Curvature |C' × C''| / |C'|³ at u.
  double curvature(double u) const;

  // The same curve with the knot u inserted `times` times (A5.1); the shape is unchanged.
  NurbsCurve insert_knot(double u, int times = 1) const;

  // True when C(front) and C(back) coincide within `tolerance` (mm).
  bool is_closed(double tolerance = 1e-12) const;

 private:
  void validate_points() const;

  KnotVector knots_;
  std::vector<Vector4d> points_;
  bool rational_ = false;
};

// Binomial coefficient C(n, k) for the small n of derivative formulas.
double binomial(int n, int k);

}  // namespace freeturn::nurbs
