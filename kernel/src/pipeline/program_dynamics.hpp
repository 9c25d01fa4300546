#pragma once
// The dynamics of a program read back (`simulate --program`): each block's time from the
// words the program gives it, each axis's motion through it by the machine's rule
// (machine/block_dynamics.hpp), and what it asks beyond the machine file's limits.
//
// The cut is the spiral's inverse-time blocks (G93): Moore's F is a block's time in
// seconds, LinuxCNC's (the iso post) 1/F minutes (docs/verify.md). The approach and the
// retract around them (G94, G0) are not the cut and are left out; each run of G93 blocks
// (a pass) starts from rest, as the run's own check has it. A cut block with no time the program
// states (no F; a dialect whose time this reader does not know, such as the Precitech's, whose one
// block time is a comment) leaves the dynamics unjudged, and the report says where.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "freeturn/io/nc_program.hpp"
#include "freeturn/machine/block_dynamics.hpp"
#include "freeturn/machine/machine.hpp"
#include "freeturn/pipeline/run_report.hpp"

namespace freeturn::detail {

class ProgramDynamics {
 public:
  // `files`: the program's files (read_nc_program), which its blocks' `file` indices name.
  ProgramDynamics(const MachineDescription& machine, const std::vector<std::string>& files);
  // The program's modal feed state as a block leaves it: G93 (inverse time), G94, G95 or 0
  // (none stated), F (NaN: none yet), and whether the motion is G0.
  struct Feed {
    int mode = 0;
    double f = std::numeric_limits<double>::quiet_NaN();
    bool rapid = false;  // G0: a move at the machine's own speed, not the cut's
  };
  // The next motion block: the machine's X, Z, C (unwrapped) and B, the block as written
  // (its file and line), and the cutter location it stands for (the report's place).
  void add(const std::array<double, 4>& q, const Feed& feed, const NcBlock& block,
           const CutterLocation& cl);
  // The program's end; the peaks and the cycle time into `figures`, an UNSAFE warning per
  // axis (and for the block rate) that the program asks more of than the machine allows,
  // or a note where the dynamics could not be judged.
  void finish(RunReport& report, PassFigures& figures);

 private:
  struct Place {
    int file = 0, line = 0;
    CutterLocation cl;
  };
  std::string where(const Place& p) const;  // "file:line"
  struct Excess {
    long blocks = 0;
    double value = 0, limit = 0, worst = 0;  // worst: value / limit
    Place at;
  };
  void judge(const BlockMotion& m, const Place& at);
  void add_excess(Excess& e, double value, double limit, const Place& at);

  const MachineDescription& machine_;
  const std::vector<std::string>& files_;
  BlockDynamics dynamics_;
  long blocks_ = 0;
  std::array<double, 4> last_q_{};
  bool started_ = false;      // inside a cut (a run of G93 blocks)
  bool judged_ = false;       // a cut was met
  bool placed_ = false;       // a block was read
  double seconds_per_f_ = 0;  // inverse time: a block's time is this × F (Moore), or 60 / F (0)
  Place last_;
  bool untimed_ = false;  // a cut block states no time this reader knows: untimed_at_
  Place untimed_at_;
  bool no_time_ = false;  // that block is G93 in a dialect read here, with no F > 0
  double no_time_f_ = 0;  // its F (NaN: none stated)
  double cycle_time_ = 0, peak_rate_ = 0;
  std::array<double, 4> peak_velocity_{}, peak_acceleration_{};
  std::array<Excess, 4> velocity_excess_, acceleration_excess_;
  Excess rate_excess_;
  std::array<double, 4> limit_velocity_{}, limit_acceleration_{};
};

}  // namespace freeturn::detail
