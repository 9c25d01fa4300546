#include "freeturn/machine/axis_mapper.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

constexpr double kDegrees = 180 / std::numbers::pi;

std::string where(double theta, double r) {
  return "θ = " + fixed_text(theta, 6) + " rad (" + fixed_text(theta * kDegrees, 4) +
         "°), r = " + fixed_text(r, 6) + " mm";
}

std::string where(const CutterLocation& cl) {
  return where(cl.contact.theta, cl.contact.r);
}

// A limit crossed is reported where the machine file states it, then the bound and the
// place on the path: "m.yaml:5:33: machine axis X max 3: θ = …, r = …".
std::string at_bound(const SourceLocation& place, const std::string& bound, const CutterLocation& cl) {
  const std::string file_place = place.to_string();
  return (file_place.empty() ? "" : file_place + ": ") + bound + ": " + where(cl);
}

std::string number(double v) {
  return significant_text(v, 6);
}

}  // namespace

AxisMapper::AxisMapper(const MachineDescription& machine, const MotionOptions& motion,
                       AxisSink& out)
    : machine_(machine),
      motion_(motion),
      out_(out),
      dynamics_(machine.interpolation == Interpolation::kCubic),
      word_scale_(machine.word_scales()) {
  report_.max_rpm = motion.spindle_rpm > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  if (machine.has(Axis::kC) && !(motion.spindle_rpm > 0))
    throw InputError("cutting.spindle_rpm", "machine '" + machine.name +
                                                "' programs the C axis: give the spindle speed (> 0 rpm)");
  if (!machine.has(Axis::kC) && !(motion.feed > 0))
    throw InputError("cutting.feed", "machine '" + machine.name +
                                         "' turns in X-Z only: give the feed (> 0 mm/min)");
}

double AxisMapper::axis_value(Axis axis, const CutterLocation& cl) const {
  const AxisSpec& s = machine_.spec(axis);
  switch (axis) {
    case Axis::kX: return s.sign * cl.x + s.offset;
    case Axis::kZ: return s.sign * cl.z + s.offset;
    case Axis::kC: return s.sign * cl.c * kDegrees + s.offset;
    case Axis::kB: return s.sign * cl.b * kDegrees + s.offset;
  }
  return 0;
}

void AxisMapper::check_block(const AxisRecord& r, const CutterLocation& cl) {
  const double values[4] = {r.x, r.z, previous_c_unwrapped_, r.b};
  for (const AxisSpec& s : machine_.axes) {
    const double v = values[static_cast<int>(s.axis)];
    if (!std::isfinite(v))
      throw InputError(where(cl), std::string(axis_letter(s.axis)) + " is not a finite number");
    if (v < s.min || v > s.max) {
      const bool above = v > s.max;
      const MachineDescription::BoundPlaces& places = machine_.travel_places[static_cast<int>(s.axis)];
      throw CheckFailure(at_bound(above ? places.max : places.min,
                                  std::string("machine axis ") + axis_letter(s.axis) +
                                      (above ? " max " : " min ") + number(above ? s.max : s.min),
                                  cl),
                         std::string(axis_letter(s.axis)) + " = " + number(v) +
                             " is outside its travel [" + number(s.min) + ", " + number(s.max) +
                             "] on machine '" + machine_.name + "'");
    }
  }
  if (machine_.has(Axis::kB) && (r.b < machine_.b_min_deg || r.b > machine_.b_max_deg)) {
    const bool above = r.b > machine_.b_max_deg;
    throw CheckFailure(
        at_bound(above ? machine_.b_limit_places.max : machine_.b_limit_places.min,
                 std::string("machine b_axis ") + (above ? "max_deg " : "min_deg ") +
                     number(above ? machine_.b_max_deg : machine_.b_min_deg),
                 cl),
        "B = " + number(r.b) + "° is outside the tool-rotation limits [" +
            number(machine_.b_min_deg) + "°, " + number(machine_.b_max_deg) + "°]");
  }
}

void AxisMapper::judge_block(const double speed[4], const double acceleration[4], double theta,
                             double r, bool stop) {
  const bool spiral = motion_.spindle_rpm > 0;
  const double m = motion_.margin;
  // The speed the limits scale with (velocity with it, acceleration with its square): a
  // spiral's rpm, a profile's feed.
  const double base = spiral ? motion_.spindle_rpm : motion_.feed;
  double speed_limit = std::numeric_limits<double>::infinity();
  const AxisSpec* limiting = nullptr;
  bool by_acceleration = false;
  for (const AxisSpec& s : machine_.axes) {
    const int i = static_cast<int>(s.axis);
    report_.peak_velocity[i] = std::max(report_.peak_velocity[i], speed[i]);
    report_.peak_acceleration[i] = std::max(report_.peak_acceleration[i], acceleration[i]);
    if (speed[i] > 0 && std::isfinite(s.max_velocity)) {
      const double candidate = base * m * s.max_velocity / speed[i];
      if (candidate < speed_limit) speed_limit = candidate, limiting = &s, by_acceleration = false;
    }
    if (acceleration[i] > 0 && std::isfinite(s.max_acceleration)) {
      const double candidate = base * std::sqrt(m * s.max_acceleration / acceleration[i]);
      if (candidate < speed_limit) speed_limit = candidate, limiting = &s, by_acceleration = true;
    }
  }
  // A profile is judged on a PVT controller only, which runs the cubics at the times its
  // feed sets; a linear controller ramps a feed move itself.
  if (!limiting || (!spiral && machine_.interpolation != Interpolation::kCubic)) return;
  double& highest = spiral ? report_.max_rpm : report_.max_feed;
  std::string& set_by = spiral ? report_.limiting : report_.feed_limiting;
  const bool lowest = speed_limit < highest;
  const bool refused = motion_.enforce_dynamics && speed_limit < base;
  if (!lowest && !refused) return;
  // A stop that sets the speed is worth naming: a short last block costs the whole program
  // its speed at one constant rpm, which scheduled timing would not.
  const std::string what = std::string(axis_letter(limiting->axis)) +
                           (by_acceleration ? " acceleration" : " velocity") +
                           (!spiral ? " on the controller's PVT cubics" : "") +
                           (stop ? " (the stop after the last block)" : "");
  if (lowest) {
    highest = speed_limit;
    set_by = what + " at " + where(theta, r);
    if (refused && !spiral) {
      feed_refused_ = true;
      feed_refused_where_ = where(theta, r);
      feed_refused_what_ = what;
    }
  }
  if (!refused || !spiral) return;  // a profile's refusal waits for its lowest feed (finish)
  throw CheckFailure(where(theta, r), what + " exceeds the machine's limit at " + number(base) +
                                          " rpm; this block allows at most " + number(speed_limit) +
                                          " rpm");
}

void AxisMapper::judge_motion(const BlockMotion& m, double theta, double r) {
  double speed[4], acceleration[4];
  for (int i = 0; i < 4; ++i) {
    speed[i] = std::abs(m.velocity[static_cast<std::size_t>(i)]);
    acceleration[i] = std::abs(m.acceleration[static_cast<std::size_t>(i)]);
  }
  judge_block(speed, acceleration, theta, r, m.stop);
}

void AxisMapper::finish() {
  // Under PVT the program's last block, its end velocity one-sided, and the stop from
  // that velocity; under linear motion a spiral's stop after it (a linear controller ramps
  // a profile's feed move itself).
  BlockMotion m;
  if (dynamics_.finish(m) && (!m.stop || motion_.spindle_rpm > 0))
    judge_motion(m, last_place_.theta, last_place_.r);
  if (dynamics_.stop_after_cubic(m)) judge_motion(m, last_place_.theta, last_place_.r);
  if (feed_refused_)
    throw InputError(feed_refused_where_,
                     feed_refused_what_ + " exceeds the machine's limit at cutting.feed " +
                         number(motion_.feed) + " mm/min: give a feed of at most " +
                         number(report_.max_feed) + " mm/min",
                     "cutting.feed");
}

void AxisMapper::write(std::span<const CutterLocation> chunk) {
  buffer_.clear();
  const bool spiral = motion_.spindle_rpm > 0;
  for (const CutterLocation& cl : chunk) {
    AxisRecord r;
    r.x = axis_value(Axis::kX, cl);
    r.z = axis_value(Axis::kZ, cl);
    double c = 0;
    if (machine_.has(Axis::kC)) {
      c = axis_value(Axis::kC, cl);
      r.c = machine_.c_wrapped ? c - 360 * std::floor(c / 360) : c;
    }
    if (machine_.has(Axis::kB)) {
      r.b = axis_value(Axis::kB, cl);
    } else if (cl.b != 0) {
      throw InputError(where(cl), "machine '" + machine_.name +
                                      "' has no B axis, but the tool is to rotate (B " +
                                      number(cl.b * kDegrees) + "°)");
    }
    previous_c_unwrapped_ = c;
    if (has_previous_) {
      if (spiral) {
        r.time = (cl.contact.theta - previous_theta_) / (2 * std::numbers::pi * motion_.spindle_rpm / 60);
      } else {
        r.time = std::hypot(r.x - previous_.x, r.z - previous_.z) / (motion_.feed / 60);
      }
      if (!(r.time > 0))
        throw InputError(where(cl), "two consecutive blocks at the same place (zero block time)");
    }
    check_block(r, cl);
    const long index = positions_++;
    const Place place{cl.contact.theta, cl.contact.r};
    if (has_previous_) {
      const double rate = 1 / r.time;
      report_.peak_block_rate = std::max(report_.peak_block_rate, rate);
      if (std::isfinite(machine_.max_block_rate)) {
        const double rpm_limit =
            motion_.spindle_rpm * motion_.margin * machine_.max_block_rate / rate;
        if (spiral && rpm_limit < report_.max_rpm) {
          report_.max_rpm = rpm_limit;
          report_.limiting = "block rate at " + where(cl);
        }
        if (motion_.enforce_dynamics && spiral && rpm_limit < motion_.spindle_rpm)
          throw CheckFailure(where(cl), "block rate exceeds the machine's limit at " +
                                            number(motion_.spindle_rpm) +
                                            " rpm; this block allows at most " + number(rpm_limit) +
                                            " rpm");
      }
      report_.cycle_time += r.time;
      report_.turns += (cl.contact.theta - previous_theta_) / (2 * std::numbers::pi);
    }
    // Dynamics per axis from the unwrapped values as the words carry them, as a program is
    // read back: at once for linear motion, a block later for a PVT cubic (its end
    // velocity waits for this block).
    BlockMotion m;
    const std::array<double, 4>& scale = word_scale_;
    if (dynamics_.add({as_written(r.x, scale[0]), as_written(r.z, scale[1]),
                       as_written(c, scale[2]), as_written(r.b, scale[3])},
                      has_previous_ ? r.time : 0.0, m)) {
      const Place& at = m.block == index ? place : last_place_;
      judge_motion(m, at.theta, at.r);
    }
    last_place_ = place;
    report_.blocks++;
    previous_ = r;
    previous_.c = c;  // unwrapped, for the next velocity
    previous_theta_ = cl.contact.theta;
    has_previous_ = true;
    buffer_.push_back(r);
  }
  out_.write(buffer_);
}

}  // namespace freeturn
