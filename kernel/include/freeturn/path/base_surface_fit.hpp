#pragma once
// Fitting the base surface of revolution to a design surface, and the quasi-revolution
// test (paper 000, §4, Eq. 9-11).
//
// The design surface is sampled on a polar grid over the aperture; the samples, rotated
// into one half plane, give points (ρ, h) to which the generating curve H(ρ) is fitted by
// least squares (with H'(0) = 0, so the base is smooth on its axis). The quasi-revolution
// angle of a sample is α = ∠(n_design, n_base); the design is of quasi-revolution for the
// base when max α < α_lim.

#include <Eigen/Core>
#include <vector>

#include "freeturn/path/base_axis.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct SurfaceSample {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// #R·#A samples on `radial` radii from inner to outer (one sample on the axis when
// inner = 0) and `angular` angles. Throws InputError naming (x, y) where the surface is
// undefined.
std::vector<SurfaceSample> sample_aperture(const Surface& surface, double inner_radius,
                                           double outer_radius, int radial = 48,
                                           int angular = 96);

struct BaseFitOptions {
  int degree = 3;
  int spans = 8;         // uniform knot spans of H over [0, rho_max]
  double rho_max = 0;    // domain of H; 0 → the largest sample radius
};

// Least-squares H(ρ) through the samples' (ρ, z), with H'(0) = 0. A small second-
// difference penalty keeps spans without samples (inside an inner radius) defined.
BaseSurface fit_base_least_squares(const std::vector<SurfaceSample>& samples,
                                   const BaseFitOptions& options = {});

struct QuasiRevolution {
  double max_angle = 0;  // max α over the samples (rad)
  double rms_angle = 0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();  // the sample with the largest α
};

// α_i = ∠(n_design, n_base) at every sample, about `axis` (default: the z axis), computed
// as atan2(sin α, |cos α|) (accurate for small angles).
QuasiRevolution measure_quasi_revolution(const std::vector<SurfaceSample>& samples,
                                         const BaseSurface& base, const BaseAxis& axis = {});

}  // namespace freeturn
