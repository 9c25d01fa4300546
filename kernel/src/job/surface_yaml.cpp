#include "freeturn/job/surface_yaml.hpp"

#include <array>
#include <string>

#include "freeturn/job/yaml_reader.hpp"
#include "freeturn/surface/even_asphere.hpp"

namespace freeturn {
namespace {

// Vertex curvature from `radius` (R, mm; 0 = flat) or `curvature` (c = 1/R, 1/mm).
double read_curvature(MapReader& map) {
  if (map.has("radius") && map.has("curvature"))
    map.fail("curvature", "surface takes either 'radius' or 'curvature', not both");
  if (map.has("curvature")) return map.number("curvature");
  const double radius = map.number("radius");
  return radius == 0 ? 0.0 : 1.0 / radius;
}

std::unique_ptr<EvenAsphere> read_even_asphere(MapReader& map, bool with_terms) {
  const double c = read_curvature(map);
  const double k = map.number("conic", 0.0);
  std::array<double, 9> a{};
  if (with_terms)
    for (int i = 2; i <= 10; ++i)
      a[static_cast<std::size_t>(i - 2)] = map.number("A" + std::to_string(2 * i), 0.0);
  return std::make_unique<EvenAsphere>(c, k, a);
}

}  // namespace

std::unique_ptr<Surface> surface_from_yaml(const YAML::Node& node, const std::string& file,
                                           double outer_radius) {
  MapReader map(node, file, "surface");
  const std::string type = map.text("type");
  std::unique_ptr<EvenAsphere> surface;
  if (type == "sphere") {
    const double radius = map.number("radius");
    if (radius == 0) map.fail("radius", "surface.radius of a sphere must not be 0");
    surface = std::make_unique<EvenAsphere>(1.0 / radius, 0.0);
  } else if (type == "even_asphere") {
    surface = read_even_asphere(map, true);
  } else if (type == "conic") {
    surface = read_even_asphere(map, false);
  } else if (type == "plane") {
    surface = std::make_unique<EvenAsphere>(0.0, 0.0);
  } else {
    map.fail("type",
             "unknown surface type '" + type + "' (known: plane, sphere, conic, even_asphere)");
  }
  map.finish();
  if (surface->defined_radius() < outer_radius)
    map.fail(map.has("conic") ? "conic" : "radius",
             "the surface is undefined beyond r = " + std::to_string(surface->defined_radius()) +
                 " mm (the conic's square root goes negative), inside the aperture radius " +
                 std::to_string(outer_radius) + " mm");
  return surface;
}

}  // namespace freeturn
