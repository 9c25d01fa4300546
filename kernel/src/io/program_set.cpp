#include "freeturn/io/program_set.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "freeturn/core/error.hpp"

namespace freeturn {

namespace {

// Set-aside main programs of this path whose run is over: ours, once the new set is in
// place, and those of runs that were killed.
void remove_replaced_programs(const std::string& main_path) {
  remove_files_of_ended_runs(main_path, ".replaced-", true);
}

}  // namespace

std::string replaced_program_path(const std::string& main_path, long pid) {
  return main_path + ".replaced-" + std::to_string(pid);
}

void commit_program_set(const std::vector<AtomicFile*>& files, void (*after_step)(int step)) {
  if (files.empty()) return;
  for (AtomicFile* f : files) f->sync();
  AtomicFile& main = *files.front();
  if (files.size() == 1) {
    main.publish();
    if (after_step) after_step(1);
    remove_replaced_programs(main.path());
    return;
  }
  const std::string aside = replaced_program_path(main.path(), static_cast<long>(::getpid()));
  std::error_code ec;
  const bool had_main = std::filesystem::exists(main.path(), ec);
  if (had_main) {
    if (std::rename(main.path().c_str(), aside.c_str()) != 0)
      throw InputError(main.path(), std::string("could not set the earlier program aside: ") +
                                        std::strerror(errno));
    sync_folder_of(main.path());
    if (after_step) after_step(0);
  }
  try {
    for (std::size_t k = 1; k < files.size(); ++k) {
      files[k]->publish();
      if (after_step) after_step(static_cast<int>(k));
    }
    main.publish();
    if (after_step) after_step(static_cast<int>(files.size()));
  } catch (const InputError& e) {
    if (!had_main) throw;
    throw InputError(e.where(), e.problem() + "\n(the earlier main program is kept as " + aside +
                                    "; its child files may already be replaced)");
  }
  remove_replaced_programs(main.path());
}

}  // namespace freeturn
