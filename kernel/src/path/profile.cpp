#include "freeturn/path/profile.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"
#include "path_stepper.hpp"
#include "section_prediction.hpp"

namespace freeturn {
namespace {

// τ = r_outer − r; X = r, C = 0, Z = f(r, 0).
class ProfilePath {
 public:
  ProfilePath(const Surface& design, const ProfileOptions& o) : design_(design), o_(o) {}

  double tau_end() const { return o_.outer_radius - o_.inner_radius; }
  double cap() const { return o_.points.max_radial_step; }
  double angle_per_tau() const { return 0.0; }
  bool creased() const { return design_.has_creases(); }

  double deviation(double x_axis, double, double z) const {
    double f, fx, fy;
    design_.sag_gradient(x_axis, 0.0, f, fx, fy);
    return std::abs(z - f) / std::sqrt(1 + fx * fx + fy * fy);
  }

  void at(double tau, detail::AxisState& s) const {
    const double r = tau >= tau_end() ? o_.inner_radius : o_.outer_radius - tau;
    double z, zx, zy;
    design_.sag_gradient(r, 0.0, z, zx, zy);
    s.tau = tau;
    s.x_axis = r;
    s.c = 0;
    s.z = z;
    s.point = {r, 0.0, z};
    // d/dτ = −d/dr.
    s.dx = -1.0;
    s.dz = -zx;
  }
  void commit(const detail::AxisState&) {}

 private:
  const Surface& design_;
  const ProfileOptions& o_;
};

}  // namespace

PathSummary plan_profile(const Surface& design, const ProfileOptions& o, ContactSink& sink) {
  if (!(o.outer_radius > o.inner_radius && o.inner_radius >= 0))
    throw InputError("aperture", "needs 0 ≤ inner radius < outer radius");
  if (o.points.rule == CutterPointRule::kEqualAngle)
    throw InputError("points", "equal-angle points need a spiral; profile mode takes "
                               "equal_arc_length or chord_error");
  // Rotational symmetry: the profile must be the same at every angle.
  for (int i = 0; i <= 32; ++i) {
    const double r = o.inner_radius + (o.outer_radius - o.inner_radius) * i / 32.0;
    const double z0 = design.sag(r, 0.0);
    if (!std::isfinite(z0))
      throw InputError("r = " + std::to_string(r) + " mm", "the design surface is undefined here");
    for (int j = 1; j < 64; ++j) {
      const double phi = 2 * std::numbers::pi * j / 64;
      const double dz = std::abs(design.sag(r * std::cos(phi), r * std::sin(phi)) - z0);
      if (!(dz <= o.symmetry_tolerance))
        throw InputError("r = " + std::to_string(r) + " mm, θ = " +
                             std::to_string(phi * 180 / std::numbers::pi) + "°",
                         "the design surface is not rotationally symmetric: its sag differs from "
                         "the profile by " + std::to_string(dz * 1e3) +
                             " µm; cut it with a spiral");
    }
  }
  ProfilePath path(design, o);
  ContactChunker out(sink);
  PathSummary summary;
  detail::distribute(path, o.points, [&](const detail::AxisState& s, double error) {
    ContactPoint p;
    p.theta = 0;
    p.r = s.x_axis;
    p.point = s.point;
    p.chord_error = error;
    detail::fill_section(design, p);
    summary.points++;
    summary.max_chord_error = std::max(summary.max_chord_error, error);
    out.push(p);
  });
  out.flush();
  return summary;
}

}  // namespace freeturn
