#include "freeturn/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "freeturn/core/error.hpp"

namespace freeturn {

namespace {

// The temporaries in use, for remove_all_temporaries(): fixed slots, so that a signal
// handler can read them without allocating. A path that finds no free slot (or is too
// long) is not registered; the next run removes it as stale.
constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 1024;
char g_temporaries[kSlots][kPathMax];
std::atomic<bool> g_slot_used[kSlots];

int register_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int k = 0; k < kSlots; ++k) {
    bool expected = false;
    if (!g_slot_used[k].load(std::memory_order_relaxed) &&
        g_slot_used[k].compare_exchange_strong(expected, true)) {
      std::memcpy(g_temporaries[k], path.c_str(), path.size() + 1);
      return k;
    }
  }
  return -1;
}

void release_temporary(int slot) {
  if (slot >= 0) g_slot_used[slot].store(false);
}

}  // namespace

void remove_files_of_ended_runs(const std::string& path, const std::string& marker,
                                bool include_own) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + marker;
  const pid_t self = ::getpid();
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if ((include_own && pid == self) || (pid != self && ::kill(pid, 0) == -1 && errno == ESRCH))
      fs::remove(it->path(), ec);
  }
}

void sync_folder_of(const std::string& path) {
  const std::filesystem::path target(path);
  const std::string folder = target.has_parent_path() ? target.parent_path().string() : ".";
  // A rename is durable only once its folder is; failure here loses nothing written, so
  // it is not an error (some file systems refuse fsync on a folder).
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void AtomicFile::remove_all_temporaries() noexcept {
  for (int k = 0; k < kSlots; ++k)
    if (g_slot_used[k].load()) ::unlink(g_temporaries[k]);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // A SIGKILL gives a run no chance to remove its temporaries, so the next writer does.
  remove_files_of_ended_runs(path_, ".tmp-", false);
  temp_path_ = path_ + ".tmp-" + std::to_string(::getpid());
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (!file_) throw InputError(path_, std::string("cannot write: ") + std::strerror(errno));
  slot_ = register_temporary(temp_path_);
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  if (file_ || synced_) std::remove(temp_path_.c_str());
  release_temporary(slot_);
}

void AtomicFile::write(std::string_view bytes) {
  if (!file_) throw InputError(path_, "written to after it was completed");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw InputError(path_, std::string("write failed: ") + std::strerror(errno));
}

void AtomicFile::commit() {
  sync();
  publish();
}

void AtomicFile::sync() {
  if (!file_) return;  // already synced
  const bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  const int saved_errno = errno;
  const bool closed = std::fclose(file_) == 0;
  const int close_errno = errno;
  file_ = nullptr;
  if (!flushed || !closed) {
    discard_temporary();
    throw InputError(path_, std::string("could not complete the file: ") +
                                std::strerror(flushed ? close_errno : saved_errno));
  }
  synced_ = true;
}

void AtomicFile::publish() {
  if (!synced_) throw InputError(path_, "could not complete the file: it was not written whole");
  synced_ = false;
  const bool renamed = std::rename(temp_path_.c_str(), path_.c_str()) == 0;
  const int err = errno;
  if (!renamed) {
    discard_temporary();
    throw InputError(path_, std::string("could not complete the file: ") + std::strerror(err));
  }
  release_temporary(slot_);
  slot_ = -1;
  sync_folder_of(path_);
}

void AtomicFile::discard_temporary() noexcept {
  std::remove(temp_path_.c_str());
  release_temporary(slot_);
  slot_ = -1;
}

}  // namespace freeturn
