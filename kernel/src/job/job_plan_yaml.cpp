#include "job_plan_yaml.hpp"

#include <cmath>
#include <numbers>

namespace freeturn::detail {
namespace {

constexpr double kRadians = std::numbers::pi / 180;

CheckPolicy read_policy(MapReader& map, const std::string& key, CheckPolicy fallback) {
  if (!map.has(key)) return fallback;
  const std::string v = map.text(key);
  if (v == "error") return CheckPolicy::kError;
  if (v == "warning") return CheckPolicy::kWarning;
  if (v == "off") return CheckPolicy::kOff;
  map.fail(key, key + " must be error, warning or off, not '" + v + "'");
}

void read_tool(MapReader& job, JobPlan& plan, const Aperture& aperture) {
  MapReader t(job.child("tool"), job.file(), "tool");
  ToolGeometry& g = plan.tool.tool;
  g.nose_radius = t.positive("nose_radius");
  g.included_angle = t.positive("included_angle_deg", 60.0) * kRadians;
  if (g.included_angle > std::numbers::pi * 1.5)
    t.fail("included_angle_deg", "included_angle_deg must be at most 270");
  g.clearance_angle = t.positive("clearance_angle_deg", 10.0) * kRadians;
  if (t.has("program_point")) {
    const std::string p = t.text("program_point");
    if (p != "centre" && p != "tip") t.fail("program_point", "program_point must be centre or tip");
    g.program_point = p == "tip" ? ProgramPoint::kTip : ProgramPoint::kNoseCentre;
  }
  g.centre_height = t.number("centre_height", 0.0);
  if (const auto w = t.optional_child("waviness")) {
    if (!w->IsSequence()) throw InputError(location_of(*w, job.file()), "tool.waviness must be a list of [angle_deg, error_mm]");
    for (std::size_t i = 0; i < w->size(); ++i) {
      const YAML::Node e = (*w)[i];
      double a, v;
      if (!e.IsSequence() || e.size() != 2 || !YAML::convert<double>::decode(e[0], a) ||
          !YAML::convert<double>::decode(e[1], v) || !std::isfinite(a) || !std::isfinite(v))
        throw InputError(location_of(e, job.file()), "tool.waviness entries are [angle_deg, error_mm]");
      if (!g.waviness.empty() && !(a * kRadians > g.waviness.back().first))
        throw InputError(location_of(e, job.file()), "tool.waviness angles must increase");
      g.waviness.emplace_back(a * kRadians, v);
    }
  }
  plan.checks.outer_radius = aperture.outer_radius;
  if (const auto c = t.optional_child("checks")) {
    MapReader cm(*c, job.file(), "tool.checks");
    static const char* const kKeys[] = {"contact_angle", "clearance", "gouge", "global_gouge", "centre"};
    for (int i = 0; i < 5; ++i) plan.checks.policy[i] = read_policy(cm, kKeys[i], CheckPolicy::kError);
    cm.finish();
  }
  t.finish();
}

void read_points(MapReader& s, CutterPointOptions& p) {
  MapReader pm(s.child("points"), s.file(), "strategy.points");
  int rules = 0;
  if (const auto e = pm.optional_child("equal_angle")) {
    MapReader m(*e, s.file(), "strategy.points.equal_angle");
    p.rule = CutterPointRule::kEqualAngle;
    const double n = m.positive("per_rev");
    if (n != std::floor(n) || n < 3 || n > 1e7) m.fail("per_rev", "per_rev must be an integer from 3 to 10000000");
    p.points_per_revolution = static_cast<int>(n);
    m.finish();
    ++rules;
  }
  if (const auto e = pm.optional_child("equal_arc")) {
    MapReader m(*e, s.file(), "strategy.points.equal_arc");
    p.rule = CutterPointRule::kEqualArcLength;
    p.arc_length = m.positive("length");
    m.finish();
    ++rules;
  }
  if (const auto e = pm.optional_child("chord")) {
    MapReader m(*e, s.file(), "strategy.points.chord");
    p.rule = CutterPointRule::kChordError;
    p.tolerance = m.positive("tolerance");
    p.max_angle_step = m.positive("max_angle_deg", 5.0) * kRadians;
    p.max_radial_step = m.positive("max_radial_step", 0.5);
    m.finish();
    ++rules;
  }
  if (rules != 1) pm.fail("equal_angle", "strategy.points takes exactly one of equal_angle, equal_arc, chord");
  pm.finish();
}

void read_strategy(MapReader& job, JobPlan& plan) {
  MapReader s(job.child("strategy"), job.file(), "strategy");
  Strategy& st = plan.strategy;
  const std::string mode = s.text("mode");
  if (mode != "spiral" && mode != "profile") s.fail("mode", "strategy.mode must be spiral or profile, not '" + mode + "'");
  st.mode = mode == "profile" ? Strategy::Mode::kProfile : Strategy::Mode::kSpiral;
  if (st.mode == Strategy::Mode::kSpiral) {
    const std::string kind = s.text("spiral");
    if (kind != "planar" && kind != "space") s.fail("spiral", "strategy.spiral must be planar or space, not '" + kind + "'");
    st.space = kind == "space";
    st.pitch = s.positive("pitch");
    st.base.kind = st.space ? BaseKind::kLeastSquares : BaseKind::kPlane;
  }
  if (const auto b = s.optional_child("base_surface")) {
    if (!st.space) s.fail("base_surface", "base_surface applies to a space spiral only");
    MapReader bm(*b, job.file(), "strategy.base_surface");
    if (bm.has("fit")) {
      const std::string fit = bm.text("fit");
      if (fit != "least_squares" && fit != "minimax") bm.fail("fit", "fit must be least_squares or minimax");
      st.base.kind = fit == "minimax" ? BaseKind::kMinimax : BaseKind::kLeastSquares;
    }
    if (const auto a = bm.optional_child("search_axis")) {
      bool v = false;
      if (!YAML::convert<bool>::decode(*a, v)) throw InputError(location_of(*a, job.file()), "search_axis must be true or false");
      if (v && st.base.kind != BaseKind::kMinimax) bm.fail("search_axis", "search_axis needs fit: minimax");
      st.base.search_axis = v;
    }
    st.base.angle_limit = bm.positive("max_normal_deviation_deg", 90.0) * kRadians;
    if (bm.has("on_exceed")) {
      const std::string e = bm.text("on_exceed");
      if (e != "error" && e != "warning") bm.fail("on_exceed", "on_exceed must be error or warning");
      st.base.refuse_above_limit = e == "error";
    }
    bm.finish();
  }
  if (s.has("direction")) {
    const std::string d = s.text("direction");
    if (d != "edge_to_centre" && d != "centre_to_edge")
      s.fail("direction", "direction must be edge_to_centre or centre_to_edge");
    st.centre_to_edge = d == "centre_to_edge";
  }
  read_points(s, st.points);
  if (st.mode == Strategy::Mode::kProfile && st.points.rule == CutterPointRule::kEqualAngle)
    s.fail("points", "equal_angle points need a spiral; profile mode takes equal_arc or chord");
  if (s.has("b_axis")) {
    const std::string b = s.text("b_axis");
    if (b != "fixed" && b != "follow") s.fail("b_axis", "b_axis must be fixed or follow");
    st.b_mode = b == "follow" ? BMode::kFollow : BMode::kFixed;
  }
  s.finish();
}

void read_cutting(MapReader& job, JobPlan& plan) {
  MapReader c(job.child("cutting"), job.file(), "cutting");
  Cutting& cut = plan.cutting;
  if (plan.strategy.mode == Strategy::Mode::kSpiral) cut.spindle_rpm = c.positive("spindle_rpm");
  else cut.feed = c.positive("feed");
  if (const auto r = c.optional_child("roughing")) {
    if (!r->IsSequence()) throw InputError(location_of(*r, job.file()), "cutting.roughing must be a list of stock depths (mm)");
    for (std::size_t i = 0; i < r->size(); ++i) {
      double d;
      if (!YAML::convert<double>::decode((*r)[i], d) || !(d > 0) || !std::isfinite(d))
        throw InputError(location_of((*r)[i], job.file()), "cutting.roughing depths must be numbers > 0");
      if (!cut.roughing_depths.empty() && !(d < cut.roughing_depths.back()))
        throw InputError(location_of((*r)[i], job.file()), "cutting.roughing depths must decrease (stock left after each pass)");
      cut.roughing_depths.push_back(d);
    }
  }
  if (const auto e = c.optional_child("enforce_dynamics")) {
    if (!YAML::convert<bool>::decode(*e, cut.enforce_dynamics))
      throw InputError(location_of(*e, job.file()), "enforce_dynamics must be true or false");
  }
  if (c.has("timing")) {
    const std::string t = c.text("timing");
    if (t != "scheduled" && t != "constant_rpm")
      c.fail("timing", "timing must be scheduled or constant_rpm, not '" + t + "'");
    cut.timing = t == "constant_rpm" ? Cutting::Timing::kConstantRpm : Cutting::Timing::kScheduled;
  }
  c.finish();
}

void read_outputs(MapReader& job, JobPlan& plan) {
  const auto o = job.optional_child("outputs");
  if (!o) return;
  MapReader m(*o, job.file(), "outputs");
  const std::pair<const char*, bool*> keys[] = {{"nc", &plan.outputs.nc},
                                                 {"cl_csv", &plan.outputs.cl_csv},
                                                 {"report", &plan.outputs.report},
                                                 {"mesh", &plan.outputs.mesh}};
  for (const auto& [key, value] : keys) {
    if (const auto v = m.optional_child(key)) {
      if (!YAML::convert<bool>::decode(*v, *value))
        throw InputError(location_of(*v, job.file()), std::string("outputs.") + key + " must be true or false");
    }
  }
  m.finish();
}

void read_limits(MapReader& job, JobPlan& plan) {
  const auto l = job.optional_child("limits");
  if (!l) return;
  MapReader m(*l, job.file(), "limits");
  const double points = m.positive("max_points", static_cast<double>(plan.limits.max_points));
  if (points != std::floor(points) || points > 1e15) m.fail("max_points", "limits.max_points must be a whole number of points");
  plan.limits.max_points = static_cast<long long>(points);
  plan.limits.max_file_mb = m.positive("max_file_mb", plan.limits.max_file_mb);
  if (plan.limits.max_file_mb > 1e9) m.fail("max_file_mb", "limits.max_file_mb must be at most 1e9 MB");
  m.finish();
}

}  // namespace

std::optional<JobPlan> read_job_plan(MapReader& job, const Aperture& aperture) {
  const bool any = job.has("tool") || job.has("strategy") || job.has("cutting") || job.has("machine");
  if (!any) {
    if (job.has("outputs")) job.fail("outputs", "outputs need tool, strategy, cutting and machine");
    if (job.has("limits")) job.fail("limits", "limits need tool, strategy, cutting and machine");
    return std::nullopt;
  }
  JobPlan plan;
  read_tool(job, plan, aperture);
  read_strategy(job, plan);
  read_cutting(job, plan);
  plan.machine = job.text("machine");
  read_outputs(job, plan);
  read_limits(job, plan);
  if (plan.strategy.b_mode == BMode::kFollow) plan.tool.b_mode = BMode::kFollow;
  return plan;
}

}  // namespace freeturn::detail
