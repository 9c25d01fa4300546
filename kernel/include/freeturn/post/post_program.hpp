#pragma once
// One NC program being written by a post-processor plugin: axis records in, the plugin's
// text out through AtomicFiles (the main program and any child files it opens), all
// committed together by finish(), or handed to a run's OutputSet. Destroyed without
// finish() (an error anywhere in the pipeline), it leaves no file behind.
//
// Everything crosses NcGuard both ways (records before the plugin sees them, text after
// it wrote them), every plugin call runs under PluginWatch (a crash or hang ends the run
// with the plugin's name and no output), and a program past max_file_bytes (its files
// together) is refused.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeturn/io/atomic_file.hpp"
#include "freeturn/io/output_set.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/machine/machine.hpp"
#include "freeturn/post/nc_guard.hpp"
#include "freeturn/post/plugin_watch.hpp"
#include "freeturn/post/post_loader.hpp"

namespace freeturn {

struct ProgramSettings {
  std::string name;  // the job's name
  double spindle_rpm = 0, feed = 0;
  long long block_count = -1;     // −1 when not known in advance
  long long max_file_bytes = -1;  // a program (its files together) growing past this is refused (−1: no limit)
  // The clearance base handed to the plugin (post_plugin.h, top_z): a bound on every
  // block's machine Z on the side z_away points to; a block past it is refused.
  double top_z = 0;
  int z_away = 1;
};

class PostProgram final : public AxisSink {
 public:
  // Throws InputError with the plugin's message when it refuses the program. An empty
  // `path` writes no file: the text still crosses the guard and the size limit, and is
  // dropped (`freeturn check` refuses what `run` would, without writing).
  PostProgram(const PostPlugin& plugin, const MachineDescription& machine,
              const ProgramSettings& settings, const std::string& path);
  ~PostProgram() override;

  void write(std::span<const AxisRecord> chunk) override;
  // Ends the program and puts its files in place as one set (io/output_set.hpp). Returns
  // the paths written.
  std::vector<std::string> finish();
  // Ends the program and hands its files to `outputs` (the main program as a program,
  // its children as data), to be committed with the rest of a run.
  void finish(OutputSet& outputs);

 private:
  static int write_bytes(void* context, const char* data, size_t size);
  static int open_file(void* context, const char* name);
  static int select_main(void* context);
  [[noreturn]] void fail(const char* stage) const;
  // After a plugin call: what the guard or the size limit refused, as an InputError.
  void check_output(const char* stage);

  const PostPlugin& plugin_;
  MachineDescription machine_;
  ProgramSettings settings_;
  ft_program_info info_{};
  ft_writer writer_{};
  void* handle_ = nullptr;
  std::string folder_;
  std::vector<std::unique_ptr<AtomicFile>> files_;  // [0] is the main program; null when dropped
  AtomicFile* current_ = nullptr;
  bool dropped_ = false;  // no file is written (an empty path)
  bool open_ = true;      // false once finish() handed the files over
  std::string main_name_;
  std::vector<ft_block> blocks_;
  char error_[512] = {0};
  NcGuard guard_;
  PluginWatch watch_;
  std::string refused_;  // the size limit's refusal, raised after the call
  long long blocks_written_ = 0;
  long long program_bytes_ = 0;  // over all its files
};

// The machine file for a name (on the machine search path) or a path (absolute, or with
// a '/' or ".yaml": used as it is). Throws InputError listing where it looked.
std::string find_machine_file(const std::string& name_or_path);

}  // namespace freeturn
