// ncdiff's NC parser (io/nc_program): any text parses into blocks or raises InputError,
// and a program compared with itself has no difference.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/io/nc_program.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto blocks = freeturn::parse_nc(text, "fuzz.nc");
    if (!freeturn::nc_diff(blocks, "a", blocks, "b").same) std::abort();
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
