#pragma once
// Block times the machine can follow (docs/machines.md, "Scheduling"): the stage between
// the axis mapper and the post-processor for programs that carry a time per block (G93
// inverse time).
//
// Each block k moves every axis a by d_a = q_a(k) − q_a(k − 1) in its time t_k. Read back
// from the program alone, the axis's velocity over the block is v = d_a/t_k and its
// acceleration between blocks k and k + 1 is the change of velocity over the shorter of
// the two times, so the schedule keeps, for every axis,
//   |d_a(k)| / t_k ≤ m·v_max,   |v_a(k+1) − v_a(k)| ≤ m·a_max·min(t_k, t_k+1),
// t_k ≥ 1/(m·max_block_rate), and t_k ≥ its nominal time (the requested spindle speed),
// with the program starting and ending at rest; m is the margin for the rounding of the
// written numbers. Only where a limit demands it is a block slower than nominal.
//
// The speeds 1/t_k are planned over a window of blocks: a backward pass gives each block
// the highest speed from which the blocks after it can still be followed (the window's end
// taken as a stop), a forward pass lowers each to what the block before it allows. The
// first half of the window is then sent; its speeds never depend on what lies past the
// window's end (a stop there is always reachable). Memory is the window's, whatever the
// path's length.

#include <vector>

#include "freeturn/machine/axis_record.hpp"
#include "freeturn/machine/machine.hpp"

namespace freeturn {

struct ScheduleOptions {
  double margin = kDynamicLimitShare;  // m: the share of each limit the schedule may use
  std::size_t window = 16384;  // blocks held for planning (half of them sent at a time)
};

// The program as written.
struct ScheduleReport {
  double cycle_time = 0;          // s: the sum of the block times
  double nominal_cycle_time = 0;  // s: at the requested speed, every block at its nominal time
  long blocks = 0;
  long slowed_blocks = 0;                      // blocks longer than nominal
  double peak_velocity[4] = {0, 0, 0, 0};      // per Axis, machine units per second
  double peak_acceleration[4] = {0, 0, 0, 0};  // per Axis, per second², as defined above
  double peak_block_rate = 0;                  // blocks per second
};

class BlockScheduler final : public AxisSink {
 public:
  // `machine` and `out` must outlive the scheduler. Records arrive with their nominal
  // times (the first record of the program with time 0).
  BlockScheduler(const MachineDescription& machine, AxisSink& out, ScheduleOptions options = {});

  void write(std::span<const AxisRecord> chunk) override;
  // Schedules and sends what is held, ending at rest. Throws InputError if no schedule
  // can be found (a block that no speed lets the machine follow).
  void finish();

  const ScheduleReport& report() const { return report_; }

 private:
  struct Block {
    AxisRecord record;
    double d[4] = {0, 0, 0, 0};  // displacement per Axis from the previous record, as written
    double nominal = 0;          // s
    double upper = 0;            // the highest speed (1/s) velocity, rate and nominal allow
    double speed = 0;            // 1/s, planned
    // A pair of speeds (the block before, this one) known to satisfy the acceleration
    // limit between them. Scaling both by λ ≤ 1 keeps it (|Δv|·max(s) scales by λ²), so
    // when the block before ends up slower, this block's speed scaled alike is a feasible
    // start for the forward pass's search.
    double ref_prev = 0, ref_self = 0;
  };
  bool pair_ok(const double* d1, double s1, const double* d2, double s2) const;
  void plan(bool final);
  void send(std::size_t count);

  const MachineDescription& machine_;
  AxisSink& out_;
  ScheduleOptions options_;
  double velocity_limit_[4], acceleration_limit_[4];  // m × the machine's; infinity if none
  bool present_[4] = {false, false, false, false};
  std::array<double, 4> word_scale_;       // per Axis (MachineDescription::word_scales)
  double last_written_[4] = {0, 0, 0, 0};  // the previous record as its words carry it
  std::vector<Block> pending_;
  std::vector<AxisRecord> buffer_;
  bool started_ = false;
  // The last block sent: the start of the next window's forward pass.
  double sent_d_[4] = {0, 0, 0, 0};
  double sent_speed_ = 0;
  double sent_velocity_[4] = {0, 0, 0, 0};
  double sent_time_ = 0;
  ScheduleReport report_;
};

}  // namespace freeturn
