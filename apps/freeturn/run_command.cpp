// freeturn run, check and simulate: the arguments parsed, the job run by the library
// (freeturn/report/run_job.hpp), its figures and verdict printed.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "commands.hpp"
#include "freeturn/freeturn.hpp"
#include "progress_line.hpp"

namespace freeturn::cli {
namespace {

// Warnings on stderr and a progress line when stderr is a terminal; nothing with --quiet.
class Observer final : public RunObserver {
 public:
  explicit Observer(bool quiet) : quiet_(quiet), progress_on_(!quiet && isatty(STDERR_FILENO)) {}
  void warning(const std::string& text) override {
    if (!quiet_) std::fprintf(stderr, "warning: %s\n", text.c_str());
  }
  void progress(const std::string& pass, double theta, double r, long points) override {
    if (!progress_on_) return;
    if (!line_ || pass != pass_) {
      line_ = std::make_unique<Progress>(true, pass);
      pass_ = pass;
    }
    line_->update(theta, r, points);
  }
  void pass_done(const std::string&) override {
    if (line_) line_->done();
    line_.reset();
  }

 private:
  bool quiet_, progress_on_;
  std::unique_ptr<Progress> line_;
  std::string pass_;
};

RunOptions run_options(const std::string& out_dir) {
  RunOptions o;
  o.output_dir = out_dir;
  o.max_yaml_bytes = yaml_byte_bound();
  return o;
}

void print_summary(const Job& job, const RunResult& r) {
  const PassFigures& f = r.report.passes.back();
  std::printf("%s on %s: %ld points, %.1f revolutions, chord error max %.3f nm, cycle %.1f s",
              job.name.c_str(), r.report.machine.c_str(), f.points, f.revolutions,
              f.chord_max * 1e6, f.cycle_time);
  if (f.scheduled)
    std::printf(" (scheduled; at one constant speed, %.4g rpm, %.1f s)", f.dynamics.max_rpm,
                f.constant_rpm_cycle_time);
  if (f.held_points > 0) std::printf(", uncut at creases max %.1f nm", f.uncut_max * 1e6);
  std::printf("\n");
  for (const std::string& w : r.files) std::printf("  %s\n", w.c_str());
}

// Prints the verdict's reasons, one "UNSAFE: …" line each; true when the program is unsafe.
bool say_unsafe(const RunReport& r, std::FILE* out = stderr) {
  for (const std::string& u : r.unsafe_reasons()) std::fprintf(out, "UNSAFE: %s\n", u.c_str());
  return !r.safe();
}

}  // namespace

int run_run(const RunArgs& args) {
  const Job job = load_job(args.job, yaml_byte_bound());
  RunOptions options = run_options(args.output);
  options.threads = args.threads;
  if (args.simulate) {
    options.simulation = SimulationOptions{};
    options.simulation->threads = args.threads;
  }
  Observer observer(args.quiet);
  const RunResult r = run_job(job, options, &observer);
  if (!args.quiet) print_summary(job, r);
  // Written, because the job downgraded a check or turned the limits off; not safe to cut.
  return say_unsafe(r.report) ? kExitCheckFailed : kExitOk;
}

int run_simulate(const SimulateArgs& args) {
  if (args.columns % 2) throw InputError("--columns", "must be even (each angle has its opposite), not " + std::to_string(args.columns));
  SimulationOptions simulation;
  simulation.radial_step = args.radial_step;
  simulation.columns = args.columns;
  simulation.threads = args.threads;
  const Job job = load_job(args.job, yaml_byte_bound());
  Observer observer(args.quiet);
  RunOptions options = run_options(args.output);
  options.threads = args.threads;
  const RunReport r = args.program.empty()
                          ? simulate_job(job, simulation, options, &observer).report
                          : simulate_program(job, args.program, simulation, options).report;
  const SimulationResult& s = *r.simulation;
  std::printf(
      "%s: simulated form error PV %.3f nm, RMS %.3f nm (max %+.3f nm at r = %.4f mm, min %+.3f nm "
      "at r = %.4f mm); %ld cells not reached\n",
      job.name.c_str(), s.pv * 1e6, s.rms * 1e6, s.max * 1e6, s.max_r, s.min * 1e6, s.min_r,
      s.uncut);
  const double ratio = s.pv > 0 ? s.predicted.pv() / s.pv : 0;
  if (args.program.empty())  // a program from elsewhere comes with no prediction
    std::printf(
        "  the planner predicted PV %.3f nm (max %+.3f, min %+.3f nm): %.3f× the simulation, %s\n",
        s.predicted.pv() * 1e6, s.predicted.max() * 1e6, s.predicted.min() * 1e6, ratio,
        prediction_bound_text(ratio));
  if (r.form_error) {
    const FormErrorSplit& e = *r.form_error;
    std::printf("  figure (the residual's mean over a pitch) PV %.3f nm, RMS %.3f nm; finish "
                "(the cusps) PV %.3f nm%s\n",
                e.figure_pv * 1e6, e.figure_rms * 1e6, e.finish_pv * 1e6,
                e.resolved ? "" : " (the grid is coarser than a third of the pitch: not resolved)");
  }
  for (const ResidualPlace& p : s.worst) {
    std::string cause = to_string(p.cause);
    std::replace(cause.begin(), cause.end(), '_', ' ');
    std::printf("  worst: %+.3f nm at r = %.4f mm, θ = %.2f° (%s)\n", p.residual * 1e6, p.r,
                p.phi * 180 / std::numbers::pi, cause.c_str());
  }
  // A program from elsewhere: what its reading could not judge (its dynamics, with no block
  // times this reader knows).
  if (!args.program.empty() && !args.quiet)
    for (const ReportWarning& w : r.warnings)
      if (w.severity != ReportWarning::Severity::kUnsafe)
        std::printf("note: %s\n", warning_line(w).c_str());
  return say_unsafe(r) ? kExitCheckFailed : kExitOk;
}

int run_check(const CheckArgs& args) {
  // Bad input (the job, the machine, the plugin) is exit 2; a job that would fail is 1.
  const Job job = load_job(args.job, yaml_byte_bound());
  try {
    Observer observer(true);
    RunOptions options = run_options("");
    options.threads = args.threads;
    const RunReport r = check_job(job, options, &observer);
    const PassFigures& f = r.passes.back();
    if (say_unsafe(r, stdout)) return kExitCheckFailed;
    std::printf(
        "PASS: %s on %s: %ld points, chord error max %.3f nm, highest rpm %.4g%s\n",
        job.name.c_str(), r.machine.c_str(), f.points, f.chord_max * 1e6, f.dynamics.max_rpm,
        r.alpha_max_deg >= 0 ? (", α_max " + std::to_string(r.alpha_max_deg) + "°").c_str() : "");
    if (!args.quiet)
      for (const std::string& w : r.messages()) std::printf("warning: %s\n", w.c_str());
    return kExitOk;
  } catch (const CheckFailure& e) {
    // A check the program would fail: exit 1. Bad input found while planning is exit 2,
    // as in `run`.
    std::printf("FAIL: %s\n", e.what());
    return kExitCheckFailed;
  }
}

}  // namespace freeturn::cli
