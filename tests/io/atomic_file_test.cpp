#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

#include "freeturn/core/error.hpp"
#include "freeturn/io/atomic_file.hpp"
#include "test_files.hpp"

using freeturn::AtomicFile;
using freeturn::test::read_file;
using freeturn::test::TempDir;

TEST_SUITE("io") {
  TEST_CASE("a committed file appears whole under its name, with no temporary left") {
    TempDir dir;
    const std::string path = dir.file("a.nc");
    {
      AtomicFile f(path);
      f.write("G1 X1\n");
      CHECK_FALSE(std::filesystem::exists(path));
      f.write("G1 X2\n");
      f.commit();
    }
    CHECK(read_file(path) == "G1 X1\nG1 X2\n");
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 1);
  }

  TEST_CASE("an abandoned file leaves the earlier version untouched and no temporary") {
    TempDir dir;
    const std::string path = dir.write("a.nc", "old program\n");
    try {
      AtomicFile f(path);
      f.write("half of a new prog");
      throw std::runtime_error("fault midway");
    } catch (const std::runtime_error&) {
    }
    CHECK(read_file(path) == "old program\n");
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 1);
  }

  TEST_CASE("a file that cannot be opened is an input error naming it") {
    CHECK_THROWS_AS(AtomicFile("/nonexistent-dir/x.nc"), freeturn::InputError);
  }
}
