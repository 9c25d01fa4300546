// Writes an ISO program with the iso post for the LinuxCNC check (linuxcnc_test.sh):
// an asphere's spiral, nose-compensated, on the machine given.
// usage: write_iso_program <plugin .so> <machine .yaml> <out.ngc>
#include <cstdio>

#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/post/post_program.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/clearance.hpp"
#include "freeturn/tool/tool_compensator.hpp"

int main(int argc, char** argv) {
  using namespace freeturn;
  if (argc != 4) return 2;
  try {
    const MachineDescription m = load_machine(argv[2]);
    const auto plugin = PostPlugin::load_file(argv[1]);
    const EvenAsphere asphere(1 / 30.0, -0.5);
    SpiralOptions o;
    o.outer_radius = 3;
    o.pitch = 0.2;
    o.points.tolerance = 1e-4;
    CompensationOptions c;
    c.tool.nose_radius = 0.5;
    if (m.has(Axis::kB)) {
      c.b_mode = BMode::kFollow;
      c.pivot_distance = m.pivot_distance;
    }
    ToolCheckOptions checks;
    checks.outer_radius = 3;
    MotionOptions motion;
    motion.spindle_rpm = 20;
    const double ceiling =
        program_z_ceiling(asphere, 0, 3, c, stand_off_for(o.points, tool_motion(c), asphere));
    PostProgram program(*plugin, m, {"asphere", 20, 0, -1, -1, ceiling, 1}, argv[3]);
    AxisMapper mapper(m, motion, program);
    ToolCompensator compensator(asphere, c, checks, mapper);
    plan_spiral(asphere, BaseSurface::plane(3), o, compensator);
    program.finish();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
