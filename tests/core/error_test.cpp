#include <doctest/doctest.h>

#include "freeturn/core/error.hpp"
#include "freeturn/core/status.hpp"

using freeturn::InputError;
using freeturn::SourceLocation;

TEST_SUITE("core") {
  TEST_CASE("InputError puts the place before the problem") {
    const InputError e(SourceLocation{"job.yaml", 3, 7}, "radius must be greater than 0");
    CHECK(std::string(e.what()) == "job.yaml:3:7: radius must be greater than 0");
    CHECK(e.where() == "job.yaml:3:7");
    CHECK(e.problem() == "radius must be greater than 0");
  }

  TEST_CASE("SourceLocation prints only what is known") {
    CHECK(SourceLocation{"a.yaml", 0, 0}.to_string() == "a.yaml");
    CHECK(SourceLocation{"a.yaml", 4, 0}.to_string() == "a.yaml:4");
    CHECK(SourceLocation{"", 0, 0}.to_string().empty());
    CHECK(std::string(InputError("plain").what()) == "plain");
    CHECK(std::string(InputError("theta=1.5 rad, r=2 mm", "missed").what()) ==
          "theta=1.5 rad, r=2 mm: missed");
  }

  TEST_CASE("Status names") {
    CHECK(std::string(freeturn::to_string(freeturn::Status::kNotConverged)) == "not converged");
    CHECK(std::string(freeturn::to_string(freeturn::Status::kMissed)) == "missed");
  }
}
