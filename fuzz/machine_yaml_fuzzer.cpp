// The machine YAML loader (job/machine_yaml): InputError or a machine, nothing else.
#include <cstdint>

#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = freeturn::fuzz::write_scratch(data, size, ".yaml");
  try {
    (void)freeturn::load_machine(path);
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
