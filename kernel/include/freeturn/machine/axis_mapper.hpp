#pragma once
// Cutter locations → machine axis values, block times and the machine's limits: the stage
// between tool compensation and the post-processor.
//
// Block times come from the spindle speed on a spiral (Δθ / ω) and from the feed along the
// path in profile mode. Travel and B limits are errors at the first block that breaks
// them. Dynamics (velocity, acceleration, block rate) scale with the spindle speed, so
// the mapper also finds the highest rpm at which every block stays within the limits:
// velocity and block rate ∝ rpm, acceleration ∝ rpm².
//
// The dynamics are those of the motion the controller makes of the blocks. Linear
// interpolation: each block's velocity Δq/t, and the change between blocks over the
// shorter one's time (from rest before the first). PVT (`interpolation: pvt`): the cubic
// Hermite of path/pvt_rule.hpp, whose velocities at the blocks are central differences:
// its largest speed and its accelerations at both ends of every block (from rest before
// the first too). Where the axes turn sharply (a nose held at a lenslet's rim) the
// cubic's acceleration is up to twice the linear figure, and three times where they
// reverse.

#include <limits>
#include <string>
#include <vector>

#include "freeturn/machine/axis_record.hpp"
#include "freeturn/machine/block_dynamics.hpp"
#include "freeturn/machine/machine.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

struct MotionOptions {
  double spindle_rpm = 0;  // spiral modes: block time = Δθ / (2π rpm / 60)
  double feed = 0;         // mm/min, profile mode (used when spindle_rpm is 0)
  // A dynamics violation at the constant spindle speed is an error (else only reported).
  // Off when a BlockScheduler follows the mapper: it sets the block times instead.
  bool enforce_dynamics = true;
  // The share of each limit the highest constant rpm may use.
  double margin = kDynamicLimitShare;
};

struct DynamicsReport {
  double peak_velocity[4] = {0, 0, 0, 0};      // per Axis, machine units per second
  double peak_acceleration[4] = {0, 0, 0, 0};  // per Axis, per second²
  double peak_block_rate = 0;                  // blocks per second
  double max_rpm = 0;  // the highest spindle speed every block can follow (spiral modes)
  double cycle_time = 0;  // s, at the requested speed (a scheduler's report has the real one)
  double turns = 0;       // spindle revolutions of the path: its cycle at max_rpm is 60·turns/max_rpm
  long blocks = 0;
  std::string limiting;  // what sets max_rpm ("X velocity at θ = …")
  // A profile on a PVT controller: the highest feed its cubics allow (mm/min; infinite
  // elsewhere), and what sets it.
  double max_feed = std::numeric_limits<double>::infinity();
  std::string feed_limiting;
};

class AxisMapper final : public CutterSink {
 public:
  // `machine` and `out` must outlive the mapper. Throws InputError for options the machine
  // cannot use (no rpm on a C machine, no feed in profile mode).
  AxisMapper(const MachineDescription& machine, const MotionOptions& motion, AxisSink& out);

  // Throws InputError at the first block outside travel or B limits (and, with
  // enforce_dynamics, a spiral's first block beyond a dynamic limit), naming the axis, the
  // value, the limit and where.
  void write(std::span<const CutterLocation> chunk) override;
  // The path is done: under PVT its last block's cubic (which waits for the block after it,
  // whose place sets the velocity it ends with) is judged now, with the one-sided velocity
  // of the program's end and the stop from it; under linear interpolation, a spiral's stop
  // after its last block (a profile runs at a feed, which the controller ramps itself).
  // With enforce_dynamics, a PVT profile whose feed some block cannot follow is refused
  // here, at cutting.feed, with the highest feed that every block allows: refused at its
  // first such block, it named a feed that a later one (the stop) refused again.
  void finish();

  const DynamicsReport& report() const { return report_; }

  // The machine value of one axis for a cutter location (before wrapping C).
  double axis_value(Axis axis, const CutterLocation& cl) const;

 private:
  void check_block(const AxisRecord& r, const CutterLocation& cl);
  // The peaks of one block's motion (per Axis: its largest speed and acceleration), into
  // the report and the highest rpm (a PVT profile: feed); with enforce_dynamics, an error
  // where the requested speed asks more of an axis than it allows. θ and r: the block's
  // place on the path.
  // `stop`: the motion is the stop after the last block, which the limit's text then names.
  void judge_block(const double speed[4], const double acceleration[4], double theta, double r,
                   bool stop = false);
  // judge_block for a block's motion (its sizes), the block at θ, r.
  void judge_motion(const BlockMotion& m, double theta, double r);
  const MachineDescription& machine_;
  MotionOptions motion_;
  AxisSink& out_;
  DynamicsReport report_;
  std::vector<AxisRecord> buffer_;
  bool has_previous_ = false;
  AxisRecord previous_;
  double previous_theta_ = 0;
  double previous_c_unwrapped_ = 0;
  // The axes' motion block by block; where each block lies on the path (θ, r), for the
  // last one placed (a PVT block's motion is known once the block after it is).
  BlockDynamics dynamics_;
  std::array<double, 4> word_scale_;  // per Axis: the motion judged is the words' (as_written)
  long positions_ = 0;
  struct Place {
    double theta = 0, r = 0;
  };
  Place last_place_;
  // A PVT profile's feed that a block cannot follow (enforce_dynamics): where the lowest
  // feed allowed is set, and what sets it.
  bool feed_refused_ = false;
  std::string feed_refused_where_, feed_refused_what_;
  Eigen::Vector3d previous_point_ = Eigen::Vector3d::Zero();
};

}  // namespace freeturn
