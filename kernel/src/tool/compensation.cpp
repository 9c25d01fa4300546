#include "freeturn/tool/compensation.hpp"

#include <cmath>
#include <limits>

namespace freeturn {

double programmed_point_offset(const CompensationOptions& o) {
  if (o.pivot_distance > 0) return o.pivot_distance;
  return o.tool.program_point == ProgramPoint::kTip ? -o.tool.nose_radius : 0.0;
}

ToolMotion tool_motion(const CompensationOptions& o) {
  ToolMotion m;
  m.nose_radius = o.tool.nose_radius;
  m.axis_offset = programmed_point_offset(o);
  m.b_follows = o.b_mode == BMode::kFollow;
  m.edge_angle = o.edge_angle;
  m.waviness_span = o.tool.waviness_span();
  m.waviness_slope = o.tool.waviness_slope();
  m.centre_height = o.tool.centre_height;
  return m;
}

CutterLocation compensate(const ContactPoint& contact, const CompensationOptions& o) {
  return compensate(contact, o, RadialLine(contact.theta));
}

CutterLocation compensate(const ContactPoint& contact, const CompensationOptions& o,
                          const RadialLine& line) {
  CutterLocation cl;
  cl.contact = contact;
  const double ct = line.cos, st = line.sin;
  const Eigen::Vector3d& n = contact.normal;
  const double n_r = n.x() * ct + n.y() * st, n_z = n.z();
  cl.psi = std::atan2(n_r, n_z);
  cl.b = o.b_mode == BMode::kFollow ? cl.psi - o.edge_angle : o.b_fixed;
  // The nose centre in a vertical plane through the contact, whose normal projects to
  // (n_e, n_z) there at angle ψ: R + δ(ψ − B) + the stand-off along it, `along` being the
  // contact's position in the plane. (along-plane, z).
  const auto centre_in_plane = [&](double n_e, double psi, double along) -> Eigen::Vector2d {
    const double length = std::hypot(n_e, n_z);
    const double radius = o.tool.nose_radius + o.tool.waviness_at(psi - cl.b) + contact.stand_off;
    return {along + radius * (n_e / length), contact.point.z() + radius * (n_z / length)};
  };
  // In the radial plane: the contact's ρ is its signed distance along e_r.
  const double p_r = contact.point.x() * ct + contact.point.y() * st;
  const Eigen::Vector2d centre = centre_in_plane(n_r, cl.psi, p_r);
  cl.nose_centre = {centre.x() * ct, centre.x() * st, centre.y()};
  const double a_r = std::sin(cl.b), a_z = std::cos(cl.b);
  const double offset = programmed_point_offset(o);
  cl.x = centre.x() + offset * a_r;
  cl.z = centre.y() + offset * a_z;
  cl.c = contact.theta;
  const double h = o.tool.centre_height;
  if (h != 0) {
    // The edge is an arc in the rake plane, machine y = h, not in a radial plane. The
    // spindle stands at C = θ − β, sin β = h/ρ, which brings the contact into that plane
    // ρ cos β along e = (cos C, sin C, 0); the nose touches it there along the normal
    // projected into (e, z). The checks and the planner keep the radial plane's nose
    // (nose_centre, ψ, B): the two touch the design at the same point, and differ by
    // first order in β only where the nose touches it twice (docs/tool.md).
    if (!edge_reaches(p_r, h)) {
      // The edge cannot reach a radius under |h| (the centre check reports it).
      cl.x = std::numeric_limits<double>::quiet_NaN();
      return cl;
    }
    const double beta = std::asin(h / p_r);
    cl.c = contact.theta - beta;
    const double n_e = n.x() * std::cos(cl.c) + n.y() * std::sin(cl.c);
    const Eigen::Vector2d rake = centre_in_plane(n_e, std::atan2(n_e, n_z), p_r * std::cos(beta));
    cl.x = rake.x() + offset * a_r;
    cl.z = rake.y() + offset * a_z;
  }
  return cl;
}

Eigen::Vector2d nose_centre_from_axes(double x, double z, double b, const CompensationOptions& o) {
  const double a_r = std::sin(b), a_z = std::cos(b);
  const double offset = programmed_point_offset(o);
  double c_x = x - offset * a_r;
  const double h = o.tool.centre_height;
  if (h != 0) c_x = std::copysign(std::hypot(c_x, h), c_x);
  return {c_x, z - offset * a_z};
}

double work_angle_from_axes(double c, double x, double b, const CompensationOptions& o) {
  const double h = o.tool.centre_height;
  return h != 0 ? c + std::atan2(h, x - programmed_point_offset(o) * std::sin(b)) : c;
}

}  // namespace freeturn
