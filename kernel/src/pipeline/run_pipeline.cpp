#include "freeturn/pipeline/run_pipeline.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/core/parallel_for.hpp"
#include "freeturn/core/version.hpp"
#include "freeturn/io/nc_line.hpp"
#include "freeturn/io/nc_program.hpp"
#include "freeturn/io/output_set.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/machine/block_schedule.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/path/tight_troughs.hpp"
#include "freeturn/pipeline/contact_tape.hpp"
#include "freeturn/post/post_program.hpp"
#include "freeturn/surface/raised_surface.hpp"
#include "freeturn/tool/clearance.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "freeturn/verify/cut_simulation.hpp"
#include "freeturn/verify/residual_output.hpp"
#include "program_dynamics.hpp"

namespace freeturn {
namespace {

// Between compensation and the machine: statistics for the report, the streamed files
// (each cutter location with the axis record the mapper made of it), progress to the
// observer.
class PassStage final : public CutterSink, public AxisSink {
 public:
  // files: the finishing pass's streamed files, or null.
  PassStage(AxisSink& post, RunFiles* files, PassFigures& figures, RunObserver* observer)
      : post_(post), files_(files), figures_(figures), observer_(observer) {}
  void set_mapper(AxisMapper& m) { mapper_ = &m; }
  // The job's limit on points over all passes (counted in *points_so_far).
  void set_limits(const Limits& limits, long long* points_so_far) {
    limits_ = limits;
    points_so_far_ = points_so_far;
  }
  void set_simulator(CutSimulator* s) { simulator_ = s; }

  void write(std::span<const CutterLocation> chunk) override {
    cls_ = chunk;
    mapper_->write(chunk);  // calls back write(std::span<const AxisRecord>) below
    if (simulator_) simulator_->write(chunk);
  }

  void write(std::span<const AxisRecord> records) override {
    if (points_so_far_) {
      *points_so_far_ += static_cast<long long>(records.size());
      if (*points_so_far_ > limits_.max_points) {
        std::string why = "the job passes ";
        why += std::to_string(limits_.max_points);
        why += " points at r = ";
        why += significant_text(cls_.back().contact.r, 6);
        why +=
            " mm and is not done: more than limits.max_points allows (a pitch or tolerance typo?); "
            "nothing was written";
        throw InputError("limits.max_points", why);
      }
    }
    post_.write(records);
    if (files_) files_->finishing_chunk(cls_, records);
    if (observer_) observer_->cutter_locations(figures_.name, cls_, records);
    for (std::size_t k = 0; k < records.size(); ++k) figures_.add(cls_[k]);
    if (observer_ && !cls_.empty())
      observer_->progress(figures_.name, cls_.back().contact.theta, cls_.back().contact.r,
                          figures_.points);
  }

 private:
  AxisMapper* mapper_ = nullptr;
  CutSimulator* simulator_ = nullptr;
  AxisSink& post_;
  RunFiles* files_;
  PassFigures& figures_;
  RunObserver* observer_;
  std::span<const CutterLocation> cls_;
  Limits limits_;
  long long* points_so_far_ = nullptr;
};

// The blocks on their way to the post, as the program writes them (after the scheduler when
// there is one, each axis at its decimals): the report's velocity and acceleration charts
// are made of these.
class BlockTap final : public AxisSink {
 public:
  BlockTap(AxisSink& next, PassFigures& figures, const MachineDescription& machine)
      : next_(next),
        figures_(figures),
        x_(machine.spec(Axis::kX)),
        c_wrapped_(machine.c_wrapped),
        cubic_(machine.interpolation == Interpolation::kCubic),
        scale_(machine.word_scales()) {}
  void write(std::span<const AxisRecord> records) override {
    for (AxisRecord r : records) {
      r.x = as_written(r.x, scale_[0]);
      r.z = as_written(r.z, scale_[1]);
      r.c = as_written(r.c, scale_[2]);
      figures_.add_block(r, x_, c_wrapped_, cubic_);
    }
    next_.write(records);
  }

 private:
  AxisSink& next_;
  PassFigures& figures_;
  AxisSpec x_;
  bool c_wrapped_;
  bool cubic_;
  std::array<double, 4> scale_;
};

// Where the blocks go when nothing is written (check, and the constant-rpm probe): nowhere,
// so that memory stays bounded whatever the path's length.
class AxisDiscard final : public AxisSink {
 public:
  void write(std::span<const AxisRecord>) override {}
};

// Spiral block times are scheduled unless the job asks for one constant speed, turns the
// machine's limits off, or the dialect writes no time per block. PVT programs run at one
// speed too: the controller derives its velocities from the block times (pvt_rule.hpp),
// so a schedule would change the cubics the chord error was measured on.
constexpr int kMapPixels = 320;  // the report's maps, per side

// The grid every report's form error map is cut on when no simulation is asked for:
// sixteen cells a pitch, at most 3000 rings, 360 columns (about 10 MB, a few per cent of
// the planning time). The figure is the residual's mean over one pitch of n cells; it
// keeps the cusp's n-th harmonic, of amplitude 4/(π²n²) of the cusp's height (a parabolic
// cusp's Fourier series): 2.5 % at n = 4, 0.16 % at n = 16.
SimulationOptions report_grid(const Job& job) {
  SimulationOptions o;
  const double pitch = job.plan->strategy.pitch;
  const double width = job.aperture.outer_radius - job.aperture.inner_radius;
  o.radial_step = std::max(pitch / 16, width / 3000);
  o.columns = 360;
  o.band = std::max(3 * pitch, 2 * o.radial_step);
  o.margin = std::max(pitch, o.radial_step);
  return o;
}

// The grid and motion a simulation of the job's finishing pass uses: what was asked, the
// rest from the job (pitch/8 radially, a band of 3 pitches, a margin of one) and the
// machine (its interpolation).
SimulationOptions simulation_grid(SimulationOptions so, const Job& job,
                                  const MachineDescription& machine,
                                  const CompensationOptions& compensation) {
  if (job.plan->strategy.mode != Strategy::Mode::kSpiral)
    throw InputError(job.place("strategy.mode"),
                     "the cut simulation needs a spiral (strategy.mode: spiral)");
  const double pitch = job.plan->strategy.pitch;
  so.compensation = compensation;
  so.interpolation = machine.interpolation;
  so.inner_radius = job.aperture.inner_radius;
  so.outer_radius = job.aperture.outer_radius;
  if (!(so.radial_step > 0)) so.radial_step = pitch / 8;
  if (!(so.band > 0)) so.band = 3 * pitch;
  if (!(so.margin > 0)) so.margin = pitch;
  return so;
}

// The simulated cut into the report: the residual, its figure and finish, and their maps.
// `kept`: the user's grid (simulate, --simulate), written out; else the report's own, whose
// cells are dropped once the figures are made.
void attach_simulation(RunReport& report, SimulationResult result, const Job& job, double margin,
                       bool kept) {
  report.simulation = std::make_shared<SimulationResult>(std::move(result));
  report.simulated = kept;
  const double inner = job.aperture.inner_radius;
  report.heat_map = std::make_shared<ResidualHeatMap>(
      residual_heat_map(*report.simulation, inner, kMapPixels));
  const double pitch = job.plan->strategy.pitch;
  report.form_error = std::make_shared<FormErrorSplit>(split_figure_finish(
      *report.simulation, inner, job.aperture.outer_radius, margin, pitch));
  const FormErrorSplit& split = *report.form_error;
  report.figure_map = std::make_shared<ResidualHeatMap>(polar_heat_map(
      split.rings, split.columns, inner, split.radial_step,
      [&](std::size_t k) { return static_cast<double>(split.figure[k]); }, kMapPixels));
  if (!kept) {
    report.simulation->residual.clear();
    report.simulation->residual.shrink_to_fit();
    report.form_error->figure.clear();
    report.form_error->figure.shrink_to_fit();
  }
}

JobParameters job_parameters(const Job& job) {
  const JobPlan& plan = *job.plan;
  JobParameters p;
  const bool spiral = plan.strategy.mode == Strategy::Mode::kSpiral;
  p.strategy = spiral ? (plan.strategy.space ? "space spiral" : "planar spiral") : "profile";
  const CutterPointOptions& points = plan.strategy.points;
  p.points_rule = points.rule == CutterPointRule::kChordError       ? "chord"
                  : points.rule == CutterPointRule::kEqualArcLength ? "equal_arc"
                                                                    : "equal_angle";
  p.chord_tolerance = points.rule == CutterPointRule::kChordError ? points.tolerance : 0.0;
  p.direction = plan.strategy.centre_to_edge ? "centre to edge" : "edge to centre";
  p.timing = plan.cutting.timing == Cutting::Timing::kScheduled ? "scheduled" : "constant_rpm";
  p.pitch = spiral ? plan.strategy.pitch : 0.0;
  p.inner_radius = job.aperture.inner_radius;
  p.outer_radius = job.aperture.outer_radius;
  p.nose_radius = plan.tool.tool.nose_radius;
  p.included_angle_deg = plan.tool.tool.included_angle * 180 / std::numbers::pi;
  p.clearance_angle_deg = plan.tool.tool.clearance_angle * 180 / std::numbers::pi;
  p.feed = plan.cutting.feed;
  p.roughing_depths = plan.cutting.roughing_depths;
  return p;
}

BaseFigures base_figures(const BasePlanOptions& options, const BasePlan& plan) {
  BaseFigures b;
  b.kind = options.kind == BaseKind::kMinimax    ? "minimax"
           : options.kind == BaseKind::kPlane    ? "plane"
                                                 : "least_squares";
  b.degree = plan.base.degree();
  b.coefficients = static_cast<int>(plan.base.coefficients().size());
  b.rho_max = plan.base.rho_max();
  b.axis_searched = plan.design_about_axis != nullptr;
  if (b.axis_searched) {
    constexpr double kDegrees = 180 / std::numbers::pi;
    b.tilt_x_deg = plan.axis.tilt_x * kDegrees;
    b.tilt_y_deg = plan.axis.tilt_y * kDegrees;
    b.tilt_deg = std::acos(std::clamp(plan.axis.direction().z(), -1.0, 1.0)) * kDegrees;
    b.crossing_x = plan.axis_crossing.x();
    b.crossing_y = plan.axis_crossing.y();
    b.crossing_z = plan.axis_crossing.z();
  }
  return b;
}

// The machine's program carries a time per block, which a schedule may set: linear motion
// (PVT cubics would change with the times) and a dialect that writes a time a block.
bool takes_block_times(const MachineDescription& machine) {
  return !machine.constant_block_time && machine.interpolation != Interpolation::kCubic;
}

bool scheduling(const Job& job, const MachineDescription& machine) {
  const Cutting& c = job.plan->cutting;
  return c.enforce_dynamics && c.timing == Cutting::Timing::kScheduled &&
         takes_block_times(machine);
}

// The highest the programmed point rises over the job's aperture (kernel Z, mm): the base
// of the height a post approaches and retracts at (tool/clearance.hpp).
double kernel_ceiling(const Job& job, const CompensationOptions& compensation,
                      const Surface& design, const CutterPointOptions& points,
                      const ToolMotion& tool) {
  return program_z_ceiling(design, job.aperture.inner_radius, job.aperture.outer_radius,
                           compensation, stand_off_for(points, tool, design));
}

double machine_z(const MachineDescription& machine, double z) {
  const AxisSpec& a = machine.spec(Axis::kZ);
  return a.sign * z + a.offset;
}

struct PreparedJob {
  MachineDescription machine;
  std::unique_ptr<PostPlugin> plugin;
  int threads = 1;  // that plan the spiral (RunOptions::threads, resolved)
  std::uintmax_t max_replay_bytes = 0;  // RunOptions::max_replay_bytes
};

MachineDescription machine_for(const Job& job, const std::string& machine_file,
                               std::uintmax_t max_yaml_bytes) {
  MachineDescription m = load_machine(machine_file, max_yaml_bytes);
  const JobPlan& plan = *job.plan;
  const bool spiral = plan.strategy.mode == Strategy::Mode::kSpiral;
  if (spiral && !m.has(Axis::kC))
    throw InputError(job.place("machine"), "strategy.mode spiral needs a C axis; machine '" + m.name +
                                               "' has none (use mode: profile, or another machine)");
  if (plan.strategy.b_mode == BMode::kFollow && !m.has(Axis::kB))
    throw InputError(job.place("strategy.b_axis"),
                     "strategy.b_axis: follow needs a B axis; machine '" + m.name + "' has none");
  if (!spiral) {
    // Profile turning programs X and Z only; the spindle runs at speed.
    std::vector<AxisSpec> xz;
    for (const AxisSpec& a : m.axes)
      if (a.axis == Axis::kX || a.axis == Axis::kZ) xz.push_back(a);
    m.axes = xz;
    // The feed is the speed along the path: an axis moving alone goes at all of it.
    for (const AxisSpec& a : m.axes)
      if (plan.cutting.feed / 60 > a.max_velocity)
        throw InputError(job.place("cutting.feed"),
                         "cutting.feed " + shortest_text(plan.cutting.feed) + " mm/min moves " +
                             axis_letter(a.axis) + " at up to " +
                             shortest_text(plan.cutting.feed / 60) +
                             " mm/s, beyond the max_velocity " + shortest_text(a.max_velocity) +
                             " mm/s of machine '" + m.name + "': give a feed of at most " +
                             shortest_text(60 * a.max_velocity) + " mm/min");
  }
  return m;
}

// Every block carries each axis word, at least a letter, a digit, the point and the
// declared decimals, and ends its line: the fewest points a pass can have (read with the
// job) make an NC program at least that many bytes. Past limits.max_file_mb the job is
// refused before any planning, at the key that sets the step.
void refuse_oversized_program(const Job& job, const MachineDescription& machine) {
  const JobPlan& plan = *job.plan;
  if (!plan.outputs.nc) return;
  double block_bytes = 1;
  for (const AxisSpec& a : machine.axes) block_bytes += 2 + a.decimals + (a.decimals > 0 ? 1 : 0);
  const double bytes = plan.estimate.per_pass * block_bytes;
  if (!(bytes > plan.limits.max_file_mb * 1048576.0)) return;
  throw InputError(job.place(plan.estimate.key),
                   plan.estimate.key + " asks for at least " +
                       significant_text(std::ceil(plan.estimate.per_pass), 15) +
                       " points a pass: an NC program of at least " +
                       significant_text(bytes / 1048576.0, 3) + " MB on machine '" + machine.name +
                       "' (" + fixed_text(block_bytes, 0) +
                       " bytes a block at least), over limits.max_file_mb (" +
                       significant_text(plan.limits.max_file_mb, 6) + " MB)");
}

// The words a program is written with round each block: X and Z by half a unit of their
// decimals, C by half a unit turned at the aperture's edge, B by half a unit about its
// pivot. The nose's centre moves by no more than their sum, nor does its distance to the
// design. The verdict lets the motion dip kChordDipAllowed below the design; the rounding
// may take that much where the chord rule stands the blocks off (by ε/2, stand_off_for:
// no more than half of it), half of it where blocks sit on the design (equal angles and
// arcs, whose chords dip too). Past that the program as written could cut below the
// design, whatever the planned one does: decimals: 0 had written X2 for X1.97998, a 20 µm
// step, and passed.
// The most the words' rounding moves the nose's centre (mm), and the axis that moves it most.
double words_rounding(const Job& job, const MachineDescription& machine,
                      const AxisSpec** coarsest = nullptr) {
  constexpr double kRadian = std::numbers::pi / 180;
  double moved = 0, largest = -1;
  for (const AxisSpec& a : machine.axes) {
    const double half_unit = 0.5 * std::pow(10.0, -a.decimals);
    const double reach = a.axis == Axis::kC   ? job.aperture.outer_radius * kRadian
                         : a.axis == Axis::kB ? machine.pivot_distance * kRadian
                                              : 1.0;
    const double shift = half_unit * reach;  // mm
    moved += shift;
    if (shift > largest) {
      largest = shift;
      if (coarsest) *coarsest = &a;
    }
  }
  return moved;
}

void refuse_coarse_axis_words(const Job& job, const MachineDescription& machine) {
  const JobPlan& plan = *job.plan;
  // The blocks' stand-off beyond what a wavy edge takes of it (the chord rule's: the other
  // rules' is measured later, and takes the rounding in).
  const ToolMotion tool = tool_motion(plan.tool);
  const double stand_off =
      stand_off_for(plan.strategy.points, tool, *job.surface) - edge_reach(tool, *job.surface);
  const double allowed =
      stand_off > 0 ? std::min(0.5 * stand_off, kChordDipAllowed) : 0.5 * kChordDipAllowed;
  const AxisSpec* coarsest = nullptr;
  const double moved = words_rounding(job, machine, &coarsest);
  if (!(moved > allowed) || !coarsest) return;
  const std::string why =
      allowed < kChordDipAllowed && stand_off > 0
          ? "half the blocks' stand-off of " + significant_text(stand_off * 1e6, 4) +
                " nm (half the chord tolerance)"
      : stand_off > 0 ? "the depth the verdict lets the motion dip below the design"
                      : "half the " + significant_text(kChordDipAllowed * 1e6, 3) +
                            " nm the verdict lets a chord dip where blocks sit on the design";
  throw InputError(
      machine.decimals_places[static_cast<int>(coarsest->axis)],
      std::string("machine axis ") + axis_letter(coarsest->axis) + " decimals " +
          std::to_string(coarsest->decimals) +
          ": the program's words round the nose's position by up to " +
          significant_text(moved * 1e6, 4) + " nm (X, Z" +
          (machine.has(Axis::kC)
               ? ", C at r = " + significant_text(job.aperture.outer_radius, 6) + " mm"
               : std::string()) +
          (machine.has(Axis::kB) ? ", B about its pivot" : std::string()) + "), more than " +
          significant_text(allowed * 1e6, 4) + " nm, " + why +
          ": the program as written could cut below the design; write more decimals" +
          (plan.strategy.points.rule != CutterPointRule::kChordError && moved <= kChordDipAllowed
               ? ", or place the points by the chord rule (strategy.points.chord), "
                 "whose blocks stand off the design by half its tolerance: the "
                 "rounding may then take up to " +
                     significant_text(kChordDipAllowed * 1e6, 3) +
                     " nm (a tolerance of 40 nm or more)"
               : std::string()));
}

PreparedJob prepare_job(const Job& job, std::uintmax_t max_yaml_bytes) {
  if (!job.plan)
    throw InputError(SourceLocation{job.file, 1, 1},
                     "the job has no tool, strategy, cutting and machine sections to run");
  std::string machine_ref = job.plan->machine;
  if (machine_ref.find('/') != std::string::npos &&
      !std::filesystem::path(machine_ref).is_absolute())
    machine_ref = (std::filesystem::path(job.file).parent_path() / machine_ref).string();
  PreparedJob p;
  std::string machine_file;
  try {
    machine_file = find_machine_file(machine_ref);
  } catch (const InputError& e) {
    throw InputError(job.place("machine"), e.what());  // at the job's `machine:`
  }
  p.machine = machine_for(job, machine_file, max_yaml_bytes);
  refuse_oversized_program(job, p.machine);
  refuse_coarse_axis_words(job, p.machine);
  try {
    p.plugin = PostPlugin::load(p.machine.plugin);
  } catch (const InputError& e) {
    throw InputError(p.machine.plugin_place, e.what());  // at the machine's `plugin:`
  }
  return p;
}

// A report's head: the job (its file's name, not its path: a report is read on another
// machine and says nothing of this one's folders; and its text), freeturn's version, the
// job's parameters and measured parts, the machine, its post and its axes' limits.
RunReport report_of(const Job& job, const PreparedJob& prepared) {
  RunReport report;
  report.job = job.name;
  report.job_file = std::filesystem::path(job.file).filename().string();
  report.version = kVersion;
  report.parameters = job_parameters(job);
  report.compensation = job.compensation;
  {
    std::ifstream in(job.file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    report.job_text = text.str();
  }
  const MachineDescription& machine = prepared.machine;
  report.machine = machine.name;
  report.plugin = std::filesystem::path(prepared.plugin->path()).filename().string();
  for (const Axis a : {Axis::kX, Axis::kZ, Axis::kC, Axis::kB}) {
    const int i = static_cast<int>(a);
    report.has_axis[i] = machine.has(a);
    if (!report.has_axis[i]) continue;
    report.max_velocity[i] = machine.spec(a).max_velocity;
    report.max_acceleration[i] = machine.spec(a).max_acceleration;
  }
  return report;
}

// The base surface a spiral is planned on, into the report.
void report_base(RunReport& report, const BasePlanOptions& options, const BasePlan& base) {
  report.alpha_max_deg = base.quasi_revolution.max_angle * 180 / std::numbers::pi;
  report.axis_moved = base.design_about_axis != nullptr;
  report.base = base_figures(options, base);
}

// Each spiral pass's planned path as the constant-rpm probe made it (contact_tape.hpp),
// with its summary: the probe records them, the run at the speed found replays the
// complete ones instead of planning again.
//
// The stand-off of equal-angle and equal-arc blocks is carried here too: found before the
// first run and kept for the ones after it (equal_rule_stand_off).
struct PlannedPasses {
  std::vector<std::unique_ptr<ContactTape>> tapes;
  std::vector<PathSummary> summaries;
  double equal_rule_stand_off = -1;  // mm; < 0 until estimated
  int stand_off_raised = 0;          // times a run found it short and was run again
};

// The deepest the motion between blocks dips below the design over a planned path (mm).
class DipGauge final : public ContactSink {
 public:
  void write(std::span<const ContactPoint> chunk) override {
    for (const ContactPoint& p : chunk) deepest = std::max(deepest, p.dip_below_design());
  }
  double deepest = 0;
};

// A run whose equal-angle or equal-arc motion dipped below the design by `dip` (mm) past
// the blocks' stand-off: run again, higher (execute_with_stand_off).
struct StandOffShort {
  double dip = 0;
};

// The planners' options for the job's aperture and strategy, with the tool's motion and the
// cutter points given (the estimate below and every pass take the same).
SpiralOptions spiral_options(const Job& job, const PreparedJob& prepared, const ToolMotion& tool,
                             const CutterPointOptions& points) {
  SpiralOptions o;
  o.pitch = job.plan->strategy.pitch;
  o.outer_radius = job.aperture.outer_radius;
  o.inner_radius = job.aperture.inner_radius;
  o.centre_to_edge = job.plan->strategy.centre_to_edge;
  o.tool = tool;
  o.points = points;
  o.threads = prepared.threads;
  return o;
}

ProfileOptions profile_options(const Job& job, const ToolMotion& tool,
                               const CutterPointOptions& points) {
  ProfileOptions o;
  o.outer_radius = job.aperture.outer_radius;
  o.inner_radius = job.aperture.inner_radius;
  o.tool = tool;
  o.points = points;
  return o;
}

// How much more than a measured dip the blocks stand off (equal_rule_stand_off).
double stand_off_over(double dip) {
  constexpr double kSampledMaximum = 1e-6;  // mm: the measured dip is a sampled maximum
  return 1.25 * dip + kSampledMaximum;
}

// Equal-angle and equal-arc blocks are placed by their rule, so nothing keeps the chords
// between them above the design: on a convex stretch they dip by about L²κ/8 (a chord of
// length L), and by more where a nose rolls over a ridge or is held at a rim. The blocks
// stand off the design by the deepest dip a plan with no stand-off finds, a quarter more,
// a nanometre for the sampled maximum and the words' rounding: the chords then stay above
// the design, within a band of about twice that. The estimate plans the spiral at
// ⌊revolutions/96⌋ times the job's pitch, so 96 to 191 revolutions (all of them when there
// are fewer), the blocks' angles and arcs as the run's: the run measures every one of its
// own segments, and one that still dips below the design runs again with its dip added
// (StandOffShort).
// Until December 2026 the blocks sat on the design, and the motion was let dip 10 nm below
// it under a PASS (more was written and called UNSAFE: the demo's compound eye at 360
// points a revolution, 102 nm). The chord rule needs none of this (stand_off_for), nor a
// path with no nose.
double equal_rule_stand_off(const Job& job, const PreparedJob& prepared, const Surface& design,
                            const BasePlan& base, const ToolMotion& tool) {
  const JobPlan& plan = *job.plan;
  if (plan.strategy.points.rule == CutterPointRule::kChordError || !(tool.nose_radius > 0))
    return 0.0;
  DipGauge gauge;
  CutterPointOptions points = plan.strategy.points;
  points.interpolation = prepared.machine.interpolation;
  points.equal_rule_stand_off = 0;
  // The dip of the round nose's own motion, its blocks on the design: the reach of the
  // real edge past it is stood off on top (stand_off_for), and each run's segments are
  // held above that reach (PassFigures::below_floor_max).
  const ToolMotion round = round_nose(tool);
  if (plan.strategy.mode == Strategy::Mode::kSpiral) {
    constexpr double kEstimateRevolutions = 96;
    const double revolutions =
        (job.aperture.outer_radius - job.aperture.inner_radius) / plan.strategy.pitch;
    SpiralOptions o = spiral_options(job, prepared, round, points);
    o.pitch *= std::max(1.0, std::floor(revolutions / kEstimateRevolutions));
    plan_spiral(design, base.base, o, gauge);
  } else {
    plan_profile(design, profile_options(job, round, points), gauge);
  }
  return stand_off_over(gauge.deepest) + words_rounding(job, prepared.machine);
}

// simulation: when set, the finishing pass is also cut in simulation and its residual
// written (grid CSV, coloured PLY) with its figures in the report.
// files: null when nothing is written (check, and the constant-rpm probe).
// planned: the probe's paths, recorded when `probe`, else replayed where complete; and the
// equal-angle or equal-arc stand-off, estimated on the first run.
RunResult execute_job(const Job& job, const PreparedJob& prepared, const std::string& out_dir,
                      RunObserver* observer, RunFiles* files,
                      const SimulationOptions* simulation, double spindle_rpm, bool probe,
                      PlannedPasses& planned) {
  const bool write = files != nullptr;
  const JobPlan& plan = *job.plan;
  const MachineDescription& machine = prepared.machine;
  const auto& plugin = prepared.plugin;
  if (write) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec) throw InputError(out_dir, "cannot create the output folder: " + ec.message());
  }
  const auto out = [&](const std::string& name) {
    return (std::filesystem::path(out_dir) / name).string();
  };

  RunReport report = report_of(job, prepared);

  // The base surface and the frame the part is cut in.
  const bool spiral = plan.strategy.mode == Strategy::Mode::kSpiral;
  BasePlan base;
  if (spiral) {
    base = plan_base_surface(*job.surface, job.aperture.inner_radius, job.aperture.outer_radius,
                             plan.strategy.base);
    report_base(report, plan.strategy.base, base);
    for (const std::string& text : base.warnings) {
      ReportWarning w;
      w.kind = "quasi_revolution";
      w.message = text;
      w.value = report.alpha_max_deg;
      w.limit = plan.strategy.base.angle_limit * 180 / std::numbers::pi;
      w.unit = "deg";
      w.x_mm = base.quasi_revolution.where.x();
      w.y_mm = base.quasi_revolution.where.y();
      report.warnings.push_back(w);
      if (observer) observer->warning(warning_line(w));
    }
  }
  const Surface& design_itself = spiral ? base.design_to_cut(*job.surface) : *job.surface;

  CompensationOptions compensation = plan.tool;
  compensation.pivot_distance = machine.has(Axis::kB) ? machine.pivot_distance : 0.0;
  ToolCheckOptions checks = plan.checks;
  checks.b_min = machine.b_min_deg * std::numbers::pi / 180;
  checks.b_max = machine.b_max_deg * std::numbers::pi / 180;
  MotionOptions motion;
  motion.spindle_rpm = !spiral ? 0.0 : spindle_rpm > 0 ? spindle_rpm : plan.cutting.spindle_rpm;
  motion.feed = plan.cutting.feed;
  // A spiral whose program carries a time per block is scheduled: the requested rpm is the
  // highest speed, and each block slows only where the machine's limits demand it.
  const bool scheduled = spiral && scheduling(job, machine);
  motion.enforce_dynamics = plan.cutting.enforce_dynamics && !scheduled && !probe;
  report.scheduled = scheduled;
  report.could_schedule =
      spiral && !scheduled && plan.cutting.enforce_dynamics && takes_block_times(machine);
  report.requested_rpm = spiral ? plan.cutting.spindle_rpm : 0.0;
  report.spindle_rpm = motion.spindle_rpm;
  report.enforce_dynamics = plan.cutting.enforce_dynamics;

  // The tool's motion as every pass plans it, with what a wavy edge may reach past the
  // round nose on this design over this aperture (path/cutter_points.hpp).
  ToolMotion tool = tool_motion(compensation);
  measure_edge_reach(tool, design_itself, job.aperture.inner_radius, job.aperture.outer_radius);
  const TightTroughs troughs(
      design_itself, tool.nose_radius + stand_off_for(plan.strategy.points, tool, design_itself),
      job.aperture.outer_radius);
  const Surface& design = troughs.any() ? troughs : design_itself;
  // Estimated once, and raised by the runs that find it short (execute_with_stand_off).
  if (planned.equal_rule_stand_off < 0)
    planned.equal_rule_stand_off = equal_rule_stand_off(job, prepared, design, base, tool);
  const double stand_off = planned.equal_rule_stand_off;
  CutterPointOptions points = plan.strategy.points;
  points.interpolation = machine.interpolation;
  points.equal_rule_stand_off = stand_off;
  report.parameters.stand_off = stand_off_for(points, tool, design);

  std::vector<double> stock = plan.cutting.roughing_depths;
  // The clearance base the post approaches and retracts beyond: above every block of
  // every pass (a roughing pass's design is raised by its stock).
  const bool posting = plan.outputs.nc && (write || !probe);
  const double ceiling = posting ? kernel_ceiling(job, compensation, design, points, tool) : 0.0;
  long long points_so_far = 0;
  stock.push_back(0.0);  // the finishing pass
  std::vector<std::unique_ptr<PostProgram>> programs;
  // Every file of the run, put in place as one set when all has succeeded
  // (io/output_set.hpp: programs set aside, data files first, programs last).
  OutputSet outputs;
  for (std::size_t pass = 0; pass < stock.size(); ++pass) {
    const bool finishing = pass + 1 == stock.size();
    const std::string suffix = finishing ? "" : ".rough-" + std::to_string(pass + 1);
    // A roughing pass cuts the design raised by its stock; the finishing pass the design
    // itself, not a view raising it by 0 (every evaluation of the design would go
    // through a second virtual call: about 2 % of a compound eye's planning).
    const RaisedSurface raised(design, stock[pass]);
    const Surface& surface = stock[pass] != 0 ? static_cast<const Surface&>(raised) : design;
    PassFigures& figures =
        report.add_pass(finishing ? "finish" : "rough-" + std::to_string(pass + 1), stock[pass]);
    figures.band_width = (job.aperture.outer_radius - job.aperture.inner_radius) / 64;
    figures.chord_floor = edge_reach(tool, design);
    AxisDiscard discard;
    AxisSink* post = &discard;
    std::unique_ptr<BlockScheduler> scheduler;
    // `check` posts the program too, into no file: what the dialect or the guard would
    // refuse in `run` (block times a dialect cannot write, a program past max_file_mb) is
    // refused there as well. The constant-speed probe does not: its speed is not final.
    if (posting) {
      programs.push_back(std::make_unique<PostProgram>(
          *plugin, machine,
          ProgramSettings{job.name + suffix, motion.spindle_rpm, motion.feed, -1,
                          static_cast<long long>(plan.limits.max_file_mb * 1048576.0),
                          machine_z(machine, ceiling + stock[pass]),
                          static_cast<int>(machine.spec(Axis::kZ).sign)},
          write ? out(job.name + "." + machine.name + suffix + ".nc") : std::string()));
      post = programs.back().get();
    }
    if (write && finishing) files->begin_finishing_pass(job, out_dir, outputs);
    BlockTap tap(*post, figures, machine);
    post = &tap;
    if (scheduled) {
      scheduler = std::make_unique<BlockScheduler>(machine, *post);
      post = scheduler.get();
    }
    PassStage stage(*post, finishing ? files : nullptr, figures, observer);
    stage.set_limits(plan.limits, &points_so_far);
    std::unique_ptr<CutSimulator> simulator;
    // Every report shows the form error: without a simulation asked for, the finishing pass
    // is cut on the report's own grid (report_grid).
    const SimulationOptions preview = report_grid(job);
    const SimulationOptions* cut =
        simulation ? simulation : write && plan.outputs.report && spiral ? &preview : nullptr;
    if (finishing && cut) {
      const SimulationOptions so = simulation_grid(*cut, job, machine, compensation);
      simulator = std::make_unique<CutSimulator>(surface, plan.tool.tool.nose_radius, so);
      stage.set_simulator(simulator.get());
    }
    AxisMapper mapper(machine, motion, stage);
    stage.set_mapper(mapper);
    ToolCompensator compensator(surface, compensation, checks, stage);
    PathSummary summary;
    if (spiral) {
      const SpiralOptions o = spiral_options(job, prepared, tool, points);
      if (probe) {
        planned.tapes.push_back(std::make_unique<ContactTape>(prepared.max_replay_bytes));
        RecordingSink recorder(compensator, *planned.tapes.back());
        summary = plan_spiral(surface, base.base, o, recorder);
        planned.summaries.push_back(summary);
      } else if (pass < planned.tapes.size() && planned.tapes[pass]->complete()) {
        planned.tapes[pass]->replay(compensator);
        summary = planned.summaries[pass];
      } else {
        summary = plan_spiral(surface, base.base, o, compensator);
      }
    } else {
      summary = plan_profile(surface, profile_options(job, tool, points), compensator);
    }
    mapper.finish();
    if (scheduler) scheduler->finish();
    // Equal-angle or equal-arc motion below the design past the estimated stand-off (below
    // the edge's reach above it, where the real edge reaches past the round nose): run
    // again before anything of this pass is reported (the third time, the verdict says so).
    if (stand_off > 0 && figures.below_floor_max > 0 && planned.stand_off_raised < 2)
      throw StandOffShort{figures.below_floor_max};
    if (observer) observer->pass_done(figures.name);
    figures.finish(summary, mapper.report(), compensator.report());
    if (scheduler) figures.take_schedule(scheduler->report());
    if (simulator)
      attach_simulation(report, simulator->finish(), job, cut->margin > 0 ? cut->margin : plan.strategy.pitch,
                        simulation != nullptr);
    for (const ReportWarning& w : figures.findings) {
      report.warnings.push_back(w);
      if (observer) observer->warning(warning_line(w));
    }
  }
  judge(report);
  if (!write) {
    OutputSet dropped;  // the programs' ends still cross the plugin and the guard
    for (auto& p : programs) p->finish(dropped);
    return {report, {}};
  }
  // Everything succeeded: the files made from the whole run, then every file put in place.
  for (auto& p : programs) p->finish(outputs);
  files->finish(job, report, design, out_dir, outputs);
  std::vector<std::string> written = outputs.commit();
  return {std::move(report), std::move(written)};
}

// A constant-speed spiral (timing: constant_rpm, or a dialect without block times) runs at
// the highest speed every block allows, up to the job's: found by planning once without
// writing (velocity scales with the rpm, acceleration with its square), then written from
// the same path, kept from that first run (RunOptions::max_replay_bytes).
RunResult run_job_at_requested_speed(const Job& job, const PreparedJob& prepared,
                                     const std::string& out_dir, RunObserver* observer,
                                     RunFiles* files, const SimulationOptions* simulation);

// A limit of the job's own (limits.max_points, limits.max_file_mb) that stops the run is
// reported at its place in the job file: the errors name the key as their place.
RunResult run_with_places(const Job& job, const PreparedJob& prepared, const std::string& out_dir,
                          RunObserver* observer, RunFiles* files, const SimulationOptions* simulation) {
  try {
    return run_job_at_requested_speed(job, prepared, out_dir, observer, files, simulation);
  } catch (const CheckFailure& e) {
    if (e.cause().empty()) throw;
    const MachineDescription& m = prepared.machine;
    if (e.cause() == "machine.b_axis.min_deg" || e.cause() == "machine.b_axis.max_deg")
      throw CheckFailure((e.cause() == "machine.b_axis.min_deg" ? m.b_limit_places.min
                                                                 : m.b_limit_places.max)
                             .to_string(),
                         e.cause() + ": " + e.where() + ": " + e.problem(), e.cause());
    throw CheckFailure(job.place(e.cause()).to_string(),
                       e.cause() + ": " + e.where() + ": " + e.problem(), e.cause());
  } catch (const InputError& e) {
    if (!e.cause().empty())
      throw InputError(job.place(e.cause()).to_string(),
                       e.cause() + ": " + (e.where().empty() ? "" : e.where() + ": ") + e.problem(),
                       e.cause());
    // An error whose place is a key the job gives ("cutting.spindle_rpm") goes there.
    if (!job.places.count(e.where()) && e.where().rfind("limits.", 0) != 0) throw;
    throw InputError(job.place(e.where()), e.where() + ": " + e.problem());
  }
}

// execute_job, run again with the blocks' stand-off raised while an equal-angle or
// equal-arc run finds its motion below the design (StandOffShort). A run that throws has
// written nothing (io/output_set.hpp); the tapes a probe recorded are planned again.
RunResult execute_with_stand_off(const Job& job, const PreparedJob& prepared,
                                 const std::string& out_dir, RunObserver* observer, RunFiles* files,
                                 const SimulationOptions* simulation, double spindle_rpm, bool probe,
                                 PlannedPasses& planned) {
  for (;;) {
    try {
      return execute_job(job, prepared, out_dir, observer, files, simulation, spindle_rpm, probe,
                         planned);
    } catch (const StandOffShort& s) {
      planned.equal_rule_stand_off += stand_off_over(s.dip);
      ++planned.stand_off_raised;
      planned.tapes.clear();
      planned.summaries.clear();
    }
  }
}

RunResult run_job_at_requested_speed(const Job& job, const PreparedJob& prepared,
                                     const std::string& out_dir, RunObserver* observer,
                                     RunFiles* files, const SimulationOptions* simulation) {
  const JobPlan& plan = *job.plan;
  const double requested = plan.cutting.spindle_rpm;
  if (plan.strategy.mode == Strategy::Mode::kSpiral && plan.cutting.enforce_dynamics &&
      !scheduling(job, prepared.machine)) {
    PlannedPasses planned;
    const RunResult probe = execute_with_stand_off(job, prepared, out_dir, nullptr, nullptr,
                                                   nullptr, requested, true, planned);
    // The speed the probe found, less a billionth: the run at that speed computes each
    // block's limit again, and rounding can put it an ulp under the probe's, which its
    // check would then refuse.
    double rpm = requested;
    for (const PassFigures& f : probe.report.passes)
      if (f.dynamics.max_rpm < rpm) rpm = f.dynamics.max_rpm * (1 - 1e-9);
    return execute_with_stand_off(job, prepared, out_dir, observer, files, simulation, rpm, false,
                                  planned);
  }
  PlannedPasses planned;
  return execute_with_stand_off(job, prepared, out_dir, observer, files, simulation, 0, false,
                                planned);
}

// The plugin reads its dialect settings when a program is created: check creates one in
// a private temporary folder and drops it unwritten, so that settings `run` would refuse
// are refused here too, at their place in the machine file.
// With `approach`, one record at the clearance base (inside the Z travel, as the program's
// first block is once the path has passed the travel check) is written too, so that an
// approach the machine's travel cannot take is refused as `run` refuses it.
void check_dialect_settings(const Job& job, const PreparedJob& prepared, bool approach) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("freeturn-check-" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  try {
    const MachineDescription& m = prepared.machine;
    CompensationOptions compensation = job.plan->tool;
    compensation.pivot_distance = m.has(Axis::kB) ? m.pivot_distance : 0.0;
    const double stock = job.plan->cutting.roughing_depths.empty()
                             ? 0.0
                             : *std::max_element(job.plan->cutting.roughing_depths.begin(),
                                                 job.plan->cutting.roughing_depths.end());
    ToolMotion tool = tool_motion(compensation);
    measure_edge_reach(tool, *job.surface, job.aperture.inner_radius, job.aperture.outer_radius);
    const double top = machine_z(
        m,
        kernel_ceiling(job, compensation, *job.surface, job.plan->strategy.points, tool) + stock);
    PostProgram probe(*prepared.plugin, m,
                      ProgramSettings{job.name, job.plan->cutting.spindle_rpm, job.plan->cutting.feed,
                                      -1, -1, top, static_cast<int>(m.spec(Axis::kZ).sign)},
                      (folder / "settings-check.nc").string());
    const AxisSpec& x = m.spec(Axis::kX);
    AxisRecord record;
    record.x = std::clamp(0.0, x.min, x.max);
    const AxisSpec& z = m.spec(Axis::kZ);
    record.z = std::clamp(top, z.min, z.max);
    if (m.has(Axis::kB)) record.b = std::clamp(0.0, m.b_min_deg, m.b_max_deg);
    if (approach && job.plan->outputs.nc) probe.write(std::span<const AxisRecord>(&record, 1));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
    throw;
  }
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
}

}  // namespace

RunResult run_pipeline(const Job& job, const RunOptions& options, RunFiles& files,
                       RunObserver* observer) {
  PreparedJob prepared = prepare_job(job, options.max_yaml_bytes);
  prepared.threads = thread_count(options.threads);
  prepared.max_replay_bytes = options.max_replay_bytes;
  return run_with_places(job, prepared, options.output_dir, observer, &files,
                         options.simulation ? &*options.simulation : nullptr);
}

RunResult run_program_simulation(const Job& job, const std::string& program,
                                 const RunOptions& options, RunFiles& files) {
  const PreparedJob prepared = prepare_job(job, options.max_yaml_bytes);
  const MachineDescription& machine = prepared.machine;
  const JobPlan& plan = *job.plan;
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec) throw InputError(options.output_dir, "cannot create the output folder: " + ec.message());
  CompensationOptions compensation = plan.tool;
  compensation.pivot_distance = machine.has(Axis::kB) ? machine.pivot_distance : 0.0;
  // The contact points of a program written elsewhere are not known: the whole lower arc
  // of the nose is swept, not a band about the contact.
  SimulationOptions asked = options.simulation ? *options.simulation : SimulationOptions{};
  if (!(asked.band > 0)) asked.band = plan.tool.tool.nose_radius;
  const SimulationOptions so = simulation_grid(asked, job, machine, compensation);
  // The frame the program is in: the job's, with its searched axis if it has one.
  const BasePlan base = plan_base_surface(*job.surface, job.aperture.inner_radius,
                                          job.aperture.outer_radius, plan.strategy.base);
  const Surface& design = base.design_to_cut(*job.surface);
  CutSimulator simulator(design, plan.tool.tool.nose_radius, so);

  RunReport report = report_of(job, prepared);
  report_base(report, plan.strategy.base, base);
  report.requested_rpm = plan.cutting.spindle_rpm;
  PassFigures& figures = report.add_pass(
      "program " + std::filesystem::path(program).filename().string(), 0.0);
  figures.band_width = (job.aperture.outer_radius - job.aperture.inner_radius) / 64;

  // The blocks through the machine's layout: machine = sign · kernel + offset. Modal
  // words; C unwrapped through the shortest turn between blocks. Machine-frame moves (G53)
  // and position settings (G92, G28) are not cutting motion.
  constexpr double kDegrees = 180 / std::numbers::pi;
  const bool has_b = machine.has(Axis::kB);
  double value[4] = {std::nan(""), std::nan(""), std::nan(""), has_b ? std::nan("") : 0.0};
  double spindle = std::nan(""), last_c = std::nan(""), theta_end = std::nan("");
  std::vector<CutterLocation> chunk;
  long blocks = 0;
  const auto axis_of = [](char letter) {
    return letter == 'X' ? 0 : letter == 'Z' ? 1 : letter == 'C' ? 2 : letter == 'B' ? 3 : -1;
  };
  // A program from elsewhere was never checked against the machine: each axis's travel
  // (and B's tool-rotation limits) is, block by block; the farthest crossing of each is
  // reported.
  struct Crossing {
    long blocks = 0;
    double value = 0, limit = 0, excess = -1;
    std::string where;
    CutterLocation at;
  };
  Crossing crossing[4];
  std::vector<std::string> program_files;
  const std::vector<NcBlock> program_blocks = read_nc_program(program, &program_files);
  detail::ProgramDynamics dynamics(machine, program_files);
  detail::ProgramDynamics::Feed feed;
  // The modes this reading assumes (io/nc_line.hpp): a block that moves under another is
  // refused rather than cut as if it were absolute millimetres. Calls are read in line, so
  // one state follows the program as a controller runs it.
  NcModeState modes;
  for (const NcBlock& b : program_blocks) {
    bool motion = false, machine_frame = false, machine_words = false, reference = false,
         presets = false, zero_words = true;
    const NcWord* first_axis = nullptr;
    const NcWord* preset = nullptr;
    for (const NcWord& w : b.words) {
      if (!w.numeric) continue;
      if (w.letter == 'G') {
        modes.apply(w.value, w.text, b.line);
        machine_words |= w.value == 53;
        reference |= w.value == 28 || w.value == 30;
        presets |= g_code_presets_frame(w.value);
      }
      if (!nc_axis_letter(w.letter)) continue;
      if (!first_axis) first_axis = &w;
      zero_words &= w.value == 0;
      if (!preset && w.letter != 'C') preset = &w;
    }
    const auto refuse_block = [&](const NcWord& w, const std::string& why) {
      throw InputError(
          SourceLocation{program_files[static_cast<std::size_t>(b.file)], b.line, w.column}, why);
    };
    if (presets && preset)
      refuse_block(*preset, std::string(1, preset->letter) +
                                " in a preset (G10, G52, G92) moves the frame the program's "
                                "later positions are read in, which this reading does not follow");
    if (first_axis) {
      const int left = modes.left(machine_words || (reference && zero_words));
      if (left >= 0)
        refuse_block(*first_axis, "an axis word under " + modes.why(left) +
                                      ": the program is read as " + kNcModesAssumed);
    }
    double next[4] = {value[0], value[1], value[2], value[3]};
    for (const NcWord& w : b.words) {
      if (!w.numeric) continue;
      if (w.letter == 'G' && (w.value == 93 || w.value == 94 || w.value == 95))
        feed.mode = static_cast<int>(w.value);
      if (w.letter == 'F') feed.f = w.value;
      if (w.letter == 'G' && (w.value == 0 || w.value == 1 || w.value == 2 || w.value == 3))
        feed.rapid = w.value == 0;
      if (w.letter == 'G' && (w.value == 53 || w.value == 92 || w.value == 28)) machine_frame = true;
      const int a = axis_of(w.letter);
      if (a < 0 || (a == 3 && !has_b)) continue;
      next[a] = w.value;
      motion = true;
    }
    if (machine_frame) continue;
    std::copy(next, next + 4, value);
    if (!motion || std::isnan(value[0]) || std::isnan(value[1]) || std::isnan(value[2])) continue;
    const AxisSpec& sx = machine.spec(Axis::kX);
    const AxisSpec& sz = machine.spec(Axis::kZ);
    const AxisSpec& sc = machine.spec(Axis::kC);
    const double c_deg = (value[2] - sc.offset) / sc.sign;
    spindle = std::isnan(spindle)
                  ? c_deg / kDegrees
                  : spindle + (machine.c_wrapped ? std::remainder(c_deg - last_c, 360.0)
                                                 : c_deg - last_c) /
                                  kDegrees;
    last_c = c_deg;
    CutterLocation cl;
    cl.x = (value[0] - sx.offset) / sx.sign;
    cl.z = (value[1] - sz.offset) / sz.sign;
    if (has_b) cl.b = (value[3] - machine.spec(Axis::kB).offset) / machine.spec(Axis::kB).sign / kDegrees;
    cl.c = spindle;
    // The nose centre's angle on the part: the spindle's, turned where the edge sits off
    // the spindle line.
    const double theta = work_angle_from_axes(spindle, cl.x, cl.b, compensation);
    theta_end = theta;
    const Eigen::Vector2d centre = nose_centre_from_axes(cl.x, cl.z, cl.b, compensation);
    cl.nose_centre = Eigen::Vector3d(centre.x() * std::cos(theta), centre.x() * std::sin(theta), centre.y());
    // The contact, where the design's normal in the radial plane passes through the nose
    // centre: radial c_r + R·s/√(1 + s²) for the design's radial slope s under the centre.
    double z, zx, zy;
    design.sag_gradient(cl.nose_centre.x(), cl.nose_centre.y(), z, zx, zy);
    const double slope = zx * std::cos(theta) + zy * std::sin(theta);  // along the signed radial
    const double radial =
        centre.x() + plan.tool.tool.nose_radius * slope / std::sqrt(1 + slope * slope);
    cl.contact.theta = theta;
    cl.contact.r = std::abs(radial);
    cl.contact.point = Eigen::Vector3d(radial * std::cos(theta), radial * std::sin(theta),
                                       std::isfinite(z) ? z : centre.y());
    for (const AxisSpec& spec : machine.axes) {
      const int a = static_cast<int>(spec.axis);
      double lo = spec.min, hi = spec.max;
      if (spec.axis == Axis::kB)
        lo = std::max(lo, machine.b_min_deg), hi = std::min(hi, machine.b_max_deg);
      const double v = value[a];
      if (v >= lo && v <= hi) continue;
      Crossing& k = crossing[a];
      ++k.blocks;
      const double excess = v < lo ? lo - v : v - hi;
      if (excess > k.excess) {
        k.excess = excess;
        k.value = v;
        k.limit = v < lo ? lo : hi;
        k.where = program_files[static_cast<std::size_t>(b.file)] + ":" + std::to_string(b.line);
        k.at = cl;
      }
    }
    dynamics.add({value[0], value[1], sc.sign * spindle * kDegrees + sc.offset, value[3]}, feed, b,
                 cl);
    figures.add(cl);
    ++blocks;
    chunk.push_back(cl);
    if (chunk.size() >= 4096) {
      simulator.write(chunk);
      chunk.clear();
    }
  }
  if (blocks < 2)
    throw InputError(program, "the program holds " + std::to_string(blocks) +
                                  " blocks that move X, Z and C: nothing to simulate");
  for (const AxisSpec& spec : machine.axes) {
    const Crossing& k = crossing[static_cast<int>(spec.axis)];
    if (k.blocks == 0) continue;
    const std::string letter = axis_letter(spec.axis);
    const bool b_limit =
        spec.axis == Axis::kB && (k.limit == machine.b_min_deg || k.limit == machine.b_max_deg);
    ReportWarning w;
    w.kind = "travel";
    w.severity = ReportWarning::Severity::kUnsafe;
    w.message = std::to_string(k.blocks) + (k.blocks == 1 ? " block takes " : " blocks take ") +
                letter + " past " + (b_limit ? "the tool-rotation limit " : "its travel limit ") +
                shortest_text(k.limit) + " of machine '" + machine.name + "': " + letter + " = " +
                shortest_text(k.value) + " at " + k.where;
    w.count = k.blocks;
    w.theta_deg = part_degrees(k.at.contact.theta);
    w.r_mm = k.at.contact.r;
    w.x_mm = k.at.contact.point.x();
    w.y_mm = k.at.contact.point.y();
    w.value = k.value;
    w.limit = k.limit;
    w.unit = spec.axis == Axis::kX || spec.axis == Axis::kZ ? "mm" : "deg";
    report.warnings.push_back(std::move(w));
  }
  simulator.write(chunk);
  PathSummary summary;
  summary.theta_end = theta_end;
  figures.finish(summary, DynamicsReport{}, ToolCheckReport{});
  dynamics.finish(report, figures);
  attach_simulation(report, simulator.finish(), job, so.margin, true);
  // Nothing vouches for a program from elsewhere but its simulated cut.
  judge_simulated_cut(report);
  OutputSet outputs;
  files.finish(job, report, design, options.output_dir, outputs);
  std::vector<std::string> written = outputs.commit();
  return {std::move(report), std::move(written)};
}

RunReport check_job(const Job& job, const RunOptions& options, RunObserver* observer) {
  PreparedJob prepared = prepare_job(job, options.max_yaml_bytes);
  prepared.threads = thread_count(options.threads);
  prepared.max_replay_bytes = options.max_replay_bytes;
  check_dialect_settings(job, prepared, false);
  // The approach after the path: `run` checks the first block's travel before the post
  // writes the approach to it, so a path past the travel fails there first (exit 1).
  RunReport report = run_with_places(job, prepared, "", observer, nullptr, nullptr).report;
  check_dialect_settings(job, prepared, true);
  return report;
}

PlannedPath plan_job(const Job& job, const RunOptions& options) {
  struct Collector final : RunObserver {
    PlannedPath path;
    void cutter_locations(const std::string& pass, std::span<const CutterLocation> locations,
                          std::span<const AxisRecord> records) override {
      if (pass != "finish") return;
      path.locations.insert(path.locations.end(), locations.begin(), locations.end());
      path.records.insert(path.records.end(), records.begin(), records.end());
    }
  } collector;
  check_job(job, options, &collector);
  return std::move(collector.path);
}

}  // namespace freeturn
