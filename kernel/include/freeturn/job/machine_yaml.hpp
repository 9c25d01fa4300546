#pragma once
// Machine description files (docs/machines.md): the standard part is read here, strictly;
// the map under the plugin's own name (`iso:`, `moore:` …) is passed to the plugin as
// YAML text.

#include <string>

#include "freeturn/job/yaml_limits.hpp"
#include "freeturn/machine/machine.hpp"

namespace freeturn {

// Throws InputError at file:line:col for a bad key or value. max_bytes bounds the file
// before it is parsed (load_yaml_file).
MachineDescription load_machine(const std::string& path, std::uintmax_t max_bytes = kMaxYamlBytes);

}  // namespace freeturn
