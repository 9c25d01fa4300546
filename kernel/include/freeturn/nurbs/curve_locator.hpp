#pragma once
// Closest points on a NURBS curve (point inversion, The NURBS Book §6.1, Eq. 6.3-6.5):
// Newton on f(u) = |C(u) − P|²/2 with step control, clamped ends (or wrapping on a
// closed curve), seeded from knot-aware samples or warm-started from a previous answer.

#include <vector>

#include "freeturn/core/status.hpp"
#include "freeturn/nurbs/curve.hpp"
#include "freeturn/nurbs/surface_locator.hpp"

namespace freeturn::nurbs {

struct CurvePointResult {
  double u = 0;
  Vector3d point = Vector3d::Zero();
  double distance = 0;
  Status status = Status::kNotConverged;
  int iterations = 0;
};

class CurveLocator {
 public:
  explicit CurveLocator(NurbsCurve curve, LocatorOptions options = {});

  const NurbsCurve& curve() const { return curve_; }
  bool closed() const { return closed_; }

  // The closest point of the whole curve to p.
  CurvePointResult closest_point(const Vector3d& p) const;
  // The closest point near u0 (a local answer).
  CurvePointResult closest_point(const Vector3d& p, double u0) const;

 private:
  double wrap_or_clamp(double u) const;

  NurbsCurve curve_;
  LocatorOptions options_;
  bool closed_ = false;
  std::vector<double> params_;
  std::vector<Vector3d> samples_;
};

}  // namespace freeturn::nurbs
