#pragma once
// The freeturn command's subcommands, each with its parsed options (main.cpp declares them
// to CLI11 with their help, defaults and units). Each returns the process exit code: 0 ok,
// 1 a check failed or files differ, 2 bad input or usage. Errors go to stderr. (A plugin
// that crashes or hangs ends the process with kExitPluginFault, 3: post/plugin_watch.hpp.)

#include <string>

namespace freeturn::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;

struct RunArgs {
  std::string job;
  std::string output = ".";
  bool quiet = false;
  bool simulate = false;
  int threads = 0;  // that plan and simulate (0: the machine's cores)
};

struct CheckArgs {
  std::string job;
  bool quiet = false;
  int threads = 0;  // that plan (0: the machine's cores)
};

struct SimulateArgs {
  std::string job;
  std::string output = ".";
  bool quiet = false;
  double radial_step = 0;  // mm (0: an eighth of the pitch)
  int columns = 360;
  int threads = 0;
  std::string program;  // an NC program to simulate instead of the job's own
};

struct SampleArgs {
  std::string job;
  std::string output = ".";
  bool quiet = false;
  int grid = 201;
};

struct NcDiffArgs {
  std::string a, b;
  double tolerance = 1e-9;  // mm or degrees
  bool quiet = false;
};

struct PluginsArgs {
  bool quiet = false;
};

int run_run(const RunArgs& args);
int run_check(const CheckArgs& args);
int run_simulate(const SimulateArgs& args);
int run_sample(const SampleArgs& args);
int run_ncdiff(const NcDiffArgs& args);
int run_plugins(const PluginsArgs& args);

}  // namespace freeturn::cli
