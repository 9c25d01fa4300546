#include <doctest/doctest.h>

#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/job/yaml_reader.hpp"

using freeturn::InputError;
using freeturn::load_yaml_text;

namespace {

// A list of nine strings, then `levels` lists of nine aliases of the one before: the last
// stands for 9^(levels + 1) strings in about 40 bytes a line.
std::string alias_tower(int levels) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k <= levels; ++k) {
    const std::string name = std::to_string(k);
    std::string before = "*a";
    before += std::to_string(k - 1);
    text.append("a").append(name).append(": &a").append(name).append(" [");
    for (int i = 0; i < 9; ++i) {
      if (i > 0) text += ", ";
      text += before;
    }
    text += "]\n";
  }
  return text;
}

std::string error_of(const std::string& text) {
  try {
    load_yaml_text(text, "job.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_SUITE("job") {
  TEST_CASE("aliases: a few reuses load, a tower of them is refused at the repeated value") {
    // A 2-level tower stands for 9³ strings: far under the floor. The reused list reads the
    // same through each alias.
    const YAML::Node small = load_yaml_text(alias_tower(2), "job.yaml");
    REQUIRE(small["a2"].size() == 9);
    CHECK(small["a2"][8][8][0].as<std::string>() == "x");
    CHECK(small["a1"][4].size() == 9);

    // Walking a_k visits N_k = 1 + 9 N_(k-1) values, N_0 = 10: the 5-level tower's keys,
    // lists and strings are 672 610 values (a_5 alone 597 871), under the floor of a million.
    CHECK(error_of(alias_tower(5)) == "no error");
    // N_6 = 5 380 840 values from about 300 bytes: refused, at the anchored list (line 1)
    // whose strings the aliases repeat, before a walk that would not end (9^41 at 40 levels).
    for (const int levels : {6, 11, 40}) {
      CAPTURE(levels);
      const std::string message = error_of(alias_tower(levels));
      CHECK(message.rfind("job.yaml:1:", 0) == 0);
      CHECK(message.find("aliases ('*name')") != std::string::npos);
    }
  }
}
