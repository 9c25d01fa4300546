#pragma once
// The job: what a user asks freeturn to do, read from YAML (docs/job-schema.md).
// The schema grows with the planner, tools and machines; unknown keys are errors.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/job/yaml_limits.hpp"
#include "freeturn/metrology/registration.hpp"
#include "freeturn/path/base_plan.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/tool_checks.hpp"

namespace freeturn {

struct Aperture {
  double outer_radius = 0;  // mm, > 0
  double inner_radius = 0;  // mm, 0 <= inner < outer
};

struct Strategy {
  enum class Mode { kSpiral, kProfile } mode = Mode::kSpiral;
  bool space = false;  // spiral: on a fitted base surface (space) or a plane (planar)
  BasePlanOptions base;
  bool centre_to_edge = false;
  double pitch = 0;  // mm per revolution (spiral)
  CutterPointOptions points;
  BMode b_mode = BMode::kFixed;  // 4-axis: B follows the contact angle
};

struct Cutting {
  double spindle_rpm = 0;  // spiral
  double feed = 0;         // mm/min, profile
  std::vector<double> roughing_depths;  // mm of stock left by each roughing pass, descending
  // false: the program runs at spindle_rpm whatever the machine's limits (said explicitly;
  // the verdict is then UNSAFE where it exceeds them).
  bool enforce_dynamics = true;
  // How block times are set on a spiral: `scheduled`, each block as fast as the machine's
  // limits allow up to spindle_rpm (machine/block_schedule.hpp); `constant_rpm`, one
  // spindle speed for the whole program, the highest the limits allow up to spindle_rpm.
  enum class Timing { kScheduled, kConstantRpm } timing = Timing::kScheduled;
};

struct Outputs {
  bool nc = true, cl_csv = false, report = true;
  bool mesh = false;  // the design as OBJ and the path (decimated) as VTK
};

// The sections a run needs; a job with only name, aperture and surface can be sampled.
// What a job may produce at most: a typo in a pitch or a tolerance must not fill a
// shop's disk or DNC link. Exceeded, the run stops and nothing is written.
struct Limits {
  long long max_points = 100'000'000;  // cutter locations over all passes
  double max_file_mb = 2048;           // each NC program (its files together), the CL file
};

// The fewest cutter points a pass can have, worked out from the job's step settings (the
// pitch, the angle, arc or radial steps and the aperture) when it is read, and the key
// that sets them: the limits are checked against it before any planning.
struct PointEstimate {
  double per_pass = 0;
  std::string key;  // "strategy.points.equal_arc.length"
};

struct JobPlan {
  CompensationOptions tool;
  ToolCheckOptions checks;
  Strategy strategy;
  Cutting cutting;
  std::string machine;  // a machine name or a path to its YAML
  Outputs outputs;
  Limits limits;
  PointEstimate estimate;
};

// One measured part the job corrects for (the `compensation:` section, docs/metrology.md):
// the file, how it was read and registered, and what registering it found. The job cuts
// design − Σ gain · error over its entries.
struct MeasuredPart {
  std::string file;    // as the job names it (relative to the job file)
  std::string format;  // zygo_xyz, xyz, csv, grid, profile
  double gain = 1;
  long invalid = 0;    // points the file marks invalid
  long points = 0;     // valid points read
  Registration registration;
};

struct Job {
  std::string file;  // where it was read from
  std::string name;  // used in output file names: letters, digits, '-', '_', '.'
  Aperture aperture;
  // The surface the job cuts: the design, or with `compensation:` a CorrectedSurface
  // (surface/corrected_surface.hpp) that holds the design.
  std::unique_ptr<Surface> surface;
  std::vector<MeasuredPart> compensation;
  std::optional<JobPlan> plan;  // present when the job has tool, strategy, cutting, machine
  // Where each value stands in the file, by its dotted key ("strategy.mode",
  // "tool.nose_radius"): errors found later, while planning or posting, are reported there.
  std::map<std::string, SourceLocation> places;

  // The place of `key`'s value; for a key the job leaves to its default, that of the
  // nearest section holding it ("tool" for tool.included_angle_deg); else the file alone.
  SourceLocation place(const std::string& key) const;
};

// Reads and validates a job file. Throws InputError ("file:line:col: what") on bad input.
// max_bytes bounds the file before it is parsed (load_yaml_file).
Job load_job(const std::string& path, std::uintmax_t max_bytes = kMaxYamlBytes);

}  // namespace freeturn
