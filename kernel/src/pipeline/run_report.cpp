#include "freeturn/pipeline/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

constexpr std::size_t kMaxSamples = 4000;  // plot points kept per pass

}  // namespace


void PassFigures::add(const CutterLocation& cl, const AxisRecord& record,
                      const AxisRecord& previous) {
  ++points;
  const std::size_t revolution =
      static_cast<std::size_t>(std::max(0.0, cl.contact.theta / (2 * std::numbers::pi)));
  if (points_per_revolution.size() <= revolution) points_per_revolution.resize(revolution + 1, 0);
  ++points_per_revolution[revolution];
  const double rate = record.time > 0 ? 1 / record.time : 0;
  // C velocity from the unwrapped step (a wrapped C jumps by 360° once a turn).
  const double dc = std::remainder(record.c - previous.c, 360.0);
  if (cl.contact.chord_below) chord_below_max = std::max(chord_below_max, cl.contact.chord_error);
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
  const double e = cl.contact.chord_error, s = cl.contact.scallop;
  chord_max = std::max(chord_max, e);
  scallop_max = std::max(scallop_max, s);
  chord_sq_ += e * e;
  scallop_sq_ += s * s;
  if ((points - 1) % stride == 0) {
    samples.push_back({cl.contact.point.x(), cl.contact.point.y(), cl.contact.point.z(),
                       cl.contact.r, e, (record.x - previous.x) * rate,
                       (record.z - previous.z) * rate, dc * rate});
    if (samples.size() >= kMaxSamples) {
      // Keep every other sample and halve the rate: memory stays bounded.
      std::size_t j = 0;
      for (std::size_t i = 0; i < samples.size(); i += 2) samples[j++] = samples[i];
      samples.resize(j);
      stride *= 2;
    }
  }
}

void PassFigures::finish(const PathSummary& s, const DynamicsReport& d, const ToolCheckReport& c) {
  revolutions = s.theta_end / (2 * std::numbers::pi);
  chord_rms = points > 0 ? std::sqrt(chord_sq_ / static_cast<double>(points)) : 0.0;
  scallop_rms = points > 0 ? std::sqrt(scallop_sq_ / static_cast<double>(points)) : 0.0;
  dynamics = d;
  cycle_time = d.cycle_time;
  constant_rpm_cycle_time =
      d.max_rpm > 0 && std::isfinite(d.max_rpm) ? 60 * d.turns / d.max_rpm : 0.0;
  checks = c;
  const std::string summary = c.summary();
  std::size_t start = 0;
  while (start < summary.size()) {
    const std::size_t end = summary.find('\n', start);
    check_warnings.push_back(summary.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (s.jumps > 0) {
    std::string w = std::to_string(s.jumps);
    w +=
        " segments where the nose centre jumps (a crease sharper than the nose), the first at θ = ";
    w += significant_text(s.first_jump_theta * 180 / std::numbers::pi, 9);
    w += "°, r = ";
    w += significant_text(s.first_jump_r, 9);
    w += " mm: the chord tolerance cannot hold there; worst ";
    w += significant_text(s.max_jump_error * 1e6, 9);
    w += " nm";
    check_warnings.push_back(w);
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

void judge(RunReport& r) {
  r.unsafe.clear();
  for (const PassFigures& f : r.passes) {
    // Every check that found something was downgraded (an error would have stopped the run).
    for (const std::string& w : f.check_warnings) r.unsafe.push_back(f.name + ": " + w);
    // The motion between blocks cuts into the design (blocks on the design, chords below
    // them): more than 10 nm is a gouge.
    if (f.chord_below_max > 1e-5)
      r.unsafe.push_back(f.name + ": the motion between blocks cuts up to " +
                         significant_text(f.chord_below_max * 1e6, 9) +
                         " nm into the design (equal-angle or equal-arc points sit on the "
                         "design and their chords dip below it; use points: chord)");
    if (!f.scheduled && r.spindle_rpm > 0 && f.dynamics.max_rpm < r.spindle_rpm * (1 - 1e-12))
      r.unsafe.push_back(f.name + ": at " + significant_text(r.spindle_rpm, 9) +
                         " rpm the program exceeds the machine's limits (enforce_dynamics: "
                         "false): the highest feasible constant speed is " +
                         significant_text(f.dynamics.max_rpm, 9) + " rpm, set by " + f.dynamics.limiting);
  }
}

}  // namespace freeturn
