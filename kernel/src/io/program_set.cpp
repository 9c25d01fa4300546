#include "freeturn/io/program_set.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "freeturn/core/error.hpp"

namespace freeturn {

namespace {

// Set-aside main programs of this path whose run is over: ours, once the new set is in
// place, and those of runs that were killed (their process is gone).
void remove_replaced_programs(const std::string& main_path) {
  namespace fs = std::filesystem;
  const fs::path target(main_path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".replaced-";
  const pid_t self = ::getpid();
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == self || (::kill(pid, 0) == -1 && errno == ESRCH)) fs::remove(it->path(), ec);
  }
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
