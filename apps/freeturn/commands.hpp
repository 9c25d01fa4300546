#pragma once
// The freeturn command's subcommands. Each takes its arguments (after the subcommand
// name) and returns the process exit code: 0 ok, 1 a check failed or files differ,
// 2 bad input or usage. Errors go to stderr. (A plugin that crashes or hangs ends the
// process with kExitPluginFault, 3: plugins/plugin_watch.hpp.)

#include <string>
#include <vector>

namespace freeturn::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;

struct Command {
  const char* name;
  const char* summary;
  const char* usage;
  int (*run)(const std::vector<std::string>& args);
};

int run_sample(const std::vector<std::string>& args);
int run_run(const std::vector<std::string>& args);
int run_check(const std::vector<std::string>& args);
int run_simulate(const std::vector<std::string>& args);
int run_ncdiff(const std::vector<std::string>& args);
int run_plugins(const std::vector<std::string>& args);

}  // namespace freeturn::cli
