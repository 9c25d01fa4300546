// freeturn: YAML job in, NC program out. This file dispatches subcommands.

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "commands.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/core/version.hpp"
#include "freeturn/io/atomic_file.hpp"
#include "freeturn/post/plugin_watch.hpp"

namespace {

using freeturn::cli::Command;

const Command kCommands[] = {
    {"run", "plan, compensate and post a job: NC programs, CL data and a report",
     "freeturn run JOB.yaml [-o DIR] [--quiet] [--simulate] [--threads N]", freeturn::cli::run_run},
    {"check", "everything run does but writing: tool checks, machine limits, dynamics; a verdict",
     "freeturn check JOB.yaml", freeturn::cli::run_check},
    {"simulate", "run a job and simulate its finishing cut: the form error before cutting",
     "freeturn simulate JOB.yaml [-o DIR] [--radial-step MM] [--columns N] [--threads N]", freeturn::cli::run_simulate},
    {"sample", "evaluate a job's design surface over its aperture and write it as CSV",
     "freeturn sample JOB.yaml [-o DIR] [--grid N]", freeturn::cli::run_sample},
    {"ncdiff", "compare two NC programs by value (axis words, codes), ignoring formatting",
     "freeturn ncdiff A.nc B.nc [--tolerance T]", freeturn::cli::run_ncdiff},
    {"plugins", "list the post-processors found and the machines that use them",
     "freeturn plugins", freeturn::cli::run_plugins},
};

void print_help(std::FILE* out) {
  std::fprintf(out,
               "freeturn %s: CAM for ultraprecision diamond turning of optical surfaces\n\n"
               "usage: freeturn [--help | --version] <command> [args]\n\ncommands:\n",
               freeturn::kVersion);
  for (const Command& c : kCommands) std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
  std::fprintf(out,
               "\n'freeturn <command> --help' shows a command's usage.\n"
               "exit codes: 0 ok, 1 a check failed or files differ, 2 bad input or usage,\n"
               "3 a post-processor plugin crashed or hung (nothing written)\n");
}

// A plugin that crashed or hung (post/plugin_watch.hpp): its message on stderr, exit 3.
// The library has removed the run's temporaries already. Async-signal-safe: write, _exit.
void end_on_plugin_fault(const char* message) {
  std::size_t left = std::strlen(message);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, message, left);
    if (n <= 0) break;
    message += n;
    left -= static_cast<std::size_t>(n);
  }
  ::_exit(freeturn::kExitPluginFault);
}

// SIGTERM (a job scheduler, `timeout`) or SIGINT (Ctrl-C) mid-run: the outputs not yet
// committed are removed, as an error would remove them, and the signal then ends the
// process as it would have (its exit status says so). Async-signal-safe: unlink, signal,
// raise.
extern "C" void end_on_signal(int number) {
  freeturn::AtomicFile::remove_all_temporaries();
  ::signal(number, SIG_DFL);
  ::raise(number);
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

}  // namespace

int main(int argc, char** argv) {
  remove_outputs_on_termination();
  freeturn::set_plugin_fault_handler(end_on_plugin_fault);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_help(stderr);
    return freeturn::cli::kExitBadInput;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_help(stdout);
    return freeturn::cli::kExitOk;
  }
  if (args[0] == "--version") {
    std::printf("freeturn %s\n", freeturn::kVersion);
    return freeturn::cli::kExitOk;
  }
  for (const Command& c : kCommands) {
    if (args[0] != c.name) continue;
    std::vector<std::string> rest(args.begin() + 1, args.end());
    if (!rest.empty() && (rest[0] == "--help" || rest[0] == "-h")) {
      std::printf("usage: %s\n%s\n", c.usage, c.summary);
      return freeturn::cli::kExitOk;
    }
    try {
      return c.run(rest);
    } catch (const freeturn::CheckFailure& e) {
      // A check set to error stopped the run before anything was written.
      std::fprintf(stderr, "FAIL: %s\n", e.what());
      return freeturn::cli::kExitCheckFailed;
    } catch (const freeturn::InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return freeturn::cli::kExitBadInput;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "freeturn %s: internal error: %s\n", c.name, e.what());
      return freeturn::cli::kExitBadInput;
    }
  }
  std::fprintf(stderr, "freeturn: unknown command '%s' (see freeturn --help)\n", args[0].c_str());
  return freeturn::cli::kExitBadInput;
}
