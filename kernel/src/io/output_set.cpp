#include "freeturn/io/output_set.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>

#include "freeturn/core/error.hpp"

namespace freeturn {

std::string replaced_program_path(const std::string& path, long pid) {
  return path + ".replaced-" + std::to_string(pid);
}

AtomicFile& OutputSet::add(std::string path, Role role) {
  entries_.push_back({std::make_unique<AtomicFile>(std::move(path)), role});
  return *entries_.back().file;
}

void OutputSet::adopt(std::unique_ptr<AtomicFile> file, Role role) {
  entries_.push_back({std::move(file), role});
}

std::vector<std::string> OutputSet::commit(void (*after_step)(int step)) {
  std::vector<std::string> paths;
  for (const Entry& e : entries_) paths.push_back(e.file->path());
  // Two outputs under one name (a plugin naming a child after another file) shared one
  // temporary: neither can be trusted, and nothing may be renamed.
  std::set<std::string> names;
  for (const std::string& p : paths)
    if (!names.insert(std::filesystem::path(p).lexically_normal().string()).second)
      throw InputError(p, "two outputs of this run have this name; nothing was written");
  for (const Entry& e : entries_) e.file->sync();
  int step = 0;
  const auto done = [&] {
    if (after_step) after_step(step);
    ++step;
  };
  // A set of one file is replaced in one atomic rename: nothing to set aside.
  const bool set_programs_aside = entries_.size() > 1;
  const long pid = static_cast<long>(::getpid());
  std::string set_aside;  // for the message if a rename fails later
  for (const Entry& e : entries_) {
    if (!set_programs_aside || e.role != Role::kProgram) continue;
    std::error_code ec;
    if (!std::filesystem::exists(e.file->path(), ec)) continue;
    const std::string aside = replaced_program_path(e.file->path(), pid);
    if (std::rename(e.file->path().c_str(), aside.c_str()) != 0)
      throw InputError(e.file->path(),
                       std::string("could not set the earlier program aside: ") +
                           std::strerror(errno) +
                           (set_aside.empty() ? "" : "\n(set aside before it:" + set_aside + ")"));
    sync_folder_of(aside);
    set_aside += "\n  " + aside;
    done();
  }
  try {
    for (const Role role : {Role::kData, Role::kProgram})
      for (const Entry& e : entries_)
        if (e.role == role) {
          e.file->publish();
          done();
        }
  } catch (const InputError& e) {
    if (set_aside.empty()) throw;
    throw InputError(e.where(), e.problem() + "\n(the earlier programs are kept as:" + set_aside +
                                    "\nsome files they call may already be replaced)");
  }
  for (const Entry& e : entries_)
    if (e.role == Role::kProgram) remove_files_of_ended_runs(e.file->path(), ".replaced-", true);
  entries_.clear();
  return paths;
}

}  // namespace freeturn
