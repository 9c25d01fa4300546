#pragma once
// The quotient rule for a rational surface's partials (The NURBS Book, A4.4), shared by
// the direct evaluation (A3.6) and the span cache's power form. Internal to nurbs/.

#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

// aw[k][l]: the homogeneous partials ∂^(k+l) S^w / ∂u^k ∂v^l for k + l ≤ d (d ≤ 2).
inline SurfaceDerivatives rational_surface_derivatives(const Vector4d (&aw)[3][3], int d) {
  constexpr double kBinomial[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 2, 1}};
  // S^(k,l) = (A^(k,l) − Σ_j C(l,j) w^(0,j) S^(k,l−j) − Σ_i C(k,i) w^(i,0) S^(k−i,l)
  //            − Σ_i Σ_j C(k,i) C(l,j) w^(i,j) S^(k−i,l−j)) / w.
  Vector3d s[3][3];
  for (int k = 0; k <= d; ++k) {
    for (int l = 0; l <= d - k; ++l) {
      Vector3d v3 = aw[k][l].head<3>();
      for (int j = 1; j <= l; ++j) v3 -= kBinomial[l][j] * aw[0][j].w() * s[k][l - j];
      for (int i = 1; i <= k; ++i) {
        v3 -= kBinomial[k][i] * aw[i][0].w() * s[k - i][l];
        for (int j = 1; j <= l; ++j)
          v3 -= kBinomial[k][i] * kBinomial[l][j] * aw[i][j].w() * s[k - i][l - j];
      }
      s[k][l] = v3 / aw[0][0].w();
    }
  }
  SurfaceDerivatives out;
  out.point = s[0][0];
  if (d >= 1) {
    out.su = s[1][0];
    out.sv = s[0][1];
  }
  if (d >= 2) {
    out.suu = s[2][0];
    out.suv = s[1][1];
    out.svv = s[0][2];
  }
  return out;
}

}  // namespace freeturn::nurbs
