#include "job_plan_yaml.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "freeturn/core/number_text.hpp"
#include "freeturn/tool/compensation.hpp"

namespace freeturn::detail {
namespace {

constexpr double kRadians = std::numbers::pi / 180;

CheckPolicy read_policy(MapReader& map, const std::string& key, CheckPolicy fallback) {
  if (!map.has(key)) return fallback;
  const std::string v = map.text(key);
  if (v == "error") return CheckPolicy::kError;
  if (v == "warning") return CheckPolicy::kWarning;
  // A check the job switches off still runs, and what it finds marks the program UNSAFE,
  // as a downgraded one does: a job cannot turn a finding into a PASS. Until December 2026
  // "off" skipped it, and microlens domes whose flanks rose 40.6° under a 40° clearance
  // were written under a PASS with `clearance: off`.
  if (v == "off") return CheckPolicy::kWarning;
  map.fail(key, key + " must be error, warning or off, not '" + v + "'");
}

void read_tool(MapReader& job, JobPlan& plan, const Aperture& aperture) {
  MapReader t(job.child("tool"), job.file(), "tool");
  ToolGeometry& g = plan.tool.tool;
  // Diamond turning noses run from a few µm to a few mm.
  g.nose_radius = t.in_range("nose_radius", 0, 100, true, " mm");
  g.included_angle = t.in_range("included_angle_deg", 60.0, 0, 270, true, "°") * kRadians;
  // Below the edge the flank clears the cut surface by this angle; past 45° no insert
  // is ground, and past 90° the "clearance" would face into the part.
  g.clearance_angle = t.in_range("clearance_angle_deg", 10.0, 0, 45, true, "°") * kRadians;
  if (t.has("program_point")) {
    const std::string p = t.text("program_point");
    if (p != "centre" && p != "tip") t.fail("program_point", "program_point must be centre or tip");
    g.program_point = p == "tip" ? ProgramPoint::kTip : ProgramPoint::kNoseCentre;
  }
  // The edge's height off the spindle axis: micrometres in practice, never the part's size.
  g.centre_height = t.in_range("centre_height", 0.0, -0.5 * aperture.outer_radius,
                               0.5 * aperture.outer_radius, false, " mm");
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
      if (!(std::abs(a) <= 180))
        throw InputError(location_of(e[0], job.file()), "tool.waviness angles must be within [-180, 180]°");
      // A form error of the edge, a fraction of the nose: one as large as the nose is a
      // different tool (or millimetres typed for micrometres).
      if (!(std::abs(v) < 0.1 * g.nose_radius))
        throw InputError(location_of(e[1], job.file()),
                         "tool.waviness error " + e[1].Scalar() +
                             " mm must be smaller than a tenth of the nose radius " +
                             t.node()["nose_radius"].Scalar() + " mm");
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

// The fewest points a pass can have over the aperture, and the key whose step sets it:
// the spiral's length over the plane, π(R_o² − R_i²)/pitch (a surface's slope only
// lengthens it), over the arc step; its turns times the points per turn (the angle cap
// bounds the chord rule's); a profile's radial length over its step.
struct StepEstimate {
  double per_pass = 0;
  SourceLocation place;
  std::string key;
  double turns = 0;  // a spiral's revolutions: over the limit at 3 points each, the pitch's typo
  SourceLocation pitch_place;
};

void read_points(MapReader& s, JobPlan& plan, const Aperture& aperture, StepEstimate& estimate) {
  CutterPointOptions& p = plan.strategy.points;
  const bool spiral = plan.strategy.mode == Strategy::Mode::kSpiral;
  const double ro = aperture.outer_radius, ri = aperture.inner_radius;
  const double turns = spiral ? (ro - ri) / plan.strategy.pitch : 0.0;
  MapReader pm(s.child("points"), s.file(), "strategy.points");
  int rules = 0;
  if (const auto e = pm.optional_child("equal_angle")) {
    MapReader m(*e, s.file(), "strategy.points.equal_angle");
    p.rule = CutterPointRule::kEqualAngle;
    const double n = m.positive("per_rev");
    if (n != std::floor(n) || n < 3 || n > 1e7) m.fail("per_rev", "per_rev must be an integer from 3 to 10000000");
    p.points_per_revolution = static_cast<int>(n);
    estimate.per_pass = turns * n;
    estimate.place = location_of(m.node()["per_rev"], s.file());
    estimate.key = "equal_angle.per_rev";
    m.finish();
    ++rules;
  }
  if (const auto e = pm.optional_child("equal_arc")) {
    MapReader m(*e, s.file(), "strategy.points.equal_arc");
    p.rule = CutterPointRule::kEqualArcLength;
    // From 10 nm (far below any chord tolerance) to 10 mm.
    p.arc_length = m.in_range("length", 1e-5, 10, false, " mm");
    const double length = spiral ? std::numbers::pi * (ro * ro - ri * ri) / plan.strategy.pitch : ro - ri;
    estimate.per_pass = length / p.arc_length;
    estimate.place = location_of(m.node()["length"], s.file());
    estimate.key = "equal_arc.length";
    m.finish();
    ++rules;
  }
  if (const auto e = pm.optional_child("chord")) {
    MapReader m(*e, s.file(), "strategy.points.chord");
    p.rule = CutterPointRule::kChordError;
    // 0.1 nm is below any machine's resolution; 0.1 mm is no finishing cut.
    p.tolerance = m.in_range("tolerance", 1e-7, 0.1, false, " mm");
    p.max_angle_step = m.in_range("max_angle_deg", 5.0, 0.001, 90, false, "°") * kRadians;
    p.max_radial_step = m.in_range("max_radial_step", 0.5, 1e-5, 100, false, " mm");
    const std::string cap = spiral ? "max_angle_deg" : "max_radial_step";
    estimate.per_pass = spiral ? turns * std::ceil(2 * std::numbers::pi / p.max_angle_step)
                               : (ro - ri) / p.max_radial_step;
    estimate.place = location_of(m.has(cap) ? m.node()[cap] : m.node(), s.file());
    estimate.key = "chord." + cap;
    m.finish();
    ++rules;
  }
  if (rules != 1) pm.fail("equal_angle", "strategy.points takes exactly one of equal_angle, equal_arc, chord");
  pm.finish();
  if (spiral) {
    estimate.turns = turns;
    estimate.pitch_place = location_of(s.node()["pitch"], s.file());
  }
}

void read_strategy(MapReader& job, JobPlan& plan, const Aperture& aperture,
                   StepEstimate& estimate) {
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
    // Passes a nose diameter apart do not overlap: a ridge stands between every two.
    if (!(st.pitch < 2 * plan.tool.tool.nose_radius))
      s.fail("pitch", "strategy.pitch " + s.node()["pitch"].Scalar() +
                          " mm is not below the nose diameter (2 × " +
                          shortest_text(plan.tool.tool.nose_radius) +
                          " mm): the passes would not overlap");
    // A spiral crosses the aperture's ring in (outer − inner) / pitch revolutions: under
    // one, it cuts an arc of the ring and leaves the rest as it was (a 10 nm ring at a
    // 0.05 mm pitch planned 2 points, 0.0002 of a revolution, and passed).
    const double width = aperture.outer_radius - aperture.inner_radius;
    if (!(st.pitch <= width))
      s.fail("pitch", "strategy.pitch " + s.node()["pitch"].Scalar() +
                          " mm is wider than the aperture's ring (" + significant_text(width, 6) +
                          " mm from r = " + significant_text(aperture.inner_radius, 9) + " to " +
                          significant_text(aperture.outer_radius, 9) +
                          " mm): the spiral would turn " + significant_text(width / st.pitch, 3) +
                          " of a revolution and leave the rest of the ring uncut");
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
    st.base.angle_limit = bm.in_range("max_normal_deviation_deg", 90.0, 0, 90, true, "°") * kRadians;
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
  read_points(s, plan, aperture, estimate);
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
  // Ultraprecision spindles turn up to about 10 000 rpm; slide feeds stay under 10 m/min.
  // Below, a thousandth (a turn in 17 hours, a micrometre a minute) is a typo, and it is
  // what the posts' three decimals can still say: less would print S0.000 or F0.000.
  if (plan.strategy.mode == Strategy::Mode::kSpiral)
    cut.spindle_rpm = c.in_range("spindle_rpm", 0.001, 20000, false, " rpm");
  else
    cut.feed = c.in_range("feed", 0.001, 10000, false, " mm/min");
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

std::optional<JobPlan> read_job_plan(MapReader& job, const Aperture& aperture,
                                     const Surface& design) {
  const bool any = job.has("tool") || job.has("strategy") || job.has("cutting") || job.has("machine");
  if (!any) {
    if (job.has("outputs")) job.fail("outputs", "outputs need tool, strategy, cutting and machine");
    if (job.has("limits")) job.fail("limits", "limits need tool, strategy, cutting and machine");
    return std::nullopt;
  }
  JobPlan plan;
  StepEstimate estimate;
  read_tool(job, plan, aperture);
  read_strategy(job, plan, aperture, estimate);
  // The chord rule keeps the round nose at least as far above the design as the real edge
  // may reach past it (stand_off_for): a wavy edge's span on a creased design, less on a
  // smooth one unless the nose nearly fits a concave section, and what the edge's centre
  // height moves a held nose's second touch. A reach near the tolerance leaves the chords
  // no band.
  ToolMotion motion = tool_motion(plan.tool);
  measure_edge_reach(motion, design, aperture.inner_radius, aperture.outer_radius);
  const double span = edge_reach(motion, design);
  const CutterPointOptions& points = plan.strategy.points;
  if (points.rule == CutterPointRule::kChordError && plan.tool.tool.nose_radius > 0 &&
      !(span <= 0.9 * points.tolerance)) {
    const bool height = motion.centre_height_reach > span - motion.centre_height_reach;
    const std::string what =
        height ? "tool.centre_height lets the edge, which lies in the rake plane h above the "
                 "spindle line, reach "
               : "tool.waviness lets the edge reach ";
    const std::string why =
        height ? " nm: where the nose is held at a crease it touches a second flank across "
                 "the radial plane the chords are measured in, turned and tilted there by "
                 "about h/ρ, and the chords keep it above the design only within a band of "
                 "ε minus that; give a chord tolerance above "
               : " nm: compensated at each contact's angle, the edge at another angle "
                 "(the far flank of a crease the nose is held at, or the rest of a nose "
                 "that nearly fits a concave section) reaches that far past the round "
                 "nose, and the chords keep it above the design only within a band of "
                 "ε minus that; give a chord tolerance above ";
    throw InputError(
        location_of(job.node()["tool"][height ? "centre_height" : "waviness"], job.file()),
        what + significant_text(span * 1e6, 4) +
            " nm past the round nose, more than 0.9 × the chord tolerance " +
            significant_text(points.tolerance * 1e6, 4) + why +
            significant_text(span / 0.9 * 1e6, 4) + " nm" +
            (height ? ", or measure the centre height smaller" : ""));
  }
  read_cutting(job, plan);
  plan.machine = job.text("machine");
  read_outputs(job, plan);
  read_limits(job, plan);
  // Before any work: a typo in a step or pitch is refused at once, at its key, rather
  // than after minutes of planning (the planner stops at the limit too).
  const double passes = static_cast<double>(plan.cutting.roughing_depths.size() + 1);
  if (3 * estimate.turns * passes > static_cast<double>(plan.limits.max_points))
    throw InputError(estimate.pitch_place,
                     "strategy.pitch makes " + significant_text(estimate.turns, 6) +
                         " revolutions, which at 3 points each (" + fixed_text(passes, 0) +
                         " passes) is over limits.max_points (" +
                         std::to_string(plan.limits.max_points) + "): a typo in the pitch?");
  if (estimate.per_pass * passes > static_cast<double>(plan.limits.max_points)) {
    const double points = std::ceil(estimate.per_pass * passes);
    throw InputError(estimate.place, "strategy.points." + estimate.key + " asks for at least " +
                                         significant_text(points, 15) + " points (" +
                                         fixed_text(passes, 0) + " passes), over limits.max_points (" +
                                         std::to_string(plan.limits.max_points) +
                                         "): a typo in a step or the pitch?");
  }
  // The CL file holds every point of the finishing pass, 16 numbers a row: at least 64
  // bytes each (most rows take 250). Over limits.max_file_mb it is refused now, not
  // after minutes of planning.
  const double cl_bytes = 64 * estimate.per_pass;
  if (plan.outputs.cl_csv && cl_bytes > plan.limits.max_file_mb * 1048576.0) {
    throw InputError(estimate.place,
                     "strategy.points." + estimate.key + " asks for at least " +
                         significant_text(std::ceil(estimate.per_pass), 15) +
                         " points, a CL file of at least " + significant_text(cl_bytes / 1048576.0, 3) +
                         " MB, over limits.max_file_mb (" + significant_text(plan.limits.max_file_mb, 6) +
                         " MB)");
  }
  if (plan.strategy.b_mode == BMode::kFollow) plan.tool.b_mode = BMode::kFollow;
  plan.estimate = {estimate.per_pass, "strategy.points." + estimate.key};
  return plan;
}

}  // namespace freeturn::detail
