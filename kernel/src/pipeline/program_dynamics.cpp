#include "program_dynamics.hpp"

#include <cmath>

#include "freeturn/core/number_text.hpp"

namespace freeturn::detail {

ProgramDynamics::ProgramDynamics(const MachineDescription& machine,
                                 const std::vector<std::string>& files)
    : machine_(machine), files_(files), dynamics_(machine.interpolation == Interpolation::kCubic) {
  // Moore's G93 F is the block time in seconds (../notes: the Moore and Precitech dialects);
  // LinuxCNC's is 1/minutes. Another dialect's inverse time is not known here.
  if (machine.plugin == "moore") seconds_per_f_ = 1;
  else if (machine.plugin == "iso") seconds_per_f_ = -60;  // 60 / F
  limit_velocity_.fill(std::numeric_limits<double>::infinity());
  limit_acceleration_.fill(std::numeric_limits<double>::infinity());
  for (const AxisSpec& a : machine.axes) {
    limit_velocity_[static_cast<std::size_t>(a.axis)] = a.max_velocity;
    limit_acceleration_[static_cast<std::size_t>(a.axis)] = a.max_acceleration;
  }
}

std::string ProgramDynamics::where(const Place& p) const {
  return files_[static_cast<std::size_t>(p.file)] + ":" + std::to_string(p.line);
}

void ProgramDynamics::add_excess(Excess& e, double value, double limit, const Place& at) {
  ++e.blocks;
  if (value / limit > e.worst) e.worst = value / limit, e.value = value, e.limit = limit, e.at = at;
}

void ProgramDynamics::judge(const BlockMotion& m, const Place& at) {
  for (std::size_t a = 0; a < 4; ++a) {
    const double v = std::abs(m.velocity[a]), acc = std::abs(m.acceleration[a]);
    peak_velocity_[a] = std::max(peak_velocity_[a], v);
    peak_acceleration_[a] = std::max(peak_acceleration_[a], acc);
    if (v > limit_velocity_[a]) add_excess(velocity_excess_[a], v, limit_velocity_[a], at);
    if (acc > limit_acceleration_[a]) add_excess(acceleration_excess_[a], acc, limit_acceleration_[a], at);
  }
}

void ProgramDynamics::add(const std::array<double, 4>& q, const Feed& feed, const NcBlock& block,
                          const CutterLocation& cl) {
  const Place here{block.file, block.line, cl};
  const std::array<double, 4> from = last_q_;
  const bool placed_before = placed_;  // a block before this one says where it starts
  last_q_ = q;
  placed_ = true;
  if (untimed_) return;
  double time = 0;
  if (feed.rapid || feed.mode != 93) {
    // Not the cut: an approach or a retract. A cut before it ends here, at rest; a cut
    // after it (another pass) starts from rest again.
    if (started_) {
      BlockMotion m;
      if (dynamics_.finish(m)) judge(m, last_);
      if (dynamics_.stop_after_cubic(m)) judge(m, last_);
      dynamics_ = BlockDynamics(machine_.interpolation == Interpolation::kCubic);
      started_ = false;
    }
    return;
  }
  if (seconds_per_f_ == 0) {
    untimed_ = true;
    untimed_at_ = here;
    return;
  }
  if (!(feed.f > 0)) {
    // G93 with no F, F0 or a negative F: no block time at all, which a controller refuses
    // (LinuxCNC stops with an error there). The blocks after it are not judged either.
    untimed_ = no_time_ = true;
    untimed_at_ = here;
    no_time_f_ = feed.f;
    return;
  }
  time = seconds_per_f_ > 0 ? seconds_per_f_ * feed.f : -seconds_per_f_ / feed.f;
  BlockMotion m;
  if (!started_) {
    started_ = judged_ = true;
    if (!placed_before) {
      // The program's first block: where it starts from is not written, so it is the
      // start, at rest.
      dynamics_.add(q, 0.0, m);
      blocks_ = 1;
      last_ = here;
      return;
    }
    // The position the cut starts from, at rest.
    dynamics_.add(from, 0.0, m);
    blocks_ = 1;
  }
  const long k = blocks_++;
  cycle_time_ += time;
  const double rate = 1 / time;
  peak_rate_ = std::max(peak_rate_, rate);
  if (rate > machine_.max_block_rate) add_excess(rate_excess_, rate, machine_.max_block_rate, here);
  if (dynamics_.add(q, time, m)) judge(m, m.block == k ? here : last_);
  last_ = here;
}

void ProgramDynamics::finish(RunReport& report, PassFigures& figures) {
  if (no_time_) {
    ReportWarning w;
    w.kind = "dynamics";
    w.severity = ReportWarning::Severity::kUnsafe;
    w.message =
        "the inverse-time (G93) block at " + where(untimed_at_) + " states " +
        (std::isnan(no_time_f_) ? std::string("no F") : "F" + significant_text(no_time_f_, 6)) +
        ": no block time, which a controller refuses; the axes' velocities and "
        "accelerations from there on are not judged";
    w.count = 1;
    w.theta_deg = part_degrees(untimed_at_.cl.contact.theta);
    w.r_mm = untimed_at_.cl.contact.r;
    w.x_mm = untimed_at_.cl.contact.point.x();
    w.y_mm = untimed_at_.cl.contact.point.y();
    report.warnings.push_back(std::move(w));
    return;
  }
  if (untimed_ || !judged_) {
    ReportWarning w;
    w.kind = "dynamics";
    w.severity = ReportWarning::Severity::kNote;
    w.message = "the axes' velocities and accelerations are not judged: " +
                (untimed_ ? "the block at " + where(untimed_at_) + " states no time"
                          : std::string("no block of the program states a time")) +
                " this reader knows (G93 with F, in Moore's or LinuxCNC's dialect; machine '" +
                machine_.name + "' is posted by '" + machine_.plugin + "')";
    report.warnings.push_back(std::move(w));
    return;
  }
  BlockMotion m;
  if (dynamics_.finish(m)) judge(m, last_);
  if (dynamics_.stop_after_cubic(m)) judge(m, last_);
  figures.cycle_time = cycle_time_;
  for (std::size_t a = 0; a < 4; ++a) {
    figures.dynamics.peak_velocity[a] = peak_velocity_[a];
    figures.dynamics.peak_acceleration[a] = peak_acceleration_[a];
  }
  figures.dynamics.peak_block_rate = peak_rate_;
  figures.dynamics.cycle_time = cycle_time_;
  const auto warn = [&](const Excess& e, const std::string& what, const std::string& unit) {
    if (e.blocks == 0) return;
    ReportWarning w;
    w.kind = "dynamics";
    w.severity = ReportWarning::Severity::kUnsafe;
    w.message = std::to_string(e.blocks) + (e.blocks == 1 ? " block asks " : " blocks ask ") +
                what + " beyond machine '" + machine_.name + "': " + significant_text(e.value, 4) +
                " " + unit + " against " + significant_text(e.limit, 4) + " at " + where(e.at);
    w.count = e.blocks;
    w.theta_deg = part_degrees(e.at.cl.contact.theta);
    w.r_mm = e.at.cl.contact.r;
    w.x_mm = e.at.cl.contact.point.x();
    w.y_mm = e.at.cl.contact.point.y();
    w.value = e.value;
    w.limit = e.limit;
    w.unit = unit;
    report.warnings.push_back(std::move(w));
  };
  for (const AxisSpec& spec : machine_.axes) {
    const auto a = static_cast<std::size_t>(spec.axis);
    const bool angle = spec.axis == Axis::kC || spec.axis == Axis::kB;
    const std::string letter = axis_letter(spec.axis);
    warn(velocity_excess_[a], letter + " velocity", angle ? "deg/s" : "mm/s");
    warn(acceleration_excess_[a], letter + " acceleration", angle ? "deg/s2" : "mm/s2");
  }
  warn(rate_excess_, "a block rate", "blocks/s");
}

}  // namespace freeturn::detail
