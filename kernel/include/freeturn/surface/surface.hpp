#pragma once
// The design surface as the planner sees it. Frame: workpiece frame, z along the
// spindle axis pointing toward the tool, lengths in mm (docs/conventions.md).

#include <Eigen/Core>

namespace freeturn {

// Sag z(x, y) and its first and second partial derivatives at one point.
struct HeightDerivatives {
  double z = 0, zx = 0, zy = 0;
  double zxx = 0, zxy = 0, zyy = 0;
};

// A design surface given as a height field z = f(x, y) over the aperture.
class Surface {
 public:
  virtual ~Surface() = default;

  // The type name used in YAML ("even_asphere", ...).
  virtual const char* type() const = 0;

  // Fast path for the hot loops: sag and gradient, no allocation.
  virtual void sag_gradient(double x, double y, double& z, double& zx, double& zy) const = 0;

  // Sag with first and second derivatives (curvature needs the second).
  virtual HeightDerivatives height_derivatives(double x, double y) const = 0;

  // Unit normal (-zx, -zy, 1)/|.|, pointing out of the part toward the tool.
  Eigen::Vector3d normal(double x, double y) const;
};

}  // namespace freeturn
