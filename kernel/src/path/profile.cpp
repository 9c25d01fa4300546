#include "freeturn/path/profile.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "freeturn/core/number_text.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "nose_section.hpp"
#include "path_stepper.hpp"
#include "section_prediction.hpp"

namespace freeturn {
namespace {

// τ = r_outer − r; X = r, C = 0, Z = f(r, 0).
class ProfilePath {
 public:
  ProfilePath(const Surface& design, const ProfileOptions& o)
      : design_(design), o_(o), nose_(design, o.tool, stand_off_for(o.points, o.tool, design)) {}

  double tau_end() const { return o_.outer_radius - o_.inner_radius; }
  double cap() const { return o_.points.max_radial_step; }
  // At one feed a block's time is its X-Z chord (pvt_rule.hpp).
  double block_time(const detail::AxisState& a, const detail::AxisState& b) const {
    return std::hypot(b.x_axis - a.x_axis, b.z - a.z);
  }
  bool creased() const { return design_.has_creases(); }
  bool holds_still() const { return true; }  // C is fixed: a held nose may not move
  bool prune_samples() const { return false; }  // one short pass: every sample is taken
  double stand_off() const { return nose_.stand_off(); }
  double chord_floor() const { return nose_.chord_floor(); }
  double axis_offset() const { return nose_.axis_offset(); }
  std::string why_not_smooth(const detail::AxisState& s) const {
    return nose_.why_not_smooth(RadialLine{}, s.contact_r);
  }

  double deviation(double x_axis, const RadialLine&, double z, double b, double hint_r) const {
    return nose_.deviation(x_axis, RadialLine{}, z, b, hint_r);
  }
  double deviation_near_hint(double x_axis, const RadialLine&, double z, double b, double hint_r,
                             double& touch_rho) const {
    return nose_.deviation_near_hint(x_axis, RadialLine{}, z, b, hint_r, touch_rho);
  }
  // A profile is one short pass: every segment on a creased design is measured in full.
  bool touch_clear(const RadialLine&, double, double) const { return false; }
  // A single pass: only its own touch counts.
  double slide(double x_axis, double, double z, double b, const detail::AxisState& ideal,
               double* ends = nullptr) const {
    return nose_.slide(x_axis, z, b, ideal.x_axis, ideal.z, ideal.b, ideal.contact_r, ideal.slope,
                       0.0, ends);
  }

  void at(double tau, const RadialLine&, detail::AxisState& s) const { at(tau, s); }
  void at(double tau, detail::AxisState& s) const {
    const double r = tau >= tau_end() ? o_.inner_radius : o_.outer_radius - tau;
    s.tau = tau;
    s.c = 0;
    place(r, s);
  }
  void commit(const detail::AxisState&) {}

 private:
  // The contact at radius r, the nose's touch (held at a crease where it would overhang
  // one) and the axes.
  void place(double r, detail::AxisState& s) const {
    double z, zx, zy;
    design_.sag_gradient(r, 0.0, z, zx, zy);
    const NoseTouch touch = nose_.touch(RadialLine{}, r, z, zx);
    s.contact_r = touch.rho;
    s.point = {touch.rho, 0.0, touch.z};
    s.slope = touch.slope;
    s.held = touch.held;
    s.uncut = touch.held ? touch.uncut : 0.0;
    s.crease_rho = touch.held ? touch.crease_rho : 0.0;
    s.rolling = touch.rolling;
    s.at_ridge = touch.at_ridge;
    s.path_r = r;
    s.spread = touch.spread;
    nose_.axes(touch.rho, touch.z, touch.slope, s.x_axis, s.z, s.b);
  }

  const Surface& design_;
  const ProfileOptions& o_;
  detail::NoseSection nose_;
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
      throw InputError("r = " + std::to_string(r) + " mm", "the design surface is undefined here",
                       "aperture.outer_radius");
    for (int j = 1; j < 64; ++j) {
      const double phi = 2 * std::numbers::pi * j / 64;
      const double dz = std::abs(design.sag(r * std::cos(phi), r * std::sin(phi)) - z0);
      if (!(dz <= o.symmetry_tolerance))
        throw InputError("r = " + std::to_string(r) + " mm, θ = " +
                             std::to_string(phi * 180 / std::numbers::pi) + "°",
                         "the design surface is not rotationally symmetric: its sag differs from "
                         "the profile by " + significant_text(dz * 1e3, 6) +
                             " µm; cut it with a spiral",
                         "strategy.mode");
    }
  }
  ProfilePath path(design, o);
  ContactChunker out(sink);
  PathSummary summary;
  detail::distribute(path, o.points, [&](const detail::AxisState& s, double error, bool jump) {
    ContactPoint p;
    p.theta = 0;
    p.r = s.contact_r;
    p.point = s.point;
    detail::set_chord(p, s, error, jump, path.stand_off(), path.chord_floor());
    detail::fill_section(design, p, s.rolling || s.at_ridge ? &s.slope : nullptr, s.at_ridge);
    summary.add(p.theta, p.r, p.chord_error, jump);
    out.push(p);
  });
  out.flush();
  return summary;
}

}  // namespace freeturn
