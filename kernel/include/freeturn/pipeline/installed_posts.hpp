#pragma once
// The post-processors a run can use, and the machine files that name each: what
// `freeturn plugins` lists, for any front end.

#include <cstdint>
#include <string>
#include <vector>

#include "freeturn/job/yaml_limits.hpp"
#include "freeturn/machine/machine.hpp"

namespace freeturn {

struct InstalledPost {
  std::string name, path;
  std::string status = "ok";  // or why the plugin does not load (an ABI version, a symbol)
  std::vector<MachineDescription> machines;  // the machine files that name it
  // Machine files on the search path that do not read, with their error (file:line:col).
  std::vector<std::string> unreadable_machines;
};

// Every plugin on the plugin search path, each with the machines on the machine search
// path that use it (post/post_loader.hpp). Never throws for a bad plugin or machine file.
std::vector<InstalledPost> installed_posts(std::uintmax_t max_yaml_bytes = kMaxYamlBytes);

}  // namespace freeturn
