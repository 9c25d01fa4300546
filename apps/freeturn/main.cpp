// freeturn: YAML job in, NC program out. This file dispatches subcommands.

#include <signal.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "freeturn/freeturn.hpp"
#include "freeturn/io/atomic_file.hpp"

namespace {

// SIGTERM (a job scheduler, `timeout`) or SIGINT (Ctrl-C) mid-run: the outputs not yet
// committed are removed, as an error would remove them, and the signal then ends the
// process as it would have (its exit status says so). Async-signal-safe: unlink, signal,
// raise.
extern "C" void end_on_signal(int number) {
  freeturn::AtomicFile::remove_all_temporaries();
  ::signal(number, SIG_DFL);
  ::raise(number);
}

// A finite number in [lo, hi]. CLI11's Range lets NaN through (every comparison with it is
// false): --tolerance nan had made ncdiff call any two programs the same, exit 0.
CLI::Validator finite_in(double lo, double hi) {
  const auto text_of = [](double v) {
    char buf[32];
    const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, error == std::errc() ? end : buf);
  };
  const std::string range = "[" + text_of(lo) + ", " + text_of(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double v = 0;
        const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
        const char* last = text.data() + text.size();
        const auto [end, error] = std::from_chars(first, last, v);
        if (first == last || error != std::errc() || end != last || !std::isfinite(v) || v < lo ||
            v > hi)
          return "must be a finite number in " + range + ", not '" + text + "'";
        return {};
      },
      "FLOAT in " + range);
}

void remove_outputs_on_termination() {
  struct sigaction action {};
  action.sa_handler = end_on_signal;
  sigemptyset(&action.sa_mask);
  for (const int number : {SIGTERM, SIGINT, SIGHUP}) {
    // A signal the caller ignores (a shell's background job ignores SIGINT) stays ignored.
    struct sigaction current {};
    if (sigaction(number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaction(number, &action, nullptr);
  }
}

// Runs a subcommand, turning its errors into the exit codes the README lists.
template <class F>
int guarded(const char* name, F&& run) {
  try {
    return run();
  } catch (const freeturn::CheckFailure& e) {
    // A check set to error stopped the run before anything was written.
    std::fprintf(stderr, "FAIL: %s\n", e.what());
    return freeturn::cli::kExitCheckFailed;
  } catch (const freeturn::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return freeturn::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "freeturn %s: internal error: %s\n", name, e.what());
    return freeturn::cli::kExitBadInput;
  }
}

constexpr const char* kExitCodes =
    "exit codes: 0 ok, 1 a check failed or files differ, 2 bad input or usage,\n"
    "3 a post-processor plugin crashed or hung (nothing written)";

}  // namespace

int main(int argc, char** argv) {
  using namespace freeturn::cli;
  remove_outputs_on_termination();
  // A plugin that crashes or hangs: the library's default fault handler is the command
  // line's behaviour (its message on stderr, exit 3; post/plugin_watch.hpp), so none is set.

  CLI::App app(std::string("freeturn ") + freeturn::kVersion +
               ": CAM for ultraprecision diamond turning of optical surfaces");
  app.set_version_flag("-V,--version", std::string("freeturn ") + freeturn::kVersion);
  app.require_subcommand(1, 1);
  app.footer(std::string("'freeturn <command> --help' shows a command's options.\n") + kExitCodes);
  int code = kExitOk;
  const auto job_option = [](CLI::App* c, std::string& job) {
    c->add_option("job", job, "the job file (YAML: docs/job-schema.md)")->required();
  };
  const auto output_option = [](CLI::App* c, std::string& output) {
    c->add_option("-o,--output", output, "the folder to write into")->capture_default_str();
  };
  // Threads that plan the spiral (and simulate): the outputs are the same on any number.
  const auto threads_option = [](CLI::App* c, int& threads) {
    c->add_option("--threads", threads,
                  "threads that plan the spiral (and simulate); the outputs are the same on any "
                  "number [default: one per core]")
        ->check(CLI::Range(1, freeturn::kMaxThreads));
  };
  const auto quiet_flag = [](CLI::App* c, bool& quiet) {
    c->add_flag("-q,--quiet", quiet, "print only errors and the verdict's reasons");
  };

  RunArgs run;
  CLI::App* run_app = app.add_subcommand(
      "run", "plan, compensate, check and post a job: NC programs, CL data and a report");
  job_option(run_app, run.job);
  output_option(run_app, run.output);
  quiet_flag(run_app, run.quiet);
  run_app->add_flag("--simulate", run.simulate, "also cut the finishing pass in simulation (docs/verify.md)");
  threads_option(run_app, run.threads);
  run_app->callback([&] { code = guarded("run", [&] { return run_run(run); }); });

  CheckArgs check;
  CLI::App* check_app = app.add_subcommand(
      "check", "everything run does but writing: tool checks, machine limits, dynamics; a verdict");
  job_option(check_app, check.job);
  quiet_flag(check_app, check.quiet);
  threads_option(check_app, check.threads);
  check_app->callback([&] { code = guarded("check", [&] { return run_check(check); }); });

  SimulateArgs simulate;
  CLI::App* simulate_app = app.add_subcommand(
      "simulate", "run a job and simulate its finishing cut: the form error before cutting");
  job_option(simulate_app, simulate.job);
  output_option(simulate_app, simulate.output);
  quiet_flag(simulate_app, simulate.quiet);
  simulate_app
      ->add_option("--radial-step", simulate.radial_step,
                   "mm between the grid's radii (0: an eighth of the pitch)")
      ->check(finite_in(0.0, 10.0))
      ->capture_default_str();
  simulate_app->add_option("--columns", simulate.columns, "angles of the grid over a turn (even)")
      ->check(CLI::Range(2, 1'000'000))->capture_default_str();
  threads_option(simulate_app, simulate.threads);
  simulate_app->add_option("--program", simulate.program,
                           "an NC program for the job's machine (from freeturn or another CAM) "
                           "to simulate instead of the job's own: nothing is planned");
  simulate_app->callback([&] { code = guarded("simulate", [&] { return run_simulate(simulate); }); });

  SampleArgs sample;
  CLI::App* sample_app = app.add_subcommand(
      "sample", "evaluate a job's design surface over its aperture and write it as CSV");
  job_option(sample_app, sample.job);
  output_option(sample_app, sample.output);
  quiet_flag(sample_app, sample.quiet);
  sample_app->add_option("--grid", sample.grid, "points along each side of the square grid")
      ->check(CLI::Range(2, 20001))->capture_default_str();
  sample_app->callback([&] { code = guarded("sample", [&] { return run_sample(sample); }); });

  NcDiffArgs ncdiff;
  CLI::App* ncdiff_app = app.add_subcommand(
      "ncdiff", "compare two NC programs by value (axis words, codes), ignoring formatting");
  ncdiff_app->add_option("a", ncdiff.a, "the first program")->required();
  ncdiff_app->add_option("b", ncdiff.b, "the second program")->required();
  ncdiff_app
      ->add_option("--tolerance", ncdiff.tolerance,
                   "the largest axis difference taken as equal (mm or degrees)")
      ->check(finite_in(0.0, 1e6))
      ->capture_default_str();
  quiet_flag(ncdiff_app, ncdiff.quiet);
  ncdiff_app->callback([&] { code = guarded("ncdiff", [&] { return run_ncdiff(ncdiff); }); });

  PluginsArgs plugins;
  CLI::App* plugins_app =
      app.add_subcommand("plugins", "list the post-processors found and the machines that use them");
  quiet_flag(plugins_app, plugins.quiet);
  plugins_app->callback([&] { code = guarded("plugins", [&] { return run_plugins(plugins); }); });

  if (argc < 2) {
    std::fprintf(stderr, "%s", app.help().c_str());
    return kExitBadInput;
  }
  // A first word that names no command and is no option: said plainly.
  const std::string first = argv[1];
  const auto commands = app.get_subcommands([](const CLI::App*) { return true; });
  const bool known = std::any_of(commands.begin(), commands.end(),
                                 [&](const CLI::App* c) { return c->get_name() == first; });
  if (!first.empty() && first[0] != '-' && !known) {
    std::fprintf(stderr, "freeturn: unknown command '%s' (see freeturn --help)\n", first.c_str());
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const CLI::App* command = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
    std::fprintf(stderr, "freeturn%s%s: %s (see freeturn%s%s --help)\n", command ? " " : "",
                 command ? command->get_name().c_str() : "", e.what(), command ? " " : "",
                 command ? command->get_name().c_str() : "");
    return kExitBadInput;
  }
  return code;
}
