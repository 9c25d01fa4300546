#pragma once
// Machines shared by the machine tests and the benchmarks.

#include "freeturn/machine/machine.hpp"

namespace freeturn::test {

// X Z C with a Moore Nanotech 250UPL's placeholder limits (its machine YAML).
inline MachineDescription moore_250upl_xzc() {
  MachineDescription m;
  m.name = "moore-nanotech-250upl";
  m.axes = {{Axis::kX, 1, 0, -75, 75, 6, 25, 500},
            {Axis::kZ, 1, 0, -75, 75, 6, 25, 2000},
            {Axis::kC, 1, 0, -1e300, 1e300, 5, 3000, 30000}};
  m.c_wrapped = true;
  m.max_block_rate = 2000;
  return m;
}

}  // namespace freeturn::test
