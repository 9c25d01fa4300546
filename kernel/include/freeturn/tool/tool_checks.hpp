#pragma once
// The checks that keep a diamond whole (paper 002): each finds where (θ, r, x, y) and by
// how much a cutter location breaks a limit, and is an error, a warning or off by
// configuration. The B-axis limit is always an error: B is never clamped.

#include <array>
#include <string>

#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/compensation.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

enum class CheckPolicy { kError, kWarning, kOff };

enum class ToolCheck {
  kContactAngle,  // |ψ − B| ≤ half the included angle
  kClearance,     // tangential slope atan(|∂z/∂θ| / r) < clearance angle
  kLocalGouge,    // concave section curvature κ ≤ 1/R
  kGlobalGouge,   // the nose's edge arc does not cut the radial section anywhere
  kCentre,        // the nose centre does not cross the axis; the centre is reachable
  kBLimits,       // B within the machine's limits (always an error)
};
constexpr int kToolCheckCount = 6;
const char* tool_check_name(ToolCheck check);

struct ToolCheckOptions {
  std::array<CheckPolicy, kToolCheckCount> policy = {CheckPolicy::kError, CheckPolicy::kError,
                                                     CheckPolicy::kError, CheckPolicy::kError,
                                                     CheckPolicy::kError, CheckPolicy::kError};
  double b_min = -3.2, b_max = 3.2;  // rad
  // How deep the section may reach into the nose before it is a gouge (mm).
  double gouge_tolerance = 1e-6;
  // Outside this radius the section is not cut (the global gouge check stops there).
  double outer_radius = 1e300;
  int gouge_samples = 16;  // along the edge arc, per cutter location
};

struct CheckFinding {
  long count = 0;    // cutter locations that broke the limit
  double worst = 0;  // the largest value found (rad, 1/mm or mm, as the check measures)
  double limit = 0;
  double theta = 0, r = 0, x = 0, y = 0;  // where the worst one is
};

struct ToolCheckReport {
  std::array<CheckFinding, kToolCheckCount> findings;
  const CheckFinding& operator[](ToolCheck c) const { return findings[static_cast<int>(c)]; }
  // One line per check that found something ("clearance: 312 points, worst 12.1° > 10°
  // at θ = …").
  std::string summary() const;
  // The line of one check ("clearance: 312 points, worst …"), without the newline.
  std::string line(ToolCheck check) const;
};

// Runs every enabled check on a cutter location. A check whose policy is kError throws
// InputError at the first violation, naming the check, the value, the limit and where;
// kWarning ones are counted in `report`.
class ToolChecker {
 public:
  ToolChecker(const Surface& design, const CompensationOptions& compensation,
              ToolCheckOptions options);
  void check(const CutterLocation& cl);
  // The same, given the radial line at cl.contact.theta (RadialLine of it, the same bits).
  void check(const CutterLocation& cl, const RadialLine& line);
  const ToolCheckReport& report() const { return report_; }

 private:
  void found(ToolCheck check, double value, double limit, const CutterLocation& cl);
  double global_gouge_depth(const CutterLocation& cl, const RadialLine& line) const;
  // The depth where the section under the nose's edge has one maximum, from the contact's
  // search alone (tool_checks.cpp); false where that cannot be shown.
  bool one_touch_depth(const RadialLine& line, double c_r, double c_z, double hint_r,
                       double edge_reach, double& depth) const;

  const Surface& design_;
  CompensationOptions compensation_;
  ToolCheckOptions options_;
  ToolCheckReport report_;
};

}  // namespace freeturn
