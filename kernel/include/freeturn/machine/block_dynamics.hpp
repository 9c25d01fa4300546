#pragma once
// The velocity and acceleration each axis goes through over each block of a program, as the
// controller moves it: the one statement of that rule, for the mapper's dynamics check
// (AxisMapper), the report's charts (PassFigures) and a program read back
// (`simulate --program`).
//
// Linear interpolation: axis a moves by d over a block of time t at v = d·(1/t), and its
// acceleration into the block is the change of velocity over the shorter of the two
// blocks' times, (v − v_before)·max(1/t, 1/t_before); the program starts at rest and
// stops after its last block, over that block's time: −v_last/t_last.
// PVT: the cubic Hermite through the block's ends, whose velocities are the central
// differences over their neighbours (path/pvt_rule.hpp; one-sided at the program's ends):
// the velocity of largest size on it, and the larger of its end accelerations (linear in
// time in between); the first block starts from rest, |v_start|/t at least, and the last
// ends at its one-sided velocity, from which the controller stops: −v_end/t_last.
#include <array>

namespace freeturn {

// One block's motion, per axis in the caller's order (X, Z, C, B), signed: a size and the
// direction it points.
struct BlockMotion {
  long block = 0;  // 1 for the move from the first position to the second
  std::array<double, 4> velocity{}, acceleration{};
  // Linear motion's stop after the last block `block`: velocity 0, the acceleration
  // that brings each axis to rest.
  bool stop = false;
};

class BlockDynamics {
 public:
  explicit BlockDynamics(bool cubic) : cubic_(cubic) {}
  // The next position (C unwrapped) and the time taken to reach it (ignored for the first).
  // True when a block's motion is known, into `out`: at once for linear motion, a block
  // later under PVT (its end velocity waits for the position after it).
  bool add(const std::array<double, 4>& q, double time, BlockMotion& out);
  // The program's end (true, into `out`, once a block has been added): under PVT its last
  // block's cubic; under linear motion the stop after the last block, which a controller
  // makes over that block: a spiral at one constant speed that ends in a short block stops
  // its spindle hard there.
  bool finish(BlockMotion& out);
  // Under PVT, after finish(): the stop after the last block (`stop` set). The last cubic
  // ends at its one-sided velocity, and the controller brings each axis to rest from it
  // over that block's time, as the first block starts from rest over its own. False under
  // linear motion, whose finish() is the stop.
  bool stop_after_cubic(BlockMotion& out) const;

 private:
  // The cubic of `block` (from q_before_ to q_last_, time t_last_), ending at v_end.
  void draw_cubic(long block, const std::array<double, 4>& v_end, BlockMotion& out);
  bool cubic_;
  long positions_ = 0;
  std::array<double, 4> q_before_{}, q_last_{}, v_before_{};
  double t_last_ = 0;
  double rate_before_ = 0;  // linear: 1/t of the block before (0: from rest)
};

}  // namespace freeturn
