#pragma once
// Surfaces given by data rather than a formula: a NURBS control net (inline or IGES), a
// height grid, a point cloud. Internal to surface_yaml.cpp.

#include <memory>

#include "freeturn/job/yaml_reader.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

std::unique_ptr<Surface> read_nurbs_surface(MapReader& map);
std::unique_ptr<Surface> read_height_grid(MapReader& map);
std::unique_ptr<Surface> read_point_cloud(MapReader& map);

}  // namespace freeturn::detail
