#pragma once
// What a run reports (the model behind report.json and report.html, report_files.hpp):
// figures per pass, gathered while the pass streams (in bounded memory: the plot series
// are decimated as they grow), and the verdict.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "freeturn/job/job.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/machine/block_dynamics.hpp"
#include "freeturn/machine/block_schedule.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/tool/tool_checks.hpp"
#include "freeturn/verify/cut_simulation.hpp"
#include "freeturn/verify/form_error.hpp"
#include "freeturn/verify/residual_output.hpp"

namespace freeturn {

// How deep the motion between blocks may dip below the design before the verdict is
// UNSAFE (mm): what the words' rounding may take where the blocks stand off by little, and a
// simulated cut's grid may miss. Every rule's blocks stand off the design (docs/tool.md):
// what dips deeper is a jump the planner could not hold.
inline constexpr double kChordDipAllowed = 1e-5;

// One thing a run found, for a person (`message`) and for a program (the rest): what, how
// bad, where the worst of it is and by how much. NaN: not known, or not a place.
struct ReportWarning {
  enum class Severity {
    kNote,     // worth knowing: blocks slowed to the machine's limits
    kWarning,  // the part may not be what the design asks: material left at creases
    kUnsafe,   // do not cut this program as it is (the verdict turns UNSAFE)
  };
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // A stable key: a tool check's ("contact_angle", "clearance", "local_gouge",
  // "global_gouge", "centre", "b_limits"), or "nose_jump", "chord_below", "dynamics",
  // "spindle_speed", "slowed_blocks", "uncut_residual", "quasi_revolution"; for a program
  // from elsewhere (`simulate --program`), "travel" and "simulated_gouge".
  std::string kind;
  Severity severity = Severity::kWarning;
  std::string pass;     // "finish", "rough-1", …; empty: the job as a whole
  std::string message;  // one sentence, without the pass
  long count = 0;       // places found (cutter locations, segments, blocks); 0: not counted
  double theta_deg = kNone, r_mm = kNone, x_mm = kNone, y_mm = kNone;  // the worst place
  double value = kNone, limit = kNone;  // the worst value and the limit it breaks, in `unit`
  std::string unit;                     // "deg", "mm", "nm", "rpm"
};
const char* to_string(ReportWarning::Severity severity);
// A tool check's ReportWarning::kind and its key in report.json ("local_gouge").
const char* tool_check_kind(ToolCheck check);

struct PlotPoint {
  double x, y, z, r, theta, chord, scallop;  // mm, rad, mm, mm
};

// One block as the program writes it (after the scheduler, when there is one): where
// (the programmed radius, |X| back through the machine's layout) and its axes' velocity
// and acceleration as the machine moves through it, signed, by the rule the dynamics
// check judges (machine/block_dynamics.hpp): linear, or the largest on a PVT cubic.
struct BlockPoint {
  double r;           // mm
  double v[3], a[3];  // X, Z (mm/s, mm/s²), C (°/s, °/s²)
};

// The path from above for drawing: at most kTurnPoints points a turn (one per angle step)
// of every `turn_stride`-th turn; turns are dropped, stride doubled, past kMaxTurns.
struct TurnSamples {
  static constexpr int kTurnPoints = 240, kMaxTurns = 48;
  std::vector<std::vector<std::pair<float, float>>> turns;  // x, y (mm) per kept turn
  long turn_stride = 1;
  double start_x = 0, start_y = 0, end_x = 0, end_y = 0;  // the path's first and last contact
  bool any = false;
  void add(double theta, double x, double y);

 private:
  long turn_ = -1, step_ = -1;  // of the last point added
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
  // The same below the floor the motion must keep above the design where the real edge
  // reaches past the round nose (path/cutter_points.hpp, edge_reach; `chord_floor`, mm):
  // what an equal-angle or equal-arc run's stand-off fell short by.
  double chord_floor = 0;
  double below_floor_max = 0;
  long held_points = 0;
  double uncut_max = 0, uncut_theta = 0, uncut_r = 0;
  double band_width = 0;           // mm
  std::vector<double> uncut_by_band;  // mm, band k covers [k, k + 1)·band_width
  ToolCheckReport checks;
  // What the pass's checks, jumps and held points found (its part of RunReport::warnings).
  std::vector<ReportWarning> findings;
  std::vector<PlotPoint> samples;  // every `stride`-th point
  long stride = 1;
  TurnSamples turns;
  std::vector<BlockPoint> blocks;  // every `block_stride`-th block as written
  long block_stride = 1;
  bool cubic_blocks = false;  // the blocks are PVT cubics: `blocks` holds their largest values
  std::vector<long> points_per_revolution;  // by revolution index ⌊θ/2π⌋

  void add(const CutterLocation& cl);
  // A block as written, in order; x_spec converts its X back to a radius. `cubic`: the
  // machine interpolates PVT cubics, so a block is drawn once the block after it is known
  // (its end velocity is the central difference over both), the last one by finish().
  void add_block(const AxisRecord& record, const AxisSpec& x_spec, bool c_wrapped, bool cubic);
  void finish(const PathSummary& s, const DynamicsReport& d, const ToolCheckReport& c);
  // The schedule the program was written with: its cycle time and axis peaks.
  void take_schedule(const ScheduleReport& s);

 private:
  double chord_sq_ = 0, scallop_sq_ = 0;
  long written_ = 0;               // blocks seen by add_block
  // The blocks' motion, and where the last one lies (|X| as a radius; C as written and
  // unwrapped).
  BlockDynamics block_dynamics_{false};
  long positions_ = 0;
  double last_r_ = 0, last_c_ = 0, c_unwrapped_ = 0;
  void keep_block(long index, const BlockPoint& b);
  void draw_block(const BlockMotion& m, double r);
};

// The base surface a spiral is planned on, and the frame the part is cut in.
struct BaseFigures {
  std::string kind;  // "least_squares", "minimax"
  int degree = 0, coefficients = 0;
  double rho_max = 0;  // mm
  // When the axis was searched (strategy.base_surface.search_axis), the turning axis in the
  // design's frame: tilted by tilt_x about x then tilt_y about y, crossing the design at
  // `crossing`, which the program puts at the origin. The part is mounted to match.
  bool axis_searched = false;
  double tilt_x_deg = 0, tilt_y_deg = 0, tilt_deg = 0;  // tilt_deg: from the z axis
  double crossing_x = 0, crossing_y = 0, crossing_z = 0;  // mm
};

// The job's own settings, as the report prints them (docs/job-schema.md names each).
struct JobParameters {
  std::string strategy, points_rule, direction, timing;
  double pitch = 0, inner_radius = 0, outer_radius = 0;                   // mm
  double chord_tolerance = 0;                                              // mm; 0: not the chord rule
  // How far the blocks stand off the design (mm): half the chord band under the chord rule,
  // the measured dip's under the others (path/cutter_points.hpp, stand_off_for).
  double stand_off = 0;
  double nose_radius = 0, included_angle_deg = 0, clearance_angle_deg = 0;  // mm, °
  double feed = 0;                                                         // mm/min
  std::vector<double> roughing_depths;                                     // mm
};

struct RunReport {
  std::string job, job_file, job_text, machine, plugin;
  std::string version;        // freeturn's
  JobParameters parameters;
  double alpha_max_deg = -1;  // spirals: the quasi-revolution angle on the base
  bool axis_moved = false;
  BaseFigures base;
  // The measured parts the job corrects for (`compensation:`), with their registration and
  // fitted error; empty without compensation.
  std::vector<MeasuredPart> compensation;
  // Everything the run found, in the order found: the base surface's, each pass's, then
  // the verdict's (judge). The verdict is UNSAFE when any is kUnsafe.
  std::vector<ReportWarning> warnings;
  std::vector<PassFigures> passes;
  bool scheduled = false;       // spiral block times scheduled to the machine's limits
  // The job asked for one constant speed where the machine could take scheduled times
  // (linear motion, a time per block): the report then says what scheduling would keep.
  bool could_schedule = false;
  bool enforce_dynamics = true;
  // The machine's dynamic limits per Axis (mm/s, °/s; infinite: none stated) and which
  // axes it has.
  double max_velocity[4] = {0, 0, 0, 0}, max_acceleration[4] = {0, 0, 0, 0};
  bool has_axis[4] = {false, false, false, false};
  double spindle_rpm = 0;       // as programmed (constant-rpm programs: the highest feasible)
  double requested_rpm = 0;     // as the job asked
  // The finishing pass cut in simulation: at the user's grid when `simulated` (simulate,
  // --simulate), else on the report's own grid (the form error map every report has).
  bool simulated = false;
  std::shared_ptr<SimulationResult> simulation;
  std::shared_ptr<FormErrorSplit> form_error;    // its figure and finish
  std::shared_ptr<ResidualHeatMap> heat_map;     // its residual from above
  std::shared_ptr<ResidualHeatMap> figure_map;   // its figure from above

  // PASS: no warning is kUnsafe.
  bool safe() const;
  // Why the program is not safe to cut ("finish: clearance: 12 points, …"), one line each.
  std::vector<std::string> unsafe_reasons() const;
  // Every warning as one line, "pass: message" (the pass left out for the job's own).
  std::vector<std::string> messages() const;

  PassFigures& add_pass(const std::string& name, double stock) {
    passes.emplace_back();
    passes.back().name = name;
    passes.back().stock = stock;
    return passes.back();
  }
};

// The RMS of a fitted error over its normalisation disk, piston left out: Noll's terms are
// orthonormal there (the mean of Z_j² over the unit disk is 1), so it is √(Σ_{j≥2} a_j²).
double zernike_rms(const std::vector<double>& a);
// The RMS of a part's fitted error E: the Zernike terms' and, when fitted, the B-spline's
// (fitted to what the terms left, so nearly orthogonal to them), added in quadrature.
double fitted_error_rms(const MeasuredPart& part);
// What a part cut with this correction is predicted to keep of the measured error (mm RMS):
// the share the gain leaves, (1 − gain)·RMS(E), and what the fit did not explain, added in
// quadrature.
double compensated_rms(const MeasuredPart& part);

// A path's angle θ (rad, counting turns) as a place on the part: degrees in [0, 360).
double part_degrees(double theta);

// One warning as a line: "finish: message".
std::string warning_line(const ReportWarning& w);

// Adds the verdict's own warnings (the motion between blocks below the design, a dynamics
// limit exceeded) from the passes' figures, and judge_simulated_cut's. Call once, when
// every pass is done.
void judge(RunReport& r);

// An UNSAFE `simulated_gouge` warning where the simulated cut the user asked for (`simulated`:
// simulate, --simulate; not the report's own grid) lies more than kChordDipAllowed below
// the design, at its deepest cell.
void judge_simulated_cut(RunReport& r);

}  // namespace freeturn
