#pragma once
// The design surface as the planner sees it: a height field z = f(x, y) in the workpiece
// frame (z along the spindle axis, toward the tool; mm; docs/conventions.md). Every
// surface a lathe cuts from +z is one; parametric ones (NURBS) provide the same view by
// inverting their parameterisation.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace freeturn {

// Sag z(x, y) and its first and second partial derivatives at one point.
struct HeightDerivatives {
  double z = 0, zx = 0, zy = 0;
  double zxx = 0, zxy = 0, zyy = 0;
};

// The radial line at angle θ about the z axis, with θ's cosine and sine: a planner's sample
// computes them once and every query along that line reads them (three sine-cosine pairs
// per sample were a tenth of the planner on a compound eye). Implicit from an angle.
struct RadialLine {
  double theta = 0, cos = 1, sin = 0;
  RadialLine() = default;
  RadialLine(double angle) : theta(angle), cos(std::cos(angle)), sin(std::sin(angle)) {}  // NOLINT

  // The line at `angle`, by rotating this one through δ = angle − θ: within 1/16 rad, δ's
  // sine and cosine by their Taylor series (to δ⁹ and δ⁸: the next terms are below 1e-19
  // of them), a few multiplications where a sine-cosine pair costs about 20 ns; farther,
  // the pair. The result is the rotation of this line's cosine and sine, so it carries their
  // rounding (a few ulp where they came from a recurrence).
  RadialLine turned_to(double angle) const {
    const double d = angle - theta;
    if (!(std::abs(d) <= 0.0625)) return RadialLine(angle);
    const double d2 = d * d;
    const double sin_d = d * (1 - d2 / 6 * (1 - d2 / 20 * (1 - d2 / 42 * (1 - d2 / 72))));
    const double cos_d = 1 - d2 / 2 * (1 - d2 / 12 * (1 - d2 / 30 * (1 - d2 / 56)));
    RadialLine line;
    line.theta = angle;
    line.cos = cos * cos_d - sin * sin_d;
    line.sin = sin * cos_d + cos * sin_d;
    return line;
  }
};

// A crease near a point (Surface::creases_near): one curve of the design's creases in (x, y),
// bounded as the nose's envelope needs (path/section_envelope.hpp, touch_clear_of_creases).
struct NearbyCrease {
  double distance = 0;    // mm: at most its distance in (x, y) from the point
  double slope_jump = 0;  // at least the jump of dz/dt across it, t along any unit direction
  int crossings = 0;      // a half-line from the point crosses it at most this often
  // Optional, for a sharper envelope (touch_clear_of_creases): where the crease is the rim
  // of a convex region (a footprint) about a centre e, with the slope's jump at each rim
  // point q along the rim's normal ν(q) in (x, y). Then ν(q) lies within normal_slack of
  // the direction from e to q, (normal_x, normal_y) is the unit direction from e to the
  // point, centre_distance its distance from e (0: nothing of this is known), and the rim
  // bends at most `curvature` (1/mm). A slack or curvature below the truth, like a
  // distance above it, would let the planner miss a crease.
  double normal_x = 0, normal_y = 0;
  double centre_distance = 0;
  double normal_slack = 0;  // rad
  double curvature = 0;
};

// A crease that is a circle in space: a lenslet's rim, where its sphere meets the base
// (Surface::crease_circles). Seen along z it is an ellipse, and a surface moved and tilted
// (TransformedSurface) finds where a section crosses it in closed form.
struct CreaseCircle {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // unit normal of the circle's plane
  double radius = 0;                                 // mm
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

  // False where no crease can be a ridge (a convex crease, the slope falling across it
  // along a section), which the nose rolls over (path/section_envelope.hpp): the planner
  // then does not look for one (domes meet in valleys alone). True may be answered freely.
  virtual bool may_have_ridges() const { return has_creases(); }

  // The creases met along the radial section at angle θ, as signed radii ρ in [rho_lo,
  // rho_hi] (ρ < 0 lies at θ + π), ascending; returns how many lie there and writes the
  // lowest out.size() of them (surface/crease_sink.hpp): a return above out.size() says
  // the list is whole only up to its last entry. The nose's envelope
  // (path/section_envelope.hpp) is exact only at creases it is told of. The default, for a
  // surface with creases, is the vertex (ρ = 0): where a cone's section folds; a lenslet
  // array finds its rims.
  virtual int section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                              std::span<double> out) const;

  // The same along the line through (x0, y0) in the direction of `line`: the creases at
  // signed distances ρ ∈ [rho_lo, rho_hi] from (x0, y0), ascending. A surface decentred
  // without a tilt (TransformedSurface) asks this of its parent for its radial sections.
  // −1 where they are not known off the axis: the default, for a line not through the
  // origin on a surface with creases.
  virtual int line_creases(double x0, double y0, const RadialLine& line, double rho_lo,
                           double rho_hi, std::span<double> out) const;

  // An upper bound of the surface's second derivative along any straight line in (x, y)
  // (d²z/dt² for a unit direction; the largest eigenvalue of the Hessian) at the points
  // within `radius` of the z axis, away from creases: the most a section can bend toward
  // the tool. +∞ when not known (the default). The nose's searches at creases use it to
  // leave out a flank that cannot reach the nose (path/section_envelope.cpp); a bound
  // below the truth would hide an overlap, so it must hold everywhere it is asked.
  virtual double max_bend(double radius) const;

  // The same bound along the surface's radial sections alone (the lines through (0, 0),
  // which every nose section the planner and the tool checks measure lies on): d²g/dρ² at
  // |ρ| ≤ radius, away from creases. max_bend's by default; a surface of revolution whose
  // bend along other lines has no bound (the sinusoidal ring just off its cone point) gives
  // its profile's. A decentred surface's sections are other lines of its parent: it keeps
  // the default, its own max_bend.
  virtual double max_section_bend(double radius) const { return max_bend(radius); }

  // An upper bound of the surface's slope |∇z| at the points within `radius` of the z axis,
  // away from creases; +∞ when not known (the default). A tilted segment's bend is bounded
  // from its parent's slope and bend (TransformedSurface::max_bend).
  virtual double max_slope(double radius) const;

  // The creases within `radius` of (x, y) in (x, y), bounded (NearbyCrease): writes at most
  // out.size() of them and returns how many, or −1 when they are not known (the default for
  // a surface with creases) or do not fit: then nothing may be assumed of the creases
  // there. A surface without creases has none (0). A crease left out, or a distance or jump
  // below the truth, would let the planner measure a segment as smooth where a crease lies
  // under the nose: each bound must hold everywhere it is asked.
  virtual int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const;

  // Every crease of the surface as a circle in space, appended to `out`; false when its
  // creases are not all circles (the default for a surface with creases: a cone's apex is
  // a point). A surface without creases has none (true, nothing appended). A circle left
  // out would let the planner cross a crease unseen where the surface is moved or tilted.
  virtual bool crease_circles(std::vector<CreaseCircle>& out) const;

  double sag(double x, double y) const;
  // (x, y, z(x, y)).
  Eigen::Vector3d point(double x, double y) const;
  // Unit normal (−zx, −zy, 1)/|·|, pointing out of the part toward the tool.
  Eigen::Vector3d normal(double x, double y) const;
};

// Forgets the calling thread's warm starts (a NURBS height field starts its inversion from
// the thread's last answer): the queries that follow give the same bits whatever the
// thread computed before. A piece of work handed to any thread of a pool calls it first.
void forget_thread_warm_starts();

}  // namespace freeturn
