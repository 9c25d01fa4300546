#include "freeturn/pipeline/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

constexpr std::size_t kMaxSamples = 4000;  // plot points kept per pass
constexpr double kDegrees = 180 / std::numbers::pi;

// "r = 2.5319 mm, θ = 100.054° (turn 75)": a place on the part, and on the path.
std::string place_text(double theta, double r) {
  return "r = " + fixed_text(r, 4) + " mm, θ = " + fixed_text(part_degrees(theta), 3) + "° (turn " +
         std::to_string(static_cast<long>(std::floor(theta / (2 * std::numbers::pi))) + 1) + ")";
}

}  // namespace


void TurnSamples::add(double theta, double x, double y) {
  if (!any) start_x = x, start_y = y, any = true;
  end_x = x, end_y = y;
  const double turn_angle = 2 * std::numbers::pi;
  const long turn = static_cast<long>(std::floor(theta / turn_angle));
  if (turn % turn_stride != 0) return;
  const long step = static_cast<long>(std::floor((theta - turn * turn_angle) / turn_angle * kTurnPoints));
  // A path may start in any turn, −1 included (a program whose C starts below 0): the
  // first point opens a turn whatever turn_ held.
  if (turn != turn_ || turns.empty()) {
    turns.emplace_back();
    if (static_cast<int>(turns.size()) > kMaxTurns) {
      // Keep every other turn (those a multiple of the doubled stride) and go on.
      turn_stride *= 2;
      std::vector<std::vector<std::pair<float, float>>> kept;
      long k = turn - static_cast<long>(turns.size() - 1) * (turn_stride / 2);
      for (auto& t : turns) {
        if (k % turn_stride == 0) kept.push_back(std::move(t));
        k += turn_stride / 2;
      }
      turns = std::move(kept);
      if (turn % turn_stride != 0) {
        turn_ = turn;
        return;
      }
      if (turns.empty() || !turns.back().empty()) turns.emplace_back();
    }
    turn_ = turn;
    step_ = -1;
  }
  if (step == step_) return;
  step_ = step;
  turns.back().emplace_back(static_cast<float>(x), static_cast<float>(y));
}

void PassFigures::add(const CutterLocation& cl) {
  ++points;
  const std::size_t revolution =
      static_cast<std::size_t>(std::max(0.0, cl.contact.theta / (2 * std::numbers::pi)));
  if (points_per_revolution.size() <= revolution) points_per_revolution.resize(revolution + 1, 0);
  ++points_per_revolution[revolution];
  chord_below_max = std::max(chord_below_max, cl.contact.dip_below_design());
  below_floor_max = std::max(below_floor_max, cl.contact.dip_below(chord_floor));
  if (cl.contact.uncut_residual > 0) {
    ++held_points;
    if (cl.contact.uncut_residual > uncut_max) {
      uncut_max = cl.contact.uncut_residual;
      uncut_theta = cl.contact.theta;
      uncut_r = cl.contact.r;
    }
    if (band_width > 0) {
      const std::size_t band = static_cast<std::size_t>(std::max(0.0, cl.contact.r / band_width));
      if (band < 4096) {
        if (uncut_by_band.size() <= band) uncut_by_band.resize(band + 1, 0.0);
        uncut_by_band[band] = std::max(uncut_by_band[band], cl.contact.uncut_residual);
      }
    }
  }
  turns.add(cl.contact.theta, cl.contact.point.x(), cl.contact.point.y());
  const double e = cl.contact.chord_error, s = cl.contact.scallop;
  chord_max = std::max(chord_max, e);
  scallop_max = std::max(scallop_max, s);
  chord_sq_ += e * e;
  scallop_sq_ += s * s;
  if ((points - 1) % stride == 0) {
    samples.push_back({cl.contact.point.x(), cl.contact.point.y(), cl.contact.point.z(),
                       cl.contact.r, cl.contact.theta, e, s});
    if (samples.size() >= kMaxSamples) {
      // Keep every other sample and halve the rate: memory stays bounded.
      std::size_t j = 0;
      for (std::size_t i = 0; i < samples.size(); i += 2) samples[j++] = samples[i];
      samples.resize(j);
      stride *= 2;
    }
  }
}

void PassFigures::keep_block(long index, const BlockPoint& b) {
  if (index % block_stride != 0) return;
  blocks.push_back(b);
  if (blocks.size() >= kMaxSamples) {
    std::size_t j = 0;
    for (std::size_t i = 0; i < blocks.size(); i += 2) blocks[j++] = blocks[i];
    blocks.resize(j);
    block_stride *= 2;
  }
}

void PassFigures::add_block(const AxisRecord& record, const AxisSpec& x_spec, bool c_wrapped,
                            bool cubic) {
  const long k = written_++;
  if (k > 0 && !(record.time > 0)) return;  // a block with no time
  cubic_blocks = cubic;
  const double r = std::abs((record.x - x_spec.offset) / x_spec.sign);
  if (k == 0) {
    block_dynamics_ = BlockDynamics(cubic);
    c_unwrapped_ = record.c;
  } else {
    c_unwrapped_ += c_wrapped ? std::remainder(record.c - last_c_, 360.0) : record.c - last_c_;
  }
  last_c_ = record.c;
  const long index = positions_++;  // the position's index in block_dynamics_
  BlockMotion m;
  if (block_dynamics_.add({record.x, record.z, c_unwrapped_, 0.0}, k == 0 ? 0.0 : record.time, m))
    draw_block(m, m.block == index ? r : last_r_);
  last_r_ = r;
}

void PassFigures::draw_block(const BlockMotion& m, double r) {
  BlockPoint b;
  b.r = r;
  for (std::size_t a = 0; a < 3; ++a) b.v[a] = m.velocity[a], b.a[a] = m.acceleration[a];
  keep_block(m.block - 1, b);
}

void PassFigures::finish(const PathSummary& s, const DynamicsReport& d, const ToolCheckReport& c) {
  BlockMotion last;  // a PVT program's last block (the charts draw blocks, not the stop)
  if (block_dynamics_.finish(last) && !last.stop) draw_block(last, last_r_);
  revolutions = s.theta_end / (2 * std::numbers::pi);
  chord_rms = points > 0 ? std::sqrt(chord_sq_ / static_cast<double>(points)) : 0.0;
  scallop_rms = points > 0 ? std::sqrt(scallop_sq_ / static_cast<double>(points)) : 0.0;
  dynamics = d;
  cycle_time = d.cycle_time;
  constant_rpm_cycle_time =
      d.max_rpm > 0 && std::isfinite(d.max_rpm) ? 60 * d.turns / d.max_rpm : 0.0;
  checks = c;
  // A check that found something was downgraded to a warning by the job (an error would
  // have stopped the run): the program is unsafe all the same.
  for (int i = 0; i < kToolCheckCount; ++i) {
    const CheckFinding& f = c.findings[static_cast<std::size_t>(i)];
    if (f.count == 0) continue;
    const ToolCheck check = static_cast<ToolCheck>(i);
    ReportWarning w;
    w.kind = tool_check_kind(check);
    w.severity = ReportWarning::Severity::kUnsafe;
    w.pass = name;
    w.message = c.line(check) + " (the check is downgraded to a warning in the job)";
    w.count = f.count;
    w.theta_deg = part_degrees(f.theta);
    w.r_mm = f.r;
    w.x_mm = f.x;
    w.y_mm = f.y;
    switch (check) {
      case ToolCheck::kContactAngle:
      case ToolCheck::kClearance:
      case ToolCheck::kBLimits:
        w.value = f.worst * kDegrees, w.limit = f.limit * kDegrees, w.unit = "deg";
        break;
      case ToolCheck::kLocalGouge:  // curvatures, reported as the radii a user compares
        w.value = 1 / f.worst, w.limit = 1 / f.limit, w.unit = "mm";
        break;
      default:
        w.value = f.worst * 1e6, w.limit = f.limit * 1e6, w.unit = "nm";
    }
    findings.push_back(std::move(w));
  }
  if (s.jumps > 0) {
    ReportWarning w;
    w.kind = "nose_jump";
    w.severity = ReportWarning::Severity::kUnsafe;
    w.pass = name;
    w.message = std::to_string(s.jumps) +
                " segments where the nose centre jumps (a crease sharper than the nose), the "
                "first at " +
                place_text(s.first_jump_theta, s.first_jump_r) +
                ": the chord tolerance cannot hold there; worst " +
                fixed_text(s.max_jump_error * 1e6, 1) + " nm";
    w.count = s.jumps;
    w.theta_deg = part_degrees(s.first_jump_theta);
    w.x_mm = s.first_jump_r * std::cos(s.first_jump_theta);
    w.y_mm = s.first_jump_r * std::sin(s.first_jump_theta);
    w.r_mm = s.first_jump_r;
    w.value = s.max_jump_error * 1e6;
    w.unit = "nm";
    findings.push_back(std::move(w));
  }
  if (held_points > 0) {
    ReportWarning w;
    w.kind = "uncut_residual";
    w.severity = ReportWarning::Severity::kWarning;
    w.pass = name;
    w.message =
        std::to_string(held_points) +
        " cutter locations hold the nose at a crease or a trough it cannot reach into: up to " +
        fixed_text(uncut_max * 1e6, 1) + " nm of material is left there, the most at " +
        place_text(uncut_theta, uncut_r) +
        " (the design is unreachable there; the program does not gouge)";
    w.count = held_points;
    w.theta_deg = part_degrees(uncut_theta);
    w.r_mm = uncut_r;
    w.x_mm = uncut_r * std::cos(uncut_theta);
    w.y_mm = uncut_r * std::sin(uncut_theta);
    w.value = uncut_max * 1e6;
    w.unit = "nm";
    findings.push_back(std::move(w));
  }
}

void PassFigures::take_schedule(const ScheduleReport& s) {
  scheduled = true;
  cycle_time = s.cycle_time;
  slowed_blocks = s.slowed_blocks;
  for (int a = 0; a < 4; ++a) {
    dynamics.peak_velocity[a] = s.peak_velocity[a];
    dynamics.peak_acceleration[a] = s.peak_acceleration[a];
  }
  dynamics.peak_block_rate = s.peak_block_rate;
  dynamics.cycle_time = s.cycle_time;
}

double zernike_rms(const std::vector<double>& a) {
  double sq = 0;
  for (std::size_t j = 1; j < a.size(); ++j) sq += a[j] * a[j];
  return std::sqrt(sq);
}

double fitted_error_rms(const MeasuredPart& part) {
  return std::hypot(zernike_rms(part.registration.zernike), part.registration.bspline_rms);
}

double compensated_rms(const MeasuredPart& part) {
  const double kept = (1 - part.gain) * fitted_error_rms(part);
  return std::hypot(kept, part.registration.fit_rms);
}

const char* tool_check_kind(ToolCheck check) {
  static constexpr const char* kKinds[kToolCheckCount] = {
      "contact_angle", "clearance", "local_gouge", "global_gouge", "centre", "b_limits"};
  return kKinds[static_cast<int>(check)];
}

double part_degrees(double theta) {
  const double d = std::fmod(theta * kDegrees, 360.0);
  return d < 0 ? d + 360 : d;
}

const char* to_string(ReportWarning::Severity severity) {
  switch (severity) {
    case ReportWarning::Severity::kNote: return "note";
    case ReportWarning::Severity::kWarning: return "warning";
    case ReportWarning::Severity::kUnsafe: return "unsafe";
  }
  return "?";
}

std::string warning_line(const ReportWarning& w) {
  return w.pass.empty() ? w.message : w.pass + ": " + w.message;
}

bool RunReport::safe() const {
  return std::none_of(warnings.begin(), warnings.end(), [](const ReportWarning& w) {
    return w.severity == ReportWarning::Severity::kUnsafe;
  });
}

std::vector<std::string> RunReport::unsafe_reasons() const {
  std::vector<std::string> lines;
  for (const ReportWarning& w : warnings)
    if (w.severity == ReportWarning::Severity::kUnsafe) lines.push_back(warning_line(w));
  return lines;
}

std::vector<std::string> RunReport::messages() const {
  std::vector<std::string> lines;
  for (const ReportWarning& w : warnings) lines.push_back(warning_line(w));
  return lines;
}

void judge_simulated_cut(RunReport& r) {
  // Only a simulation the user asked for: the report's own grid is there for its maps, and
  // runs that write no report have none, so a verdict that read it would depend on the
  // outputs chosen.
  if (!r.simulation || !r.simulated) return;
  const SimulationResult& cut = *r.simulation;
  if (!(cut.min < -kChordDipAllowed)) return;
  ReportWarning w;
  w.kind = "simulated_gouge";
  w.severity = ReportWarning::Severity::kUnsafe;
  w.r_mm = cut.min_r;
  w.theta_deg = part_degrees(cut.min_phi);
  w.x_mm = cut.min_r * std::cos(cut.min_phi);
  w.y_mm = cut.min_r * std::sin(cut.min_phi);
  w.message = "the simulated cut goes " + fixed_text(-cut.min * 1e6, 1) +
              " nm below the design (the most allowed is " + fixed_text(kChordDipAllowed * 1e6, 1) +
              " nm) at r = " + fixed_text(cut.min_r, 4) + " mm, θ = " + fixed_text(w.theta_deg, 2) +
              "°";
  w.value = -cut.min * 1e6;
  w.limit = kChordDipAllowed * 1e6;
  w.unit = "nm";
  r.warnings.push_back(std::move(w));
}

void judge(RunReport& r) {
  // The cut simulated from the program's own blocks (when asked for) is a second witness
  // beside the planner's figures: a nose it finds below the design is a gouge whatever they
  // say (a chord measure that fell short once let 45 nm through under a PASS).
  judge_simulated_cut(r);
  for (const PassFigures& f : r.passes) {
    // The motion between blocks cuts into the design (blocks on the design, chords below
    // them): more than 10 nm is a gouge.
    if (f.chord_below_max > kChordDipAllowed) {
      ReportWarning w;
      w.kind = "chord_below";
      w.severity = ReportWarning::Severity::kUnsafe;
      w.pass = f.name;
      // Under the chord rule the blocks stand off the design and no measured chord dips
      // below it: what does is a jump the chord rule could not hold (reported beside this).
      w.message = "the motion between blocks cuts up to " + fixed_text(f.chord_below_max * 1e6, 1) +
                  " nm into the design" +
                  (r.parameters.chord_tolerance > 0
                       ? std::string(" where the nose centre jumps across a crease the planner "
                                     "does not roll over or hold at (a creased surface decentred "
                                     "or tilted is not searched for its creases)")
                       : std::string(" (equal-angle or equal-arc blocks stand off the design by "
                                     "the dip measured before, and two runs raised it short of "
                                     "this one; use points: chord)"));
      w.value = f.chord_below_max * 1e6;
      w.limit = kChordDipAllowed * 1e6;
      w.unit = "nm";
      r.warnings.push_back(std::move(w));
    }
    // Written with enforce_dynamics: false at a speed (a spiral's rpm, a PVT profile's feed)
    // over the highest the blocks allow.
    const auto over_the_limits = [&](double at, double highest, const std::string& unit,
                                     const std::string& what, const std::string& set_by) {
      ReportWarning w;
      w.kind = "dynamics";
      w.severity = ReportWarning::Severity::kUnsafe;
      w.pass = f.name;
      w.message = "at " + significant_text(at, 6) + " " + unit +
                  " the program exceeds the machine's limits (enforce_dynamics: false): the "
                  "highest feasible " +
                  what + " is " + significant_text(highest, 6) + " " + unit + ", set by " + set_by;
      w.value = at;
      w.limit = highest;
      w.unit = unit;
      r.warnings.push_back(std::move(w));
    };
    if (!f.scheduled && r.spindle_rpm > 0 && f.dynamics.max_rpm < r.spindle_rpm * (1 - 1e-12)) {
      over_the_limits(r.spindle_rpm, f.dynamics.max_rpm, "rpm", "constant speed",
                      f.dynamics.limiting);
    } else if (!f.scheduled && r.spindle_rpm > 0 && r.spindle_rpm < r.requested_rpm * (1 - 1e-9)) {
      ReportWarning w;
      w.kind = "spindle_speed";
      w.severity = ReportWarning::Severity::kWarning;
      w.pass = f.name;
      w.message =
          "the machine's limits allow at most " + significant_text(r.spindle_rpm, 4) +
          " rpm at one constant speed (set by " + f.dynamics.limiting + "), not the requested " +
          significant_text(r.requested_rpm, 4) + " rpm: the program runs at " +
          significant_text(r.spindle_rpm, 4) + " rpm" +
          (r.could_schedule ? std::string(" (with cutting.timing: scheduled it would run at ") +
                                  significant_text(r.requested_rpm, 4) +
                                  " rpm, slowing only the blocks that need it)"
                            : std::string());
      w.value = r.spindle_rpm;
      w.limit = r.requested_rpm;
      w.unit = "rpm";
      r.warnings.push_back(std::move(w));
    }
    if (r.spindle_rpm == 0 && r.parameters.feed > 0 &&
        f.dynamics.max_feed < r.parameters.feed * (1 - 1e-12))
      over_the_limits(r.parameters.feed, f.dynamics.max_feed, "mm/min", "feed",
                      f.dynamics.feed_limiting);
    if (f.scheduled && f.slowed_blocks > 0) {
      ReportWarning w;
      w.kind = "slowed_blocks";
      w.severity = ReportWarning::Severity::kNote;
      w.pass = f.name;
      w.message = std::to_string(f.slowed_blocks) + " of " + std::to_string(f.points) +
                  " blocks run slower than the requested " + significant_text(r.requested_rpm, 4) +
                  " rpm, where the machine's axis limits demand it";
      w.count = f.slowed_blocks;
      r.warnings.push_back(std::move(w));
    }
  }
}

}  // namespace freeturn
