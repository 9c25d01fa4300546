#pragma once
// A main program and the child files it calls, put in place as one set.
//
// Files are renamed one at a time, so a run killed while committing a set could leave
// the earlier main program beside new child files: a program that loads, runs, and cuts
// the new points from the old program's start. commit_program_set() never lets that be:
//   1. every file is synced to disk first (an I/O error stops here, nothing renamed);
//   2. an earlier main program is renamed aside to "<main>.replaced-<pid>";
//   3. the children take their final names, then the main program takes its own;
//   4. the set-aside program (and any a killed run left) is removed.
// Killed between 2 and 3, the folder holds no main program under its name: nothing an
// operator can load calls a child it was not written with. The earlier program is kept,
// whole, under its ".replaced-" name until a run of the same job completes.

#include <string>
#include <vector>

#include "freeturn/io/atomic_file.hpp"

namespace freeturn {

// files      the main program, then its children, all written and not yet committed.
// after_step called after each rename, for tests that kill the process there:
//            step 0 after the earlier main program is set aside (only when there was
//            one), steps 1..#children after each child, #files after the main program.
// Throws InputError if a file cannot be synced or renamed; if that happens after step 0
// the message says where the earlier main program now is.
void commit_program_set(const std::vector<AtomicFile*>& files,
                        void (*after_step)(int step) = nullptr);

// "<main>.replaced-<pid>": where commit_program_set() sets an earlier main program aside.
std::string replaced_program_path(const std::string& main_path, long pid);

}  // namespace freeturn
