#pragma once
// What `freeturn run` reports: figures per pass, gathered while the pass streams (in
// bounded memory: the plot series are decimated as they grow), then report.json and a
// self-contained report.html with inline SVG plots.

#include <memory>
#include <string>
#include <vector>

#include "freeturn/io/output_set.hpp"
#include "freeturn/verify/cut_simulation.hpp"
#include "freeturn/verify/residual_output.hpp"

#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/tool/tool_checks.hpp"

namespace freeturn::cli {

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
  double cycle_time = 0;                                                  // s
  DynamicsReport dynamics;
  ToolCheckReport checks;
  std::vector<std::string> check_warnings;
  std::vector<PlotPoint> samples;  // every `stride`-th point
  long stride = 1;
  std::vector<long> points_per_revolution;  // by revolution index ⌊θ/2π⌋

  // `record` and `previous` are the machine blocks of this point and the one before.
  void add(const CutterLocation& cl, const AxisRecord& record, const AxisRecord& previous);
  void finish(const PathSummary& s, const DynamicsReport& d, const ToolCheckReport& c);

 private:
  double chord_sq_ = 0, scallop_sq_ = 0;
};

struct RunReport {
  std::string job, job_file, job_text, machine, plugin;
  double alpha_max_deg = -1;  // spirals: the quasi-revolution angle on the base
  bool axis_moved = false;
  std::vector<std::string> warnings;
  std::vector<PassFigures> passes;
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

// Writes both files into `outputs`, to be put in place with the rest of the run.
void write_report(const RunReport& r, const std::string& json_path, const std::string& html_path,
                  OutputSet& outputs);

// A progress line on a terminal: points done, rate, estimated time left (from θ or r).
class Progress {
 public:
  Progress(bool enabled, std::string label);
  void update(double theta, double r, long points);
  void done();

 private:
  bool enabled_;
  std::string label_;
  double start_ = 0, last_print_ = 0;
  double interval_ = 0.25;  // s between updates
  double first_r_ = -1;
};

}  // namespace freeturn::cli
