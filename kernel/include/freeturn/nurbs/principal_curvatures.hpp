#pragma once
// Normal, principal curvatures and principal directions of a parametric surface at a
// point, from its first and second fundamental forms (do Carmo, §3.3; The NURBS Book
// uses the same forms for offset and curvature checks).

#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

struct PrincipalCurvatures {
  Vector3d normal = Vector3d::Zero();  // Su × Sv / |Su × Sv|
  double k1 = 0, k2 = 0;               // k1 ≥ k2; positive where the surface bends toward
                                       // the normal (a sphere seen from inside: +1/R)
  Vector3d d1 = Vector3d::Zero();      // unit tangent directions of k1 and k2
  Vector3d d2 = Vector3d::Zero();
  bool regular = false;  // false where Su × Sv vanishes (a pole)
};

// d: a point evaluated with order 2.
PrincipalCurvatures principal_curvatures(const SurfaceDerivatives& d);

}  // namespace freeturn::nurbs
