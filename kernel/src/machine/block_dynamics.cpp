#include "freeturn/machine/block_dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "freeturn/path/pvt_rule.hpp"

namespace freeturn {

bool BlockDynamics::add(const std::array<double, 4>& q, double time, BlockMotion& out) {
  const long k = positions_++;
  if (k == 0) {
    q_last_ = q;
    return false;
  }
  if (cubic_) {
    bool known = false;
    if (k == 1) {
      // The first block's start velocity, one-sided.
      for (int a = 0; a < 4; ++a) v_before_[a] = pvt::velocity(q_last_[a], q[a], time);
    } else {
      std::array<double, 4> v_end;
      for (int a = 0; a < 4; ++a) v_end[a] = pvt::velocity(q_before_[a], q[a], t_last_ + time);
      draw_cubic(k - 1, v_end, out);
      v_before_ = v_end;
      known = true;
    }
    q_before_ = q_last_;
    q_last_ = q;
    t_last_ = time;
    return known;
  }
  const double rate = 1 / time, faster = std::max(rate, rate_before_);
  out.block = k;
  for (int a = 0; a < 4; ++a) {
    const double velocity = (q[a] - q_last_[a]) * rate;
    out.acceleration[a] = (velocity - v_before_[a]) * faster;
    out.velocity[a] = velocity;
    v_before_[a] = velocity;
  }
  rate_before_ = rate;
  q_last_ = q;
  return true;
}

bool BlockDynamics::finish(BlockMotion& out) {
  if (positions_ < 2) return false;
  if (!cubic_) {
    out.block = positions_ - 1;
    out.stop = true;
    for (int a = 0; a < 4; ++a) {
      out.velocity[a] = 0;
      out.acceleration[a] = -v_before_[a] * rate_before_;
    }
    return true;
  }
  // The last block's end velocity, one-sided from the block before it.
  std::array<double, 4> v_end;
  for (int a = 0; a < 4; ++a) v_end[a] = pvt::velocity(q_before_[a], q_last_[a], t_last_);
  draw_cubic(positions_ - 1, v_end, out);
  return true;
}

bool BlockDynamics::stop_after_cubic(BlockMotion& out) const {
  if (!cubic_ || positions_ < 2) return false;
  out.block = positions_ - 1;
  out.stop = true;
  for (int a = 0; a < 4; ++a) {
    const double v_end = pvt::velocity(q_before_[a], q_last_[a], t_last_);
    out.velocity[a] = 0;
    out.acceleration[a] = -v_end / t_last_;
  }
  return true;
}

void BlockDynamics::draw_cubic(long block, const std::array<double, 4>& v_end, BlockMotion& out) {
  out.block = block;
  const bool from_rest = block == 1;
  for (int a = 0; a < 4; ++a) {
    out.velocity[a] = pvt::extreme_velocity(q_before_[a], v_before_[a], q_last_[a], v_end[a], t_last_);
    double at_start, at_end;
    pvt::end_accelerations(q_before_[a], v_before_[a], q_last_[a], v_end[a], t_last_, at_start, at_end);
    double acceleration = std::abs(at_end) > std::abs(at_start) ? at_end : at_start;
    // The program starts at rest: the first block's start velocity is reached over its time.
    if (from_rest && std::abs(v_before_[a]) / t_last_ > std::abs(acceleration))
      acceleration = v_before_[a] / t_last_;
    out.acceleration[a] = acceleration;
  }
}

}  // namespace freeturn
