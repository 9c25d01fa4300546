#pragma once
// A measured surface registered to the design and its form error fitted, in one least
// squares problem (docs/metrology.md).
//
// A measured point p (the instrument's frame) is the design's point q = R·p + t with
//   R = Rz(clocking) · Ry(tilt_y) · Rx(tilt_x),   t = (decentre_x, decentre_y, piston),
// and the part's error E(q) = Σ a_j Z_j(q_x / R_n, q_y / R_n) (Noll's Zernike terms over
// the normalisation radius R_n) is what its height has beyond the design's:
//   r(p) = q_z − design(q_x, q_y) − E(q_x, q_y) → min over the pose and the a_j.
// The correspondence is along z at the transformed (x, y), remade every iteration: the
// closest-point step of ICP for a height field. Solved by Gauss–Newton with a
// Levenberg–Marquardt damping (Nocedal & Wright §10.3); a pose the data cannot tell apart
// (the clocking of a rotationally symmetric design) stays where the damping holds it.
// The terms the pose already holds are left out of E: Z1 (piston) when piston is
// registered, Z2 and Z3 (tilt) when tilt is.
//
// Outliers: after convergence, points with |r − median(r)| > k · 1.4826 · MAD(r) (a robust
// σ; k = outlier_sigmas) are dropped and the fit repeated, until none is dropped (at most
// three times).

#include <optional>
#include <string>
#include <vector>

#include "freeturn/io/measurement_file.hpp"
#include "freeturn/nurbs/surface.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

// How far the B-spline part of the error reaches, in R_n: the corrected design is evaluated
// past the aperture's edge (docs/metrology.md).
inline constexpr double kBsplineReach = 1.5;

struct RegistrationOptions {
  bool piston = true, tilt = true, decentre = true, clocking = true;  // the pose's free parts
  // A 2-D profile along x (y = 0): only the tilt about y, the decentre in x and the
  // rotationally symmetric terms (m = 0) can be seen in it; the rest stays 0.
  bool profile = false;
  int zernike_terms = 36;         // fit Noll terms 1 … N (N ≤ 231; 0: register only)
  double normalization_radius = 0;  // mm, R_n; the aperture's outer radius
  double inner_radius = 0, outer_radius = 0;  // mm: points registered outside are not used
  double outlier_sigmas = 5;
  int max_iterations = 50;
  // What the Zernike terms leave, fitted after them as a bicubic B-spline height over
  // [−kBsplineReach·R_n, kBsplineReach·R_n]², bspline_control control points per side over
  // the aperture's diameter (the same knot spacing beyond it), with thin-plate smoothing
  // (nurbs/least_squares.hpp): a local error (a bump, a zone) no low-order polynomial holds.
  // 0: no B-spline.
  int bspline_control = 0;
  double bspline_smoothing = 0;
};

struct Registration {
  double piston = 0, tilt_x = 0, tilt_y = 0;        // mm, rad, rad
  double decentre_x = 0, decentre_y = 0, clocking = 0;  // mm, mm, rad
  double normalization_radius = 0;
  std::vector<double> zernike;  // a_j for j = 1 … N (mm); 0 for terms left out
  // The B-spline part of the error (x, y, z in mm; x affine in u, y in v, over
  // [−kBsplineReach·R_n, kBsplineReach·R_n]²), when asked for; bspline_height reads it.
  std::optional<nurbs::NurbsSurface> bspline;
  int bspline_control = 0;  // its control points per side over the aperture, as asked for
  double bspline_rms = 0;  // its RMS over the points used (mm)
  double measured_rms = 0, measured_pv = 0;  // the error E + r over the points used (mm)
  double fit_rms = 0;     // what E (Zernike and B-spline) does not explain, over the points used (mm)
  long used = 0, outliers = 0, outside = 0;  // points used, dropped as outliers, outside the aperture
  int iterations = 0;
};

// The B-spline part of an error at (x, y) (mm, the design's frame), fitted for the
// normalization radius R_n: (x, y) outside its square take its edge's value.
double bspline_height(const nurbs::NurbsSurface& bspline, double normalization_radius, double x,
                      double y);

// Throws InputError at `where` (the measurement file) when the measurement cannot be
// registered: too few points inside the aperture, or a pose that runs away (diverging).
Registration register_measurement(const Surface& design, const Measurement& measurement,
                                  const RegistrationOptions& options, const std::string& where);

}  // namespace freeturn
