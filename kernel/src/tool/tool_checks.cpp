#include "freeturn/tool/tool_checks.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/path/section_envelope.hpp"

namespace freeturn {
namespace {

// Angles in degrees, curvatures as radii, lengths in µm: the units a user reads.
std::string value_text(ToolCheck check, double v) {
  switch (check) {
    case ToolCheck::kContactAngle:
    case ToolCheck::kClearance:
    case ToolCheck::kBLimits:
      return fixed_text(v * 180 / std::numbers::pi, 4) + "°";
    case ToolCheck::kLocalGouge:
      return "concave radius " + significant_text(1 / v, 6) + " mm";
    default:
      return fixed_text(v * 1e3, 4) + " µm";
  }
}

std::string where_text(const CheckFinding& f) {
  return "θ = " + fixed_text(f.theta, 6) + " rad (" + fixed_text(f.theta * 180 / std::numbers::pi, 4) +
         "°), r = " + fixed_text(f.r, 6) + " mm, (x, y) = (" + fixed_text(f.x, 6) + ", " +
         fixed_text(f.y, 6) + ") mm";
}

}  // namespace

const char* tool_check_name(ToolCheck check) {
  static const char* const kNames[kToolCheckCount] = {"contact angle", "clearance",  "gouge",
                                                      "global gouge",  "centre",     "B limits"};
  return kNames[static_cast<int>(check)];
}

std::string ToolCheckReport::summary() const {
  std::string out;
  for (int i = 0; i < kToolCheckCount; ++i)
    if (findings[i].count > 0) out += line(static_cast<ToolCheck>(i)) + "\n";
  return out;
}

std::string ToolCheckReport::line(ToolCheck c) const {
  const CheckFinding& f = (*this)[c];
  const std::string limit = c == ToolCheck::kLocalGouge
                                  ? " < nose radius " + significant_text(1 / f.limit, 6) + " mm"
                                  : " > limit " + value_text(c, f.limit);
  return std::string(tool_check_name(c)) + ": " + std::to_string(f.count) + " points, worst " +
         value_text(c, f.worst) + limit + " at " + where_text(f);
}

ToolChecker::ToolChecker(const Surface& design, const CompensationOptions& compensation,
                         ToolCheckOptions options)
    : design_(design), compensation_(compensation), options_(options) {}

void ToolChecker::found(ToolCheck check, double value, double limit, const CutterLocation& cl) {
  const int i = static_cast<int>(check);
  CheckPolicy policy = options_.policy[i];
  if (check == ToolCheck::kBLimits) policy = CheckPolicy::kError;
  if (policy == CheckPolicy::kOff) return;
  CheckFinding& f = report_.findings[i];
  f.limit = limit;
  f.count++;
  if (f.count == 1 || value > f.worst) {
    f.worst = value;
    f.theta = cl.contact.theta;
    f.r = cl.contact.r;
    f.x = cl.contact.point.x();
    f.y = cl.contact.point.y();
  }
  if (policy == CheckPolicy::kError) {
    CheckFinding here = f;
    here.worst = value;
    here.theta = cl.contact.theta;
    here.r = cl.contact.r;
    here.x = cl.contact.point.x();
    here.y = cl.contact.point.y();
    const bool curvature = check == ToolCheck::kLocalGouge;
    // The tool's setting each check holds against the design.
    static const char* const kCause[kToolCheckCount] = {
        "tool.included_angle_deg", "tool.clearance_angle_deg", "tool.nose_radius",
        "tool.nose_radius",        "tool.centre_height",       ""};
    if (check == ToolCheck::kBLimits) {
      // The machine's limit, not the tool's: the command line reports it where the
      // machine file states the bound crossed.
      const bool below = cl.b < options_.b_min;
      throw CheckFailure(where_text(here),
                         "B limits check: B = " + value_text(check, cl.b) +
                             " is outside the tool-rotation limits [" +
                             value_text(check, options_.b_min) + ", " +
                             value_text(check, options_.b_max) + "]",
                         below ? "machine.b_axis.min_deg" : "machine.b_axis.max_deg");
    }
    if (check == ToolCheck::kCentre)
      // The limit is 0 (an edge off the spindle line reaches no radius under its height):
      // the message says what to change instead.
      throw CheckFailure(
          where_text(here),
          "centre check: the edge, " + value_text(check, value) +
              " off the spindle line, cannot reach r = " + fixed_text(cl.contact.r, 6) +
              " mm: set aperture.inner_radius to at least " +
              significant_text(std::abs(compensation_.tool.centre_height), 6) +
              " mm, or correct the centre height (tool.checks.centre: warning "
              "writes the program leaving material about the axis, UNSAFE)",
          kCause[i]);
    throw CheckFailure(where_text(here),
                     std::string(tool_check_name(check)) + " check: " + value_text(check, value) +
                         (curvature ? " is below the nose radius " +
                                          shortest_text(compensation_.tool.nose_radius) + " mm"
                                    : " exceeds the limit " + value_text(check, limit)),
                       kCause[i]);
  }
}

double ToolChecker::global_gouge_depth(const CutterLocation& cl, const RadialLine& line) const {
  // The edge arc: angles within half the included angle of the tool axis a(B). Its
  // lowest points face the part; the section z_s(ρ) = f(ρ cos θ, ρ sin θ) must stay below
  // the arc, z_s(ρ) ≤ c_z − √(R² − (ρ − c_r)²), everywhere under it.
  const double R = compensation_.tool.nose_radius;
  const double half = 0.5 * compensation_.tool.included_angle;
  const double ct = line.cos, st = line.sin;
  const double c_r = cl.nose_centre.x() * ct + cl.nose_centre.y() * st;
  const double c_z = cl.nose_centre.z();
  double depth;
  if (one_touch_depth(line, c_r, c_z, cl.contact.r, std::abs(cl.b) + half, depth)) return depth;
  double deepest = -1e300;
  const int n = options_.gouge_samples;
  for (int k = 0; k <= n; ++k) {
    // Angle on the edge from the tool axis's opposite (the tip), −half … +half, about B.
    const double phi = cl.b - half + 2 * half * k / n;
    const double rho = c_r - R * std::sin(phi);
    if (std::abs(rho) > options_.outer_radius) continue;
    const double arc_z = c_z - R * std::cos(phi);
    const double zs = design_.sag(rho * ct, rho * st);
    if (!std::isfinite(zs)) continue;
    deepest = std::max(deepest, zs - arc_z);
  }
  // The sampled arc can step over the sharp peak a crease makes; the envelope's search
  // evaluates the section at every crease under the nose and refines near the contact.
  const NoseOverlap exact = nose_overlap(design_, line, c_r, c_z, R, cl.contact.r);
  return std::max(deepest, exact.height);
}

bool ToolChecker::one_touch_depth(const RadialLine& line, double c_r, double c_z, double hint_r,
                                  double edge_reach, double& depth) const {
  // Where the section bends less than the nose (m = 1/R − max_section_bend > 0), the height h(ρ) of
  // the section over the lower arc is m-strongly concave on every smooth piece under it, and
  // where no crease can raise it elsewhere (touch_clear_of_creases) its one maximum is the
  // deepest point: a search from the contact finds it, and the samples along the edge, values
  // of the same h, cannot exceed it. The search's last point ρ lies within |h'(ρ)|/m of the
  // maximum, which exceeds h(ρ) by at most h'(ρ)²/(2m): the depth returned includes that
  // (the margin 1 pm more, for rounding).
  // Only for an edge within the lower half of the nose (|B| + half the included angle below
  // 90°): the envelope bounds the lower arc.
  const double R = compensation_.tool.nose_radius;
  if (!(R > 0) || !(edge_reach < 0.5 * std::numbers::pi)) return false;
  const double m = section_concavity(design_, R, std::abs(c_r) + R);
  if (!(m > 0)) return false;
  const NoseOverlap near = nose_overlap_near(design_, line, c_r, c_z, R, hint_r);
  const double d = near.rho - c_r, s = std::sqrt(R * R - d * d);
  const double rise = near.slope - d / s;  // h'(ρ)
  if (!std::isfinite(near.height) || !std::isfinite(rise) || !(s > 0)) return false;
  const double margin = std::abs(rise) / m + 1e-9;
  if (!touch_clear_of_creases(design_, near.rho * line.cos, near.rho * line.sin, R, margin))
    return false;
  depth = near.height + rise * rise / (2 * m);
  return true;
}

void ToolChecker::check(const CutterLocation& cl) {
  check(cl, RadialLine(cl.contact.theta));
}

void ToolChecker::check(const CutterLocation& cl, const RadialLine& line) {
  const ToolGeometry& tool = compensation_.tool;
  const auto enabled = [&](ToolCheck c) {
    return options_.policy[static_cast<int>(c)] != CheckPolicy::kOff;
  };
  if (compensation_.b_mode == BMode::kFollow && (cl.b < options_.b_min || cl.b > options_.b_max))
    found(ToolCheck::kBLimits, cl.b < options_.b_min ? options_.b_min - cl.b : cl.b - options_.b_max,
          0.0, cl);
  if (enabled(ToolCheck::kContactAngle)) {
    const double relative = std::abs(cl.psi - cl.b), limit = 0.5 * tool.included_angle;
    if (relative > limit) found(ToolCheck::kContactAngle, relative, limit, cl);
  }
  const ContactPoint& p = cl.contact;
  if (enabled(ToolCheck::kClearance)) {
    // |∂z/∂θ| / r = |∇z · e_θ| = |n · e_θ| / n_z. With the edge h above the spindle line
    // the flank faces the machine's y, which is e_θ turned by C − θ = −asin(h/ρ): there
    // the radial slope counts too.
    const double sin_c = tool.centre_height != 0 ? std::sin(cl.c) : line.sin;
    const double cos_c = tool.centre_height != 0 ? std::cos(cl.c) : line.cos;
    const double n_theta = -p.normal.x() * sin_c + p.normal.y() * cos_c;
    const double slope = std::atan(std::abs(n_theta) / p.normal.z());
    if (slope >= tool.clearance_angle) found(ToolCheck::kClearance, slope, tool.clearance_angle, cl);
  }
  if (enabled(ToolCheck::kLocalGouge) && p.section_curvature * tool.nose_radius > 1.0)
    found(ToolCheck::kLocalGouge, p.section_curvature, 1 / tool.nose_radius, cl);
  if (enabled(ToolCheck::kGlobalGouge)) {
    const double depth = global_gouge_depth(cl, line);
    if (depth > options_.gouge_tolerance)
      found(ToolCheck::kGlobalGouge, depth, options_.gouge_tolerance, cl);
  }
  if (enabled(ToolCheck::kCentre)) {
    // A centre height that keeps the edge from reaching this radius. The nose centre may
    // cross the axis (X through zero): whether the nose then reaches below the design on
    // the other side is the global gouge check's question, in the signed section.
    if (!std::isfinite(cl.x)) found(ToolCheck::kCentre, std::abs(tool.centre_height), 0.0, cl);
  }
}

}  // namespace freeturn
