#include "freeturn/machine/block_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A block planned slower than this share of the next one's speed is a crawl (plan).
constexpr double kCrawl = 1.0 / 64;

// Bisection between a feasible speed lo and an infeasible hi > lo, up to the boundary.
template <class Ok>
double feasible_boundary(double lo, double hi, Ok&& ok) {
  for (int it = 0; it < 48 && hi - lo > 1e-13 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (ok(mid))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// The largest speed s ≤ cap for which ok(s) holds: cap itself, or a descent by factors of
// 0.8 to a feasible speed, then bisection up to the boundary. 0 when none is found.
template <class Ok>
double largest_feasible(double cap, Ok&& ok) {
  if (ok(cap)) return cap;
  double hi = cap, lo = cap;
  for (int it = 0;; ++it) {
    if (it == 160) return 0.0;  // 0.8^160 ≈ 3e-16 of the cap
    hi = lo;
    lo *= 0.8;
    if (ok(lo)) break;
  }
  return feasible_boundary(lo, hi, ok);
}

// The same, knowing a feasible speed `known` ≤ cap (0: none known): bisection between it
// and the cap when the cap is not feasible.
template <class Ok>
double largest_feasible_from(double known, double cap, Ok&& ok) {
  if (!(known > 0) || !(known <= cap) || !ok(known)) return largest_feasible(cap, ok);
  if (ok(cap)) return cap;
  return feasible_boundary(known, cap, ok);
}

// A nominal block time as send() writes a block's (up to the next whole microsecond). The
// 1e-6 µs slack keeps a time that is a whole µs to rounding from becoming the next one.
double whole_microseconds_up(double seconds) {
  return std::ceil(1e6 * seconds - 1e-6) * 1e-6;
}

// The time send() writes for a block planned at speed s (1/s): whole microseconds, up.
double written_time(double s) {
  return std::ceil(1e6 / s - 1e-6) * 1e-6;
}

// The speed a block planned at s runs at as written (0 stays 0: rest).
double written_speed(double s) {
  return s > 0 ? 1 / written_time(s) : 0.0;
}

std::string place_of(const AxisRecord& r) {
  return "the block to X " + fixed_text(r.x, 6) + " Z " + fixed_text(r.z, 6) + " C " +
         fixed_text(r.c, 5);
}

}  // namespace

BlockScheduler::BlockScheduler(const MachineDescription& machine, AxisSink& out,
                               ScheduleOptions options)
    : machine_(machine), out_(out), options_(options), word_scale_(machine.word_scales()) {
  for (int a = 0; a < 4; ++a) velocity_limit_[a] = acceleration_limit_[a] = kInfinity;
  for (const AxisSpec& s : machine.axes) {
    const int a = static_cast<int>(s.axis);
    present_[a] = true;
    velocity_limit_[a] = options_.margin * s.max_velocity;
    acceleration_limit_[a] = options_.margin * s.max_acceleration;
  }
  options_.window = std::max<std::size_t>(options_.window, 16);
  pending_.reserve(options_.window);
  buffer_.reserve(options_.window);
}

// Checked at the speeds as written (whole microseconds), on the displacements as written:
// what a reader of the program alone finds. The margin is left for the post's own
// rounding of the times (a few parts in 1e9) and for ties in the words' rounding.
bool BlockScheduler::pair_ok(const double* d1, double s1, const double* d2, double s2) const {
  s1 = written_speed(s1);
  s2 = written_speed(s2);
  const double faster = std::max(s1, s2);
  for (int a = 0; a < 4; ++a) {
    if (!present_[a] || !std::isfinite(acceleration_limit_[a])) continue;
    if (std::abs(d2[a] * s2 - d1[a] * s1) * faster > acceleration_limit_[a]) return false;
  }
  return true;
}

void BlockScheduler::write(std::span<const AxisRecord> chunk) {
  for (const AxisRecord& r : chunk) {
    // The positions as the program's words carry them (as_written). Planned on the
    // unrounded path, an axis whose limit is small beside its words' rounding over a
    // block's time (Z at 0.001 mm/s², 6 decimals, blocks of 0.2 s) read back 2 % over it.
    double written[4];
    const double q[4] = {r.x, r.z, r.c, r.b};
    for (int a = 0; a < 4; ++a) written[a] = present_[a] ? as_written(q[a], word_scale_[a]) : 0.0;
    if (!started_) {
      // The program's first position: reached by the approach, no duration.
      started_ = true;
      for (int a = 0; a < 4; ++a) last_written_[a] = written[a];
      buffer_.clear();
      buffer_.push_back(r);
      buffer_.back().time = 0;
      out_.write(buffer_);
      continue;
    }
    Block b;
    b.record = r;
    for (int a = 0; a < 4; ++a) b.d[a] = written[a] - last_written_[a];
    const int c = static_cast<int>(Axis::kC);
    if (machine_.c_wrapped) b.d[c] = std::remainder(b.d[c], 360.0);
    b.nominal = r.time;
    double upper = r.time > 0 ? 1 / r.time : kInfinity;
    for (int a = 0; a < 4; ++a)
      if (present_[a] && b.d[a] != 0 && std::isfinite(velocity_limit_[a]))
        upper = std::min(upper, velocity_limit_[a] / std::abs(b.d[a]));
    if (std::isfinite(machine_.max_block_rate))
      upper = std::min(upper, options_.margin * machine_.max_block_rate);
    if (!(upper > 0) || !std::isfinite(upper))
      throw InputError(place_of(r), "the block has no time the machine's limits allow");
    b.upper = upper;
    pending_.push_back(b);
    for (int a = 0; a < 4; ++a) last_written_[a] = written[a];
    if (pending_.size() >= options_.window) {
      plan(false);
      send(options_.window / 2);
    }
  }
}

void BlockScheduler::plan(bool /*final*/) {
  // Backward: the window's end is taken as a stop, which the blocks sent later can always
  // be brought to, so what is sent now never depends on blocks not yet seen.
  static const double kRest[4] = {0, 0, 0, 0};
  const double* next_d = kRest;
  double next_s = 0;
  for (std::size_t k = pending_.size(); k-- > 0;) {
    Block& b = pending_[k];
    double s = largest_feasible(b.upper, [&](double v) { return pair_ok(b.d, v, next_d, next_s); });
    // No speed of this block reaches the next at its speed: slow the next one down (a
    // slower pair is closer to rest, which every block can leave or reach).
    for (int it = 0; !(s > 0) && it < 200 && k + 1 < pending_.size(); ++it) {
      next_s *= 0.5;
      pending_[k + 1].speed = next_s;
      s = largest_feasible(b.upper, [&](double v) { return pair_ok(b.d, v, next_d, next_s); });
    }
    // A speed of the next block that leaves this one only a crawl (a pivot's swing between
    // B-following blocks: 4.8e12 s for one block, so that an ISO program carried F0 and
    // the report a cycle of 400 000 years): slowing the next block instead, where that
    // takes less time over the two, as the fallback above does where nothing is left.
    while (k + 1 < pending_.size() && s > 0 && s < kCrawl * next_s) {
      const double slower_next = 0.5 * next_s;
      const double own =
          largest_feasible(b.upper, [&](double v) { return pair_ok(b.d, v, next_d, slower_next); });
      if (!(own > 0) || !(1 / own + 1 / slower_next < 1 / s + 1 / next_s)) break;
      next_s = slower_next;
      pending_[k + 1].speed = next_s;
      s = own;
    }
    if (!(s > 0))
      throw CheckFailure(place_of(b.record), "no block time lets the machine follow it",
                         "cutting.spindle_rpm");
    b.speed = s;
    if (k + 1 < pending_.size()) {
      pending_[k + 1].ref_prev = s;
      pending_[k + 1].ref_self = next_s;
    }
    next_d = b.d;
    next_s = s;
  }
  // Forward: from the last block sent (or rest), each block as fast as the one before allows.
  const double* prev_d = sent_d_;
  double prev_s = sent_speed_;
  for (Block& b : pending_) {
    const double known =
        b.ref_prev > 0 && prev_s <= b.ref_prev ? b.ref_self * prev_s / b.ref_prev : 0.0;
    const double s = largest_feasible_from(
        known, b.speed, [&](double v) { return pair_ok(prev_d, prev_s, b.d, v); });
    if (!(s > 0))
      throw CheckFailure(place_of(b.record), "no block time lets the machine follow it",
                         "cutting.spindle_rpm");
    b.speed = s;
    b.ref_prev = prev_s;
    b.ref_self = s;
    prev_d = b.d;
    prev_s = s;
  }
}

void BlockScheduler::send(std::size_t count) {
  count = std::min(count, pending_.size());
  buffer_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const Block& b = pending_[k];
    // Whole microseconds, as the posts write a block's time (6 decimals): the program's
    // cycle is then the sum of the written times. Rounding up only slows the block, by at
    // most 1 µs, which the margin covers.
    const double t = written_time(b.speed);
    buffer_.push_back(b.record);
    buffer_.back().time = t;
    const double shorter = report_.blocks > 0 ? std::min(t, sent_time_) : t;
    for (int a = 0; a < 4; ++a) {
      if (!present_[a]) continue;
      const double v = b.d[a] / t;
      report_.peak_velocity[a] = std::max(report_.peak_velocity[a], std::abs(v));
      report_.peak_acceleration[a] =
          std::max(report_.peak_acceleration[a], std::abs(v - sent_velocity_[a]) / shorter);
      sent_velocity_[a] = v;
      sent_d_[a] = b.d[a];
    }
    report_.peak_block_rate = std::max(report_.peak_block_rate, 1 / t);
    report_.cycle_time += t;
    report_.nominal_cycle_time += b.nominal;
    // Slowed only where the machine's limits made the block longer than its nominal time
    // written the same way: the rounding up to a whole µs alone slows no block.
    if (t > whole_microseconds_up(b.nominal) + 0.5e-6) report_.slowed_blocks++;
    report_.blocks++;
    sent_speed_ = 1 / t;
    sent_time_ = t;
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count));
  if (!buffer_.empty()) out_.write(buffer_);
}

void BlockScheduler::finish() {
  if (pending_.empty()) return;
  plan(true);
  send(pending_.size());
  // The stop after the last block.
  for (int a = 0; a < 4; ++a)
    if (present_[a])
      report_.peak_acceleration[a] =
          std::max(report_.peak_acceleration[a], std::abs(sent_velocity_[a]) / sent_time_);
}

}  // namespace freeturn
