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
  const double length = std::hypot(n_r, n_z);
  const double u_r = n_r / length, u_z = n_z / length;  // n̂_p in (ρ, z)
  cl.psi = std::atan2(n_r, n_z);
  cl.b = o.b_mode == BMode::kFollow ? cl.psi - o.edge_angle : o.b_fixed;
  const double radius =
      o.tool.nose_radius + o.tool.waviness_at(cl.psi - cl.b) + contact.stand_off;
  // In the radial plane: the contact's ρ is its signed distance along e_r.
  const double p_r = contact.point.x() * ct + contact.point.y() * st;
  const double c_r = p_r + radius * u_r, c_z = contact.point.z() + radius * u_z;
  cl.nose_centre = {c_r * ct, c_r * st, c_z};
  const double a_r = std::sin(cl.b), a_z = std::cos(cl.b);
  const double offset = programmed_point_offset(o);
  double x = c_r + offset * a_r, z = c_z + offset * a_z;
  cl.c = contact.theta;
  const double h = o.tool.centre_height;
  if (h != 0) {
    // The edge sits h above the spindle line: at machine X it touches radius √(X² + h²),
    // turned by atan2(h, X). NaN where |x| < |h| (the centre check reports it).
    const double reach = x * x - h * h;
    const double corrected = reach >= 0 ? std::copysign(std::sqrt(reach), x)
                                        : std::numeric_limits<double>::quiet_NaN();
    cl.c = contact.theta - std::atan2(h, corrected);
    x = corrected;
  }
  cl.x = x;
  cl.z = z;
  return cl;
}

Eigen::Vector2d nose_centre_from_axes(double x, double z, double b, const CompensationOptions& o) {
  const double a_r = std::sin(b), a_z = std::cos(b);
  const double h = o.tool.centre_height;
  if (h != 0) x = std::copysign(std::sqrt(x * x + h * h), x);
  const double offset = programmed_point_offset(o);
  return {x - offset * a_r, z - offset * a_z};
}

double work_angle_from_axes(double c, double x, const CompensationOptions& o) {
  const double h = o.tool.centre_height;
  return h != 0 ? c + std::atan2(h, x) : c;
}

}  // namespace freeturn
