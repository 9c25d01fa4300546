#pragma once
// What a run reports (the model behind report.json and report.html, report_files.hpp):
// figures per pass, gathered while the pass streams (in bounded memory: the plot series
// are decimated as they grow), and the verdict.

#include <memory>
#include <string>
#include <vector>

#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/machine/block_schedule.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/tool/tool_checks.hpp"
#include "freeturn/verify/cut_simulation.hpp"
#include "freeturn/verify/residual_output.hpp"

namespace freeturn {

struct PlotPoint {
  double x, y, z, r, chord;
  double vx, vz, vc;  // axis velocities of the block ending here (mm/s, mm/s, °/s)
};

struct PassFigures {
  std::string name;
  double stock = 0;  // mm left above the design by this pass
  long points = 0;
  double revolutions = 0;
  double chord_max = 0, chord_rms = 0, scallop_max = 0, scallop_rms = 0;  // mm
  double cycle_time = 0;  // s: the programmed cycle, the sum of the block times written
  // The best program at one spindle speed: the highest rpm every block allows, and its cycle.
  double constant_rpm_cycle_time = 0;  // s
  bool scheduled = false;              // block times set by the scheduler
  long slowed_blocks = 0;              // scheduled blocks slower than the requested rpm
  DynamicsReport dynamics;  // peaks of the program as written; max_rpm at one constant speed
  // Where the nose is held at a concave crease (path/section_envelope.hpp): points held,
  // the largest uncut residual (mm) and where, and its largest value per radial band.
  // The deepest the interpolated motion dips below the design between blocks (mm): 0 under
  // the chord rule's one-sided band; equal-angle and equal-arc points may have some.
  double chord_below_max = 0;
  long held_points = 0;
  double uncut_max = 0, uncut_theta = 0, uncut_r = 0;
  double band_width = 0;           // mm
  std::vector<double> uncut_by_band;  // mm, band k covers [k, k + 1)·band_width
  ToolCheckReport checks;
  std::vector<std::string> check_warnings;
  std::vector<PlotPoint> samples;  // every `stride`-th point
  long stride = 1;
  std::vector<long> points_per_revolution;  // by revolution index ⌊θ/2π⌋

  // `record` and `previous` are the machine blocks of this point and the one before.
  void add(const CutterLocation& cl, const AxisRecord& record, const AxisRecord& previous);
  void finish(const PathSummary& s, const DynamicsReport& d, const ToolCheckReport& c);
  // The schedule the program was written with: its cycle time and axis peaks.
  void take_schedule(const ScheduleReport& s);

 private:
  double chord_sq_ = 0, scallop_sq_ = 0;
};

struct RunReport {
  std::string job, job_file, job_text, machine, plugin;
  double alpha_max_deg = -1;  // spirals: the quasi-revolution angle on the base
  bool axis_moved = false;
  std::vector<std::string> warnings;
  std::vector<PassFigures> passes;
  bool scheduled = false;       // spiral block times scheduled to the machine's limits
  bool enforce_dynamics = true;
  double spindle_rpm = 0;       // as programmed (constant-rpm programs: the highest feasible)
  double requested_rpm = 0;     // as the job asked
  // Why the program is not safe to cut, each with its worst place: a check the job
  // downgraded to a warning that found something, a jump of the nose, a dynamics limit the
  // program exceeds. Empty: PASS.
  std::vector<std::string> unsafe;
  bool simulated = false;
  std::shared_ptr<SimulationResult> simulation;  // of the finishing pass, when simulated
  std::shared_ptr<ResidualHeatMap> heat_map;     // its residual from above

  PassFigures& add_pass(const std::string& name, double stock) {
    passes.emplace_back();
    passes.back().name = name;
    passes.back().stock = stock;
    return passes.back();
  }
};

// Fills r.unsafe from the passes' figures (call once every pass is done).
void judge(RunReport& r);

}  // namespace freeturn
