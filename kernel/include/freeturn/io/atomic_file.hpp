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
  // Opens "<path>.tmp-<pid>" for writing. Throws InputError if it cannot.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view bytes);
  // Flushes, fsyncs and renames to the final path. Throws InputError on an I/O failure.
  void commit();

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
};

}  // namespace freeturn
