#pragma once
// Creases that are circles in space (lenslet rims, Surface::crease_circles), seen along z
// after a rigid motion: each an ellipse in (x, y), indexed on a grid, so that a surface
// moved and tilted (TransformedSurface) knows where a line in (x, y) crosses them.
//
// A circle of radius ρ about K in the plane normal to a, moved by W = R(X − o), is
// W(φ) = R(K − o) + ρ(cos φ·Re₁ + sin φ·Re₂) (e₁, e₂ unit and normal to a and to each
// other). Seen along z that is p₀ + ρ(cos φ u + sin φ v), u and v the (x, y) parts of Re₁
// and Re₂: the point p lies on it when |M⁻¹(p − p₀)| = ρ, M = [u v]. A line q₀ + t d
// crosses it where |M⁻¹(q₀ − p₀) + t M⁻¹d|² = ρ², a quadratic in t. The design is a height
// field, so the surface over each such point is the rim's own point: a crease of the
// section there.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class ProjectedRims {
 public:
  ProjectedRims() = default;
  // rotation R and origin o: the world point of a surface point X is R(X − o). False (and
  // nothing kept) where a circle is seen edge-on (its plane contains z) or a value is not
  // finite: no section's crossing could then be trusted.
  bool build(std::span<const CreaseCircle> circles, const Eigen::Matrix3d& rotation,
             const Eigen::Vector3d& origin);
  bool empty() const { return rims_.empty(); }

  // The crossings of the line through (x0, y0) along `line`'s direction, at signed
  // distances t ∈ [t_lo, t_hi], ascending, two within 1e-12 mm counted once; returns how
  // many there are and writes the lowest out.size() of them (surface/crease_sink.hpp).
  int crossings(double x0, double y0, const RadialLine& line, double t_lo, double t_hi,
                std::span<double> out) const;

 private:
  struct Rim {
    double px, py;              // p₀, the centre seen along z
    double m00, m01, m10, m11;  // M⁻¹
    double radius;
    double half_x, half_y;  // the ellipse's half extents in x and y
  };
  std::vector<Rim> rims_;
  // A grid over the ellipses' bounding boxes: cell k lists rims items_[start_[k] … start_[k + 1]).
  double x0_ = 0, y0_ = 0, cell_ = 1, inverse_cell_ = 1;
  int per_side_x_ = 0, per_side_y_ = 0;
  std::vector<int> start_, items_;
};

}  // namespace freeturn
