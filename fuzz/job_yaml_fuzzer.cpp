// The job YAML loader (job/): any bytes either load or raise InputError; nothing else
// escapes, crashes, hangs or allocates without bound.
#include <cstdint>

#include "freeturn/core/error.hpp"
#include "freeturn/job/job.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = freeturn::fuzz::write_scratch(data, size, ".yaml");
  try {
    const freeturn::Job job = freeturn::load_job(path);
    // A loaded surface must evaluate without crashing where the job says it is defined.
    if (job.surface) (void)job.surface->sag(0.5 * job.aperture.outer_radius, 0.0);
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
