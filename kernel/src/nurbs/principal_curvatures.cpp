#include "freeturn/nurbs/principal_curvatures.hpp"

#include <algorithm>
#include <cmath>

namespace freeturn::nurbs {

PrincipalCurvatures principal_curvatures(const SurfaceDerivatives& d) {
  PrincipalCurvatures pc;
  const Vector3d cross = d.su.cross(d.sv);
  const double len = cross.norm();
  const double E = d.su.dot(d.su), F = d.su.dot(d.sv), G = d.sv.dot(d.sv);
  if (!(len > 1e-14 * std::max(E, G))) return pc;
  pc.regular = true;
  pc.normal = cross / len;
  const double L = d.suu.dot(pc.normal), M = d.suv.dot(pc.normal), N = d.svv.dot(pc.normal);
  // Shape operator S = I⁻¹ II = [[a, b], [c, d]]; its eigenvalues are the principal
  // curvatures. The discriminant ((a − d)/2)² + bc keeps its accuracy at umbilics, where
  // H² − K would lose half the digits to cancellation.
  const double det_i = E * G - F * F;
  const double a = (G * L - F * M) / det_i, b = (G * M - F * N) / det_i;
  const double c = (E * M - F * L) / det_i, dd = (E * N - F * M) / det_i;
  const double H = 0.5 * (a + dd);
  const double disc = std::sqrt(std::max(0.0, 0.25 * (a - dd) * (a - dd) + b * c));
  pc.k1 = H + disc;
  pc.k2 = H - disc;
  // An eigenvector (du, dv) of S for k: (b, k − a) or (k − d, c), the longer one.
  auto direction = [&](double k) -> Vector3d {
    const double x1 = b, y1 = k - a, x2 = k - dd, y2 = c;
    const bool first = x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2;
    const Vector3d t = first ? Vector3d(x1 * d.su + y1 * d.sv) : Vector3d(x2 * d.su + y2 * d.sv);
    const double n = t.norm();
    return n > 0 ? Vector3d(t / n) : Vector3d::Zero();
  };
  const double scale = std::max(std::abs(pc.k1), std::abs(pc.k2));
  if (disc <= 1e-12 * scale || scale == 0) {
    // Umbilic: every direction is principal; report an orthonormal pair.
    pc.d1 = d.su.normalized();
    pc.d2 = pc.normal.cross(pc.d1);
  } else {
    pc.d1 = direction(pc.k1);
    pc.d2 = pc.normal.cross(pc.d1);
  }
  return pc;
}

}  // namespace freeturn::nurbs
