#pragma once
// The design surface as the planner sees it: a height field z = f(x, y) in the workpiece
// frame (z along the spindle axis, toward the tool; mm; docs/conventions.md). Every
// surface a lathe cuts from +z is one; parametric ones (NURBS) provide the same view by
// inverting their parameterisation.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>

namespace freeturn {

// Sag z(x, y) and its first and second partial derivatives at one point.
struct HeightDerivatives {
  double z = 0, zx = 0, zy = 0;
  double zxx = 0, zxy = 0, zyy = 0;
};

class Surface {
 public:
  virtual ~Surface() = default;

  // The type name used in YAML ("even_asphere", ...).
  virtual const char* type() const = 0;

  // Fast path for the hot loops: sag and gradient, no allocation.
  virtual void sag_gradient(double x, double y, double& z, double& zx, double& zy) const = 0;

  // Sag with first and second derivatives (curvature needs the second).
  virtual HeightDerivatives height_derivatives(double x, double y) const = 0;

  // The radius about the z axis inside which the surface is defined (a conic's square
  // root stays real, a lens array has lenslets); infinity when defined everywhere.
  virtual double defined_radius() const { return std::numeric_limits<double>::infinity(); }

  // True when the surface has creases (slope discontinuities: lenslet rims, a cone's
  // vertex). Chord errors across a crease peak sharply, so they are sampled more densely.
  virtual bool has_creases() const { return false; }

  double sag(double x, double y) const;
  // (x, y, z(x, y)).
  Eigen::Vector3d point(double x, double y) const;
  // Unit normal (−zx, −zy, 1)/|·|, pointing out of the part toward the tool.
  Eigen::Vector3d normal(double x, double y) const;
};

}  // namespace freeturn
