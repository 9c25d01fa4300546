#include "freeturn/io/output_set.hpp"

#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "test_files.hpp"

using freeturn::AtomicFile;
using freeturn::OutputSet;
using freeturn::replaced_program_path;
using freeturn::test::read_file;
using freeturn::test::TempDir;

namespace {

// A run's outputs: two programs (the first with two child files), and a report.
struct Output {
  const char* name;
  OutputSet::Role role;
};
const Output kOutputs[] = {
    {"part.nc", OutputSet::Role::kProgram},  {"part_001.nc", OutputSet::Role::kData},
    {"part_002.nc", OutputSet::Role::kData}, {"part.rough-1.nc", OutputSet::Role::kProgram},
    {"report.json", OutputSet::Role::kData},
};
constexpr int kPrograms = 2, kData = 3;

// An earlier run's outputs: each file says which run wrote it.
void write_old_run(const TempDir& dir) {
  for (const Output& o : kOutputs) dir.write(o.name, std::string("OLD ") + o.name + "\n");
}

std::vector<std::string> commit_new_run(const TempDir& dir, void (*after_step)(int)) {
  OutputSet outputs;
  for (const Output& o : kOutputs)
    outputs.add(dir.file(o.name), o.role).write(std::string("NEW ") + o.name + "\n");
  return outputs.commit(after_step);
}

int g_kill_step = -1;
void kill_at_step(int step) {
  if (step == g_kill_step) ::raise(SIGKILL);
}

// commit_new_run in a child process that SIGKILLs itself right after `step`; returns the
// child's pid (gone by then).
pid_t killed_commit(const TempDir& dir, int step) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    g_kill_step = step;
    try {
      commit_new_run(dir, kill_at_step);
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

std::string state_of(const TempDir& dir, const char* name) {
  const std::string path = dir.file(name);
  if (!std::filesystem::exists(path)) return "absent";
  const std::string text = read_file(path);
  return text.substr(0, 3);  // OLD or NEW
}

std::size_t count_files(const TempDir& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir.path()),
                                                std::filesystem::directory_iterator()));
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE(
      "a run killed after any rename of its outputs leaves no program beside files it was not "
      "written with") {
    // Steps: 0, 1 the two programs set aside; 2..4 the data files; 5, 6 the programs.
    for (int step = 0; step < kPrograms + kData + kPrograms; ++step) {
      CAPTURE(step);
      TempDir dir;
      write_old_run(dir);
      const pid_t pid = killed_commit(dir, step);
      int data_new = 0;
      for (const Output& o : kOutputs)
        if (o.role == OutputSet::Role::kData) data_new += state_of(dir, o.name) == "NEW";
      for (const Output& o : kOutputs) {
        if (o.role != OutputSet::Role::kProgram) continue;
        CAPTURE(o.name);
        const std::string state = state_of(dir, o.name);
        if (state == "absent") {
          // Set aside whole, where the operator can still find it.
          CHECK(read_file(replaced_program_path(dir.file(o.name), pid)) ==
                std::string("OLD ") + o.name + "\n");
        } else if (state == "OLD") {
          // Still in place only before anything it calls or is described by changed.
          CHECK(data_new == 0);
        } else {
          CHECK(state == "NEW");
          CHECK(data_new == kData);
        }
      }
      // The expected state after each step, in the order the header promises.
      CHECK(state_of(dir, "part.nc") == (step < 5 ? "absent" : "NEW"));
      CHECK(state_of(dir, "part.rough-1.nc") == (step == 0 ? "OLD" : step < 6 ? "absent" : "NEW"));
      CHECK(data_new == std::max(0, std::min(kData, step - 1)));
      // The next run completes the set and removes what the killed one left.
      commit_new_run(dir, nullptr);
      for (const Output& o : kOutputs) CHECK(state_of(dir, o.name) == "NEW");
      CHECK(count_files(dir) == std::size(kOutputs));
    }
  }

  TEST_CASE(
      "outputs with no earlier programs are renamed without setting anything aside, in the order "
      "added") {
    TempDir dir;
    static std::vector<int> steps;
    steps.clear();
    const std::vector<std::string> paths =
        commit_new_run(dir, [](int step) { steps.push_back(step); });
    CHECK(steps == std::vector<int>{0, 1, 2, 3, 4});
    REQUIRE(paths.size() == std::size(kOutputs));
    for (std::size_t k = 0; k < paths.size(); ++k) CHECK(paths[k] == dir.file(kOutputs[k].name));
    CHECK(count_files(dir) == std::size(kOutputs));
  }

  TEST_CASE(
      "a file that cannot take its name stops the set, and the error says where the earlier "
      "programs are") {
    TempDir dir;
    write_old_run(dir);
    // A non-empty folder under the report's name: rename(2) cannot replace it.
    std::filesystem::remove(dir.file("report.json"));
    std::filesystem::create_directory(dir.file("report.json"));
    dir.write("report.json/x", "x");
    std::string message;
    try {
      commit_new_run(dir, nullptr);
    } catch (const freeturn::InputError& e) {
      message = e.what();
    }
    CHECK(message.find("report.json") != std::string::npos);
    for (const char* program : {"part.nc", "part.rough-1.nc"}) {
      const std::string aside = replaced_program_path(dir.file(program), ::getpid());
      CHECK(message.find(aside) != std::string::npos);
      CHECK_FALSE(std::filesystem::exists(dir.file(program)));
      CHECK(read_file(aside) == std::string("OLD ") + program + "\n");
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
  }

  TEST_CASE("a set of one file is replaced in a single rename, with nothing set aside") {
    TempDir dir;
    dir.write("one.nc", "OLD\n");
    OutputSet outputs;
    outputs.add(dir.file("one.nc"), OutputSet::Role::kProgram).write("NEW\n");
    static std::vector<int> steps;
    steps.clear();
    outputs.commit([](int step) { steps.push_back(step); });
    CHECK(steps == std::vector<int>{0});
    CHECK(read_file(dir.file("one.nc")) == "NEW\n");
    CHECK(count_files(dir) == 1);
  }

  TEST_CASE("two outputs under one name are refused before anything is renamed") {
    TempDir dir;
    write_old_run(dir);
    OutputSet outputs;
    outputs.add(dir.file("part.nc"), OutputSet::Role::kProgram).write("NEW main\n");
    outputs.add(dir.file("part_001.nc")).write("NEW child\n");
    // A plugin naming its second child like its first: both write one temporary.
    outputs.add(dir.file("./part_001.nc")).write("NEW other child\n");
    CHECK_THROWS_WITH_AS(outputs.commit(),
                         doctest::Contains("two outputs of this run have this name"),
                         freeturn::InputError);
    for (const Output& o : kOutputs) CHECK(state_of(dir, o.name) == "OLD");
  }
}
