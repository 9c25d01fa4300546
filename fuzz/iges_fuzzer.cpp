// The IGES reader (io/iges_surface): InputError or surfaces that evaluate, at their
// domain's corners and middle, to finite points.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "freeturn/core/error.hpp"
#include "freeturn/io/iges_surface.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = freeturn::fuzz::write_scratch(data, size, ".igs");
  try {
    for (const freeturn::IgesSurfaceEntry& entry : freeturn::read_iges_surfaces(path)) {
      const freeturn::nurbs::NurbsSurface& s = entry.surface;
      const double u = 0.5 * (s.front_u() + s.knots_u().back()), v = 0.5 * (s.front_v() + s.knots_v().back());
      (void)s.point(u, v);
      (void)s.point(s.front_u(), s.front_v());
    }
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
