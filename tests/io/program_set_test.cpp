#include "freeturn/io/program_set.hpp"

#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "test_files.hpp"

using freeturn::AtomicFile;
using freeturn::commit_program_set;
using freeturn::replaced_program_path;
using freeturn::test::read_file;
using freeturn::test::TempDir;

namespace {

const char* const kNames[] = {"part.nc", "part_001.nc", "part_002.nc"};

// An earlier program set: each file says which set it belongs to.
void write_set(const TempDir& dir, const std::string& tag) {
  for (const char* name : kNames) dir.write(name, tag + " " + name + "\n");
}

// Writes the new set through AtomicFiles and commits it, the hook deciding where to stop.
void commit_new_set(const TempDir& dir, void (*after_step)(int)) {
  std::vector<std::unique_ptr<AtomicFile>> files;
  std::vector<AtomicFile*> set;
  for (const char* name : kNames) {
    files.push_back(std::make_unique<AtomicFile>(dir.file(name)));
    files.back()->write(std::string("NEW ") + name + "\n");
    set.push_back(files.back().get());
  }
  commit_program_set(set, after_step);
}

int g_kill_step = -1;
void kill_at_step(int step) {
  if (step == g_kill_step) ::raise(SIGKILL);
}

// Runs commit_new_set in a child process that SIGKILLs itself right after `step`;
// returns the child's pid (it is gone by then).
pid_t killed_commit(const TempDir& dir, int step) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    g_kill_step = step;
    try {
      commit_new_set(dir, kill_at_step);
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGKILL);
  return pid;
}

std::size_t count_files(const TempDir& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir.path()),
                                                std::filesystem::directory_iterator()));
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE(
      "a program set killed after any rename never leaves a loadable main program with another "
      "set's children") {
    // Steps: 0 earlier main set aside, 1 and 2 the children, 3 the main program.
    for (int step = 0; step <= 3; ++step) {
      CAPTURE(step);
      TempDir dir;
      write_set(dir, "OLD");
      const pid_t pid = killed_commit(dir, step);
      const std::string main = dir.file("part.nc");
      if (step < 3) {
        // No main program an operator could load; the earlier one is whole, set aside.
        CHECK_FALSE(std::filesystem::exists(main));
        CHECK(read_file(replaced_program_path(main, pid)) == "OLD part.nc\n");
        CHECK(read_file(dir.file("part_001.nc")) ==
              (step >= 1 ? "NEW" : "OLD") + std::string(" part_001.nc\n"));
        CHECK(read_file(dir.file("part_002.nc")) ==
              (step >= 2 ? "NEW" : "OLD") + std::string(" part_002.nc\n"));
      } else {
        for (const char* name : kNames)
          CHECK(read_file(dir.file(name)) == std::string("NEW ") + name + "\n");
      }
      // The next run of the job completes the set and removes what the killed one left.
      commit_new_set(dir, nullptr);
      for (const char* name : kNames)
        CHECK(read_file(dir.file(name)) == std::string("NEW ") + name + "\n");
      CHECK(count_files(dir) == 3);
    }
  }

  TEST_CASE(
      "a program set with no earlier main program is renamed without setting anything aside") {
    TempDir dir;
    static std::vector<int> steps;
    steps.clear();
    commit_new_set(dir, [](int step) { steps.push_back(step); });
    CHECK(steps == std::vector<int>{1, 2, 3});
    CHECK(count_files(dir) == 3);
    CHECK(read_file(dir.file("part.nc")) == "NEW part.nc\n");
  }

  TEST_CASE(
      "a child that cannot take its name stops the set, and the error says where the earlier "
      "program is") {
    TempDir dir;
    write_set(dir, "OLD");
    // A non-empty folder under the second child's name: rename(2) cannot replace it.
    std::filesystem::remove(dir.file("part_002.nc"));
    std::filesystem::create_directory(dir.file("part_002.nc"));
    dir.write("part_002.nc/x", "x");
    std::string message;
    try {
      commit_new_set(dir, nullptr);
    } catch (const freeturn::InputError& e) {
      message = e.what();
    }
    const std::string aside = replaced_program_path(dir.file("part.nc"), ::getpid());
    CHECK(message.find("part_002.nc") != std::string::npos);
    CHECK(message.find(aside) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("part.nc")));
    CHECK(read_file(aside) == "OLD part.nc\n");
    // Nothing of the failed set is left as a temporary.
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
  }

  TEST_CASE("a single file needs no set-aside: it is replaced in one rename") {
    TempDir dir;
    dir.write("one.nc", "OLD\n");
    AtomicFile f(dir.file("one.nc"));
    f.write("NEW\n");
    static std::vector<int> steps;
    steps.clear();
    commit_program_set({&f}, [](int step) { steps.push_back(step); });
    CHECK(steps == std::vector<int>{1});
    CHECK(read_file(dir.file("one.nc")) == "NEW\n");
    CHECK(count_files(dir) == 1);
  }
}
