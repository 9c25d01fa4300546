#pragma once
// Every file of a run, put in place as one set.
//
// A rename is atomic one file at a time; a set of them is not. Committed one by one, a
// run killed midway could leave an earlier main program beside new child files (a program
// that loads, runs and cuts the new points from the old program's start), or a new
// program beside the report of an earlier one. OutputSet orders the renames so that no
// moment leaves a main program an operator can load beside files it was not written with:
//   1. every file is synced to disk (an I/O error stops here, nothing renamed);
//   2. each program already at its final name is renamed aside, whole, to
//      "<name>.replaced-<pid>";
//   3. the data files (child point files, CL data, report, meshes) take their names;
//   4. the programs take theirs;
//   5. the set-aside programs, and any a killed run left (its process gone), are removed.
// Killed anywhere, each main program on disk is either absent (the earlier one kept whole
// under its ".replaced-" name until a run completes) or the new one, and then every data
// file is new as well. A set of one file is a single rename.

#include <memory>
#include <string>
#include <vector>

#include "freeturn/io/atomic_file.hpp"

namespace freeturn {

class OutputSet {
 public:
  // kProgram: an NC main program, the file an operator loads (set aside, renamed last).
  // kData: anything a program calls or that describes it.
  enum class Role { kData, kProgram };

  // A new file of the set (opens its temporary; throws InputError if it cannot).
  AtomicFile& add(std::string path, Role role = Role::kData);
  // A file written elsewhere, not yet committed.
  void adopt(std::unique_ptr<AtomicFile> file, Role role);

  // Puts every file in place as above and returns their paths in the order added.
  // after_step, for tests that kill the process there, is called after each rename:
  // steps 0..#set-aside−1 set programs aside, then one per data file, then one per
  // program. Throws InputError, before anything is renamed, if two files share a name;
  // then if a file cannot be synced or renamed, past step 2 saying where the earlier
  // programs are.
  std::vector<std::string> commit(void (*after_step)(int step) = nullptr);

  bool empty() const { return entries_.empty(); }

 private:
  struct Entry {
    std::unique_ptr<AtomicFile> file;
    Role role;
  };
  std::vector<Entry> entries_;
};

// "<path>.replaced-<pid>": where OutputSet::commit() sets an earlier program aside.
std::string replaced_program_path(const std::string& path, long pid);

}  // namespace freeturn
