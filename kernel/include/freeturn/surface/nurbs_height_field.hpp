#pragma once
// A NURBS surface seen as a height field z = f(x, y): (x, y) is mapped back to (u, v) by
// Newton's method on the first two coordinates of S(u, v), warm-started from the previous
// query of the same thread (a tool path moves a little between points), with the
// kernel's cold ray intersection along −z as the fallback. Surfaces fitted to data on
// x-y parameters (height_grid, point_cloud) have x affine in u and y in v; they skip the
// inversion altogether.
//
// S and its partials come from a span cache (nurbs/surface_span_cache.hpp), one per thread,
// which a path's consecutive queries reuse while they stay in one knot span. Its answer is
// a function of (u, v) alone, so the bits do not depend on the thread or on the queries
// before. The thread's cache and warm start are tied to this surface by an instance id
// drawn afresh by every construction, copy and move: never by address, which a later
// surface could reuse.
//
// Derivatives of the graph from those of S (implicit function theorem): with J the 2×2
// Jacobian of (S_x, S_y) in (u, v) and g = (∂S_z/∂u, ∂S_z/∂v),
//   ∇z = J⁻ᵀ g,    ∇²z = J⁻ᵀ (∇²S_z − z_x ∇²S_x − z_y ∇²S_y) J⁻¹.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "freeturn/core/instance_id.hpp"
#include "freeturn/nurbs/surface_locator.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

class NurbsHeightField final : public Surface {
 public:
  // Throws InputError("surface", …) when the surface is not a graph over x-y (its
  // projection folds over: the Jacobian of (S_x, S_y) changes sign), naming (u, v).
  explicit NurbsHeightField(nurbs::NurbsSurface surface);

  const char* type() const override { return "nurbs"; }
  // NaN outside the surface's projection onto the x-y plane.
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;
  // The largest disc about the origin inside the projection (0 if the origin is outside).
  double defined_radius() const override { return defined_radius_; }
  // On affine parameters and a non-rational surface, from the control net's differences
  // (the whole surface, whatever the radius); +∞ otherwise.
  double max_bend(double) const override { return bend_bound_; }
  double max_slope(double) const override { return slope_bound_; }

  // Creases are the seams where the surface is only C⁰: an interior knot of multiplicity
  // at least the degree whose knot line the normal turns across (a double knot of a
  // quadratic circle's net is C⁰ in parameter but smooth in shape, and is no crease).
  bool has_creases() const override { return !crease_u_.empty() || !crease_v_.empty(); }
  // Where the radial section crosses those knot lines: in closed form on affine
  // parameters, else by sign changes of u − u* (v − v*) along the section and bisection.
  int section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                      std::span<double> out) const override;
  std::span<const double> crease_knots_u() const { return crease_u_; }
  std::span<const double> crease_knots_v() const { return crease_v_; }

  const nurbs::NurbsSurface& nurbs() const { return locator_.surface(); }
  const nurbs::SurfaceLocator& locator() const { return locator_; }
  // True when x = x0 + sx·u and y = y0 + sy·v exactly (no inversion needed).
  bool affine_parameters() const { return affine_; }

  // The parameters of the surface point above (x, y); false outside the projection.
  bool parameters_at(double x, double y, double& u, double& v) const;

 private:
  bool newton(double x, double y, double& u, double& v) const;
  // S and its partials to `order` through this thread's span cache.
  nurbs::SurfaceDerivatives evaluate_cached(double u, double v, int order) const;
  // Derivatives at (u, v) over the point (x, y); at a pole (J singular) the gradient comes
  // from the limit normal and the Hessian from central differences of the gradient.
  HeightDerivatives derivatives_at(double x, double y, double u, double v, int order) const;
  double boundary_distance() const;
  void find_creases();
  // bend_bound_ and slope_bound_ from the net, on affine parameters.
  void bound_from_net();

  InstanceId id_;  // the thread caches' key
  nurbs::SurfaceLocator locator_;
  bool affine_ = false;
  double x0_ = 0, sx_ = 1, y0_ = 0, sy_ = 1;
  double bend_bound_ = std::numeric_limits<double>::infinity();   // max_bend
  double slope_bound_ = std::numeric_limits<double>::infinity();  // max_slope
  double z_above_ = 0;  // above every control point: the origin of cold rays
  double scale_ = 1;    // size of the control net, for tolerances
  double defined_radius_ = 0;
  std::vector<double> crease_u_, crease_v_;  // knot values of the seams, ascending
};

}  // namespace freeturn
