#pragma once
// Machine description files (docs/machines.md): the standard part is read here, strictly;
// the map under the plugin's own name (`iso:`, `moore:` …) is passed to the plugin as
// YAML text.

#include <string>

#include "freeturn/machine/machine.hpp"

namespace freeturn {

// Throws InputError at file:line:col for a bad key or value.
MachineDescription load_machine(const std::string& path);

}  // namespace freeturn
