// report.json (docs/report.schema.json): written with nlohmann-json, whose numbers are the
// shortest text that reads back as the same double, written without the C library (no
// locale reaches them), and whose strings it escapes.
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "report_writers.hpp"

namespace freeturn::detail {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written: a diff reads top down

constexpr int kSchemaVersion = 1;
constexpr double kDegrees = 180 / std::numbers::pi;
constexpr const char* kAxes[4] = {"X", "Z", "C", "B"};

// JSON has no NaN or infinity: what is not a number is null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json warning_json(const ReportWarning& w) {
  Json j;
  j["kind"] = w.kind;
  j["severity"] = to_string(w.severity);
  j["pass"] = w.pass.empty() ? Json(nullptr) : Json(w.pass);
  j["message"] = w.message;
  j["count"] = w.count;
  j["theta_deg"] = number(w.theta_deg);
  j["r_mm"] = number(w.r_mm);
  j["x_mm"] = number(w.x_mm);
  j["y_mm"] = number(w.y_mm);
  j["value"] = number(w.value);
  j["limit"] = number(w.limit);
  j["unit"] = w.unit.empty() ? Json(nullptr) : Json(w.unit);
  return j;
}

// Per axis the machine has: {"X": v, …} in the axis's own unit per second (^2).
Json per_axis(const RunReport& r, const double (&values)[4]) {
  Json j = Json::object();
  for (int a = 0; a < 4; ++a)
    if (r.has_axis[a]) j[kAxes[a]] = number(values[a]);
  return j;
}

Json pass_json(const RunReport& r, const PassFigures& f) {
  Json j;
  j["name"] = f.name;
  j["stock_mm"] = f.stock;
  j["points"] = f.points;
  j["revolutions"] = f.revolutions;
  j["chord_error_nm"] = {{"max", f.chord_max * 1e6}, {"rms", f.chord_rms * 1e6}};
  j["chord_below_design_max_nm"] = f.chord_below_max * 1e6;
  j["scallop_nm"] = {{"max", f.scallop_max * 1e6}, {"rms", f.scallop_rms * 1e6}};
  j["cycle_time_s"] = f.cycle_time;
  j["scheduled"] = f.scheduled;
  j["slowed_blocks"] = f.slowed_blocks;
  j["constant_rpm"] = {{"max_rpm", number(f.dynamics.max_rpm)},
                       {"limited_by", f.dynamics.limiting},
                       {"cycle_time_s", f.constant_rpm_cycle_time}};
  Json uncut;
  uncut["held_points"] = f.held_points;
  uncut["max_nm"] = f.uncut_max * 1e6;
  uncut["at_theta_deg"] = f.held_points > 0 ? number(part_degrees(f.uncut_theta)) : Json(nullptr);
  uncut["at_r_mm"] = f.held_points > 0 ? number(f.uncut_r) : Json(nullptr);
  uncut["band_width_mm"] = f.band_width;
  Json bands = Json::array();
  for (const double b : f.uncut_by_band) bands.push_back(b * 1e6);
  uncut["max_by_band_nm"] = std::move(bands);
  j["uncut_residual"] = std::move(uncut);
  j["peak_velocity_per_s"] = per_axis(r, f.dynamics.peak_velocity);
  j["peak_acceleration_per_s2"] = per_axis(r, f.dynamics.peak_acceleration);
  j["peak_block_rate_per_s"] = f.dynamics.peak_block_rate;
  Json checks = Json::object();
  for (int c = 0; c < kToolCheckCount; ++c) {
    const CheckFinding& k = f.checks.findings[static_cast<std::size_t>(c)];
    checks[tool_check_kind(static_cast<ToolCheck>(c))] = {{"violations", k.count}};
  }
  j["checks"] = std::move(checks);
  return j;
}

Json simulation_json(const RunReport& r) {
  const SimulationResult& s = *r.simulation;
  Json j;
  j["grid"] = {{"source", r.simulated ? "simulation" : "report_grid"},
               {"rings", s.rings},
               {"columns", s.columns},
               {"radial_step_mm", s.radial_step},
               {"cells_not_reached", s.uncut}};
  j["residual_nm"] = {{"pv", s.pv * 1e6}, {"rms", s.rms * 1e6}, {"max", s.max * 1e6},
                      {"min", s.min * 1e6}, {"max_at_r_mm", s.max_r}, {"min_at_r_mm", s.min_r}};
  if (r.form_error) {
    const FormErrorSplit& e = *r.form_error;
    j["figure_nm"] = {{"pv", e.figure_pv * 1e6},
                      {"rms", e.figure_rms * 1e6},
                      {"max", e.figure_max * 1e6},
                      {"min", e.figure_min * 1e6},
                      {"piston", e.piston * 1e6}};
    j["finish_nm"] = {{"pv", e.finish_pv * 1e6}, {"rms", e.finish_rms * 1e6}};
    j["split"] = {{"window_rings", e.window}, {"resolved", e.resolved}};
  }
  const double ratio = s.pv > 0 ? s.predicted.pv() / s.pv : 0.0;
  j["predicted_nm"] = {{"pv", s.predicted.pv() * 1e6},
                       {"max", s.predicted.max() * 1e6},
                       {"min", s.predicted.min() * 1e6},
                       {"max_scallop", s.predicted.max_scallop * 1e6},
                       {"max_uncut", s.predicted.max_uncut * 1e6},
                       {"max_chord_above", s.predicted.max_chord_above * 1e6},
                       {"max_chord_below", s.predicted.max_chord_below * 1e6}};
  j["predicted_over_simulated_pv"] = ratio;
  j["prediction"] = prediction_bound_text(ratio);
  Json worst = Json::array();
  for (const ResidualPlace& p : s.worst)
    worst.push_back({{"r_mm", p.r},
                     {"theta_deg", p.phi * kDegrees},
                     {"residual_nm", p.residual * 1e6},
                     {"cause", to_string(p.cause)}});
  j["worst"] = std::move(worst);
  return j;
}

Json compensation_json(const MeasuredPart& m) {
  const Registration& g = m.registration;
  Json zernike = Json::array();
  for (const double a : g.zernike) zernike.push_back(a * 1e6);
  Json j;
  j["file"] = m.file;
  j["format"] = m.format;
  j["gain"] = m.gain;
  j["points"] = {{"valid", m.points}, {"invalid", m.invalid}, {"used", g.used},
                 {"outliers", g.outliers}, {"outside_aperture", g.outside}};
  j["registration"] = {{"piston_mm", g.piston},          {"tilt_x_rad", g.tilt_x},
                       {"tilt_y_rad", g.tilt_y},         {"decentre_x_mm", g.decentre_x},
                       {"decentre_y_mm", g.decentre_y},  {"clocking_deg", g.clocking * kDegrees},
                       {"iterations", g.iterations}};
  j["fit"] = {{"zernike_terms", static_cast<long>(g.zernike.size())},
              {"normalization_radius_mm", g.normalization_radius},
              {"zernike_nm", std::move(zernike)},
              {"bspline", g.bspline ? Json{{"control_points", g.bspline_control},
                                           {"rms_nm", g.bspline_rms * 1e6}}
                                    : Json(nullptr)},
              {"residual_rms_nm", g.fit_rms * 1e6}};
  j["measured_error_nm"] = {{"rms", g.measured_rms * 1e6}, {"pv", g.measured_pv * 1e6}};
  j["correction_rms_nm"] = m.gain * fitted_error_rms(m) * 1e6;
  j["predicted_after_rms_nm"] = compensated_rms(m) * 1e6;
  return j;
}

}  // namespace

std::string warnings_json(const std::vector<ReportWarning>& warnings) {
  Json list = Json::array();
  for (const ReportWarning& w : warnings) list.push_back(warning_json(w));
  return list.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string report_json(const RunReport& r) {
  Json j;
  j["schema_version"] = kSchemaVersion;
  j["generator"] = {{"name", "freeturn"}, {"version", r.version}};
  j["job"] = {{"name", r.job}, {"file", r.job_file}, {"yaml", r.job_text}};
  const JobParameters& p = r.parameters;
  Json roughing = Json::array();
  for (const double d : p.roughing_depths) roughing.push_back(d);
  j["parameters"] = {{"strategy", p.strategy},
                     {"points", p.points_rule},
                     {"chord_tolerance_nm", p.chord_tolerance > 0 ? Json(p.chord_tolerance * 1e6) : Json(nullptr)},
                     {"stand_off_nm", p.stand_off * 1e6},
                     {"direction", p.direction},
                     {"timing", p.timing},
                     {"pitch_mm", p.pitch},
                     {"inner_radius_mm", p.inner_radius},
                     {"outer_radius_mm", p.outer_radius},
                     {"nose_radius_mm", p.nose_radius},
                     {"included_angle_deg", p.included_angle_deg},
                     {"clearance_angle_deg", p.clearance_angle_deg},
                     {"requested_rpm", r.requested_rpm},
                     {"feed_mm_per_min", p.feed},
                     {"roughing_depths_mm", std::move(roughing)}};
  j["machine"] = {{"name", r.machine},
                  {"post", r.plugin},
                  {"max_velocity_per_s", per_axis(r, r.max_velocity)},
                  {"max_acceleration_per_s2", per_axis(r, r.max_acceleration)}};
  const std::vector<std::string> reasons = r.unsafe_reasons();
  j["verdict"] = {{"status", r.safe() ? "PASS" : "UNSAFE"}, {"reasons", reasons}};
  if (r.alpha_max_deg >= 0) {
    const BaseFigures& b = r.base;
    Json base = {{"kind", b.kind},
                 {"degree", b.degree},
                 {"coefficients", b.coefficients},
                 {"rho_max_mm", b.rho_max},
                 {"alpha_max_deg", r.alpha_max_deg},
                 {"axis_searched", b.axis_searched}};
    if (b.axis_searched)
      base["axis"] = {{"tilt_x_deg", b.tilt_x_deg}, {"tilt_y_deg", b.tilt_y_deg},
                      {"tilt_deg", b.tilt_deg},     {"crossing_x_mm", b.crossing_x},
                      {"crossing_y_mm", b.crossing_y}, {"crossing_z_mm", b.crossing_z}};
    j["base_surface"] = std::move(base);
  } else {
    j["base_surface"] = nullptr;
  }
  j["timing"] = {{"scheduled", r.scheduled},
                 {"spindle_rpm", r.spindle_rpm},
                 {"requested_rpm", r.requested_rpm},
                 {"enforce_dynamics", r.enforce_dynamics}};
  Json warnings = Json::array();
  for (const ReportWarning& w : r.warnings) warnings.push_back(warning_json(w));
  j["warnings"] = std::move(warnings);  // as warnings_json writes them
  Json passes = Json::array();
  for (const PassFigures& f : r.passes) passes.push_back(pass_json(r, f));
  j["passes"] = std::move(passes);
  j["form_error"] = r.simulation ? simulation_json(r) : Json(nullptr);
  Json compensation = Json::array();
  for (const MeasuredPart& m : r.compensation) compensation.push_back(compensation_json(m));
  j["compensation"] = std::move(compensation);
  // A byte that is not UTF-8 (a Latin-1 comment the reader let through) becomes U+FFFD:
  // the file stays valid JSON.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace freeturn::detail
