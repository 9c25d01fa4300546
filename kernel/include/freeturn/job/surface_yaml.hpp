#pragma once
// Building a design surface from its YAML map ({type: ..., parameters}).

#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

// node: the `surface:` map. file: its path, for messages.
// outer_radius: the aperture the surface must be defined over (mm).
// Throws InputError naming the key and its line for unknown types or keys, missing or
// non-finite parameters, and surfaces undefined inside the aperture.
std::unique_ptr<Surface> surface_from_yaml(const YAML::Node& node, const std::string& file,
                                           double outer_radius);

}  // namespace freeturn
