#pragma once
// A file that appears under its final name only when complete: bytes go to a temporary
// file beside it, and commit() flushes, syncs and renames it into place. If the writer
// is destroyed without commit (an error, an exception), the temporary is removed and
// whatever was at the final name before is untouched.

#include <cstdio>
#include <string>
#include <string_view>

namespace freeturn {

class AtomicFile {
 public:
  // Opens "<path>.tmp-<pid>" for writing, first removing temporaries of the same path
  // whose process is gone (a killed run's). Throws InputError if it cannot.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view bytes);
  // Flushes, fsyncs and renames to the final path, then fsyncs the folder so the rename
  // survives a power loss. Throws InputError on an I/O failure (the temporary is removed,
  // the final name untouched). Equivalent to sync() then publish().
  void commit();
  // The two halves of commit(), for a set of files that must all be on disk before any
  // of them takes its final name (io/output_set.hpp). sync() flushes, fsyncs and closes
  // the temporary; publish() renames it and fsyncs the folder. Each throws InputError.
  void sync();
  void publish();

  const std::string& path() const { return path_; }

  // Removes the temporary of every AtomicFile not yet committed or destroyed. For a
  // process about to end abnormally (a post-processor plugin that crashed or hung):
  // async-signal-safe, it only unlinks.
  static void remove_all_temporaries() noexcept;

 private:
  int slot_ = -1;  // in the registry remove_all_temporaries() reads
  std::string path_;
  std::string temp_path_;
  // Removes the temporary and frees its registry slot: the file will not be published.
  void discard_temporary() noexcept;

  std::FILE* file_ = nullptr;
  bool synced_ = false;  // closed and on disk, not yet renamed
};

// Removes the files "<path><marker><pid>" beside `path` whose process is gone (a killed
// run's), and this process's own when `include_own`.
void remove_files_of_ended_runs(const std::string& path, const std::string& marker,
                                bool include_own);

// fsyncs the folder holding `path`, so that a rename into it survives a power loss.
// Best effort: a folder that cannot be opened or synced is left as it is.
void sync_folder_of(const std::string& path);

}  // namespace freeturn
