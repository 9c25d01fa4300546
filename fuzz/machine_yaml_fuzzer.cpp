// The machine YAML loader (job/machine_yaml) and the dialect settings it hands a post:
// InputError or a machine, nothing else; and a machine that loads, if its plugin is one
// freeturn ships, gets a program created from its settings and a few blocks written (to
// a scratch file that is never committed). A plugin that refuses its settings raises
// InputError; one that crashes or hangs ends the process (exit 3), which the fuzzer
// reports as a finding.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/post/post_loader.hpp"
#include "freeturn/post/post_program.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = freeturn::fuzz::write_scratch(data, size, ".yaml");
  try {
    freeturn::MachineDescription m = freeturn::load_machine(path);
    if (m.plugin != "moore" && m.plugin != "iso" && m.plugin != "precitech") return 0;
    static const auto plugins = [] {
      std::array<std::unique_ptr<freeturn::PostPlugin>, 3> p;
      p[0] = freeturn::PostPlugin::load("moore");
      p[1] = freeturn::PostPlugin::load("iso");
      p[2] = freeturn::PostPlugin::load("precitech");
      return p;
    }();
    const freeturn::PostPlugin& plugin = *plugins[m.plugin == "moore" ? 0 : m.plugin == "iso" ? 1 : 2];
    const std::string out = freeturn::fuzz::scratch_file(".nc");
    freeturn::PostProgram program(plugin, m, freeturn::ProgramSettings{"fuzz", 10, 5, 3, 1 << 20, 1.0, 1}, out);
    const freeturn::AxisRecord blocks[] = {{1.0, 0.5, 0, 0, 0}, {0.9, 0.4, 10, 0, 0.1}, {0.8, 0.3, 20, 0, 0.1}};
    program.write(blocks);
    // Destroyed unfinished: nothing is committed.
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
