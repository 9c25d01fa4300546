#include "freeturn/job/surface_yaml.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "freeturn/core/number_text.hpp"
#include "freeturn/job/yaml_reader.hpp"
#include "surface_data_yaml.hpp"
#include "freeturn/surface/biconic.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/odd_asphere.hpp"
#include "freeturn/surface/qbfs.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/toroidal.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/surface/xy_polynomial.hpp"
#include "freeturn/surface/zernike.hpp"

namespace freeturn {
namespace {

constexpr const char* kKnownTypes =
    "plane, sphere, conic, even_asphere, odd_asphere, biconic, toroidal, xy_polynomial, "
    "zernike, qbfs, sinusoidal_ring, sinusoidal_grid, alvarez, compound_eye, microlens_array, "
    "nurbs, height_grid, point_cloud";

bool is_data_type(const std::string& type) {
  return type == "nurbs" || type == "height_grid" || type == "point_cloud";
}

// Vertex curvature from `<radius_key>` (R, mm; 0 = flat) or `<curvature_key>` (c = 1/R).
double read_curvature(MapReader& map, const std::string& radius_key = "radius",
                      const std::string& curvature_key = "curvature") {
  if (map.has(radius_key) && map.has(curvature_key))
    map.fail(curvature_key,
             "surface takes either '" + radius_key + "' or '" + curvature_key + "', not both");
  if (map.has(curvature_key)) return map.number(curvature_key);
  const double radius = map.number(radius_key);
  return radius == 0 ? 0.0 : 1.0 / radius;
}

std::array<double, 9> read_asphere_terms(MapReader& map) {
  static const char* const kKeys[9] = {"A4", "A6", "A8", "A10", "A12", "A14", "A16", "A18", "A20"};
  std::array<double, 9> a{};
  for (int i = 0; i < 9; ++i) a[i] = map.number(kKeys[i], 0.0);
  return a;
}

// Term coefficients as a map {index: value} (1-based) or a list [A_1, A_2, …].
std::vector<double> read_terms(MapReader& map, const std::string& key, int max_index) {
  const YAML::Node node = map.child(key);
  std::vector<double> out;
  const auto value_of = [&](const YAML::Node& v, const std::string& what) {
    double x;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, x) || !std::isfinite(x))
      throw InputError(location_of(v, map.file()),
                       "surface." + key + " " + what + " must be a finite number");
    return x;
  };
  if (node.IsSequence()) {
    if (static_cast<int>(node.size()) > max_index)
      throw InputError(location_of(node, map.file()),
                       "surface." + key + " has " + std::to_string(node.size()) +
                           " terms; at most " + std::to_string(max_index));
    for (std::size_t i = 0; i < node.size(); ++i)
      out.push_back(value_of(node[i], "term " + std::to_string(i + 1)));
    return out;
  }
  if (!node.IsMap())
    throw InputError(location_of(node, map.file()),
                     "surface." + key + " must be a map {term index: coefficient} or a list");
  for (auto it = node.begin(); it != node.end(); ++it) {
    int index = 0;
    if (!YAML::convert<int>::decode(it->first, index) || index < 1 || index > max_index)
      throw InputError(location_of(it->first, map.file()),
                       "surface." + key + " term '" + it->first.Scalar() +
                           "' must be an index from 1 to " + std::to_string(max_index));
    if (static_cast<int>(out.size()) < index) out.resize(static_cast<std::size_t>(index), 0.0);
    out[static_cast<std::size_t>(index - 1)] =
        value_of(it->second, "term " + std::to_string(index));
  }
  return out;
}

LensletArrayOptions::Pattern read_pattern(MapReader& map, const std::string& key,
                                          bool rings_allowed) {
  if (!map.has(key)) {
    map.optional_child(key);
    return LensletArrayOptions::Pattern::kHexagonal;
  }
  const std::string p = map.text(key);
  if (p == "hexagonal") return LensletArrayOptions::Pattern::kHexagonal;
  if (p == "square" && !rings_allowed) return LensletArrayOptions::Pattern::kSquare;
  if (p == "rings" && rings_allowed) return LensletArrayOptions::Pattern::kRings;
  map.fail(key, "surface." + key + " must be " +
                    (rings_allowed ? "rings or hexagonal" : "square or hexagonal") + ", not '" + p +
                    "'");
}

// reach: the radius about the array's own axis its lenslets fill (placed_reach).
std::unique_ptr<Surface> read_lenslets(MapReader& map, bool compound_eye, double reach) {
  LensletArrayOptions o;
  if (compound_eye) {
    const double rb = map.number("base_radius");
    if (rb == 0)
      map.fail("base_radius",
               "surface.base_radius must not be 0 (use microlens_array for a plane)");
    o.base_curvature = 1 / rb;
  }
  o.lens_radius = map.number("lens_radius");
  o.lens_diameter = map.positive("lens_diameter");
  o.pitch = map.positive("pitch");
  o.pattern = read_pattern(map, compound_eye ? "pattern" : "lattice", compound_eye);
  o.extent = reach;
  try {
    return std::make_unique<LensletArray>(o);
  } catch (const InputError& e) {
    map.fail(map.has(e.where()) ? e.where() : "type", e.problem());
  }
}

std::unique_ptr<Surface> read_base(MapReader& map, const std::string& type, double reach) {
  if (type == "plane") return std::make_unique<EvenAsphere>(0.0, 0.0);
  if (type == "sphere") {
    const double radius = map.number("radius");
    if (radius == 0) map.fail("radius", "surface.radius of a sphere must not be 0");
    return std::make_unique<EvenAsphere>(1.0 / radius, 0.0);
  }
  if (type == "conic") {
    const double c = read_curvature(map);
    return std::make_unique<EvenAsphere>(c, map.number("conic", 0.0));
  }
  if (type == "even_asphere") {
    const double c = read_curvature(map);
    const double k = map.number("conic", 0.0);
    return std::make_unique<EvenAsphere>(c, k, read_asphere_terms(map));
  }
  if (type == "odd_asphere") {
    const double c = read_curvature(map);
    const double k = map.number("conic", 0.0);
    return std::make_unique<OddAsphere>(
        c, k, map.has("coefficients") ? read_terms(map, "coefficients", 30) : std::vector<double>{});
  }
  if (type == "qbfs") {
    const double c = read_curvature(map);
    const double rn = map.positive("normalization_radius");
    // a_0 … a_M: a list, or a map {m: a_m} with m from 0.
    std::vector<double> a;
    if (map.has("coefficients")) {
      const YAML::Node node = map.node()["coefficients"];
      if (node.IsMap()) {
        // read_terms indexes from 1; shift the keys by reading each one here.
        for (auto it = node.begin(); it != node.end(); ++it) {
          int m = -1;
          double value;
          if (!YAML::convert<int>::decode(it->first, m) || m < 0 || m > 30)
            throw InputError(location_of(it->first, map.file()),
                             "surface.coefficients term '" + it->first.Scalar() +
                                 "' must be an index m from 0 to 30");
          if (!it->second.IsScalar() || !YAML::convert<double>::decode(it->second, value) ||
              !std::isfinite(value))
            throw InputError(location_of(it->second, map.file()),
                             "surface.coefficients a_" + std::to_string(m) +
                                 " must be a finite number");
          if (static_cast<int>(a.size()) <= m) a.resize(static_cast<std::size_t>(m + 1), 0.0);
          a[static_cast<std::size_t>(m)] = value;
        }
        map.child("coefficients");
      } else {
        a = read_terms(map, "coefficients", 31);
      }
    }
    return std::make_unique<Qbfs>(c, rn, std::move(a));
  }
  if (type == "biconic") {
    const double cx = read_curvature(map, "radius_x", "curvature_x");
    const double cy = read_curvature(map, "radius_y", "curvature_y");
    return std::make_unique<Biconic>(cx, cy, map.number("conic_x", 0.0),
                                     map.number("conic_y", 0.0));
  }
  if (type == "toroidal") {
    const double c = read_curvature(map);
    const double k = map.number("conic", 0.0);
    const double rotation = map.number("rotation_radius");
    const std::vector<double> alpha =
        map.has("alpha") ? read_terms(map, "alpha", 8) : std::vector<double>{};
    std::array<double, 8> a{};
    for (std::size_t i = 0; i < alpha.size(); ++i) a[i] = alpha[i];
    return std::make_unique<Toroidal>(c, k, rotation, a);
  }
  if (type == "xy_polynomial") {
    const double c = read_curvature(map);
    const double k = map.number("conic", 0.0);
    const double rn = map.positive("normalization_radius");
    return std::make_unique<XyPolynomial>(c, k, rn, read_terms(map, "coefficients", 230));
  }
  if (type == "zernike") {
    const double c = read_curvature(map);
    const double k = map.number("conic", 0.0);
    const auto asphere = read_asphere_terms(map);
    const double rn = map.positive("normalization_radius");
    return std::make_unique<Zernike>(c, k, asphere, rn, read_terms(map, "coefficients", 231));
  }
  if (type == "sinusoidal_ring") {
    const double amplitude = map.number("amplitude");
    if (map.has("period") == map.has("angular_frequency"))
      map.fail(
          "period",
          "sinusoidal_ring takes exactly one of 'period' (mm) or 'angular_frequency' (rad/mm)");
    const double w = map.has("period") ? 2 * std::numbers::pi / map.positive("period")
                                       : map.positive("angular_frequency");
    return std::make_unique<SinusoidalRing>(amplitude, w, map.number("offset", 0.0));
  }
  if (type == "sinusoidal_grid") {
    const double amplitude = map.number("amplitude");
    return std::make_unique<SinusoidalGrid>(amplitude, map.positive("wavelength_x"),
                                            map.positive("wavelength_y"));
  }
  if (type == "compound_eye") return read_lenslets(map, true, reach);
  if (type == "microlens_array") return read_lenslets(map, false, reach);
  if (type == "nurbs") return detail::read_nurbs_surface(map);
  if (type == "height_grid") return detail::read_height_grid(map);
  if (type == "point_cloud") return detail::read_point_cloud(map);
  if (type == "alvarez") return std::make_unique<Alvarez>(map.number("A"), map.number("D", 0.0));
  map.fail("type", "unknown surface type '" + type + "' (known: " + kKnownTypes + ")");
}

// How far from the parent's axis an aperture of radius `outer_radius` reaches once the
// placement (below) has moved it: the decentre's distance added, and as much again for a
// tilt (to 60°). A lenslet array fills this radius, so that a segment of one has its
// lenslets out to the aperture's edge (until December 2026 those past the aperture's
// radius about the parent's axis were missing: a flat where the array was asked for).
// The placement's values are read, and refused, by read_placement; here only numbers
// count.
double placed_reach(const YAML::Node& surface, double outer_radius) {
  double reach = outer_radius;
  const auto number = [](const YAML::Node& n, const char* key) {
    double v = 0;
    if (n.IsMap() && n[key] && n[key].IsScalar() && YAML::convert<double>::decode(n[key], v) &&
        std::isfinite(v))
      return v;
    return 0.0;
  };
  if (surface.IsMap() && surface["decenter"])
    reach += std::hypot(number(surface["decenter"], "x"), number(surface["decenter"], "y"));
  if (surface.IsMap() && (surface["tilt_deg"] || surface["align_normal"])) reach += outer_radius;
  return reach;
}

// Optional decentre and tilt around any surface (an off-axis segment).
std::unique_ptr<Surface> read_placement(MapReader& map, std::unique_ptr<Surface> surface) {
  const auto decentre = map.optional_child("decenter");
  const auto tilt = map.optional_child("tilt_deg");
  const auto align = map.optional_child("align_normal");
  if (!decentre && !tilt && !align) return surface;
  double dx = 0, dy = 0;
  if (decentre) {
    MapReader d(*decentre, map.file(), "surface.decenter");
    dx = d.number("x", 0.0);
    dy = d.number("y", 0.0);
    d.finish();
  }
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  bool aligned = false;
  if (align) {
    if (!align->IsScalar() || !YAML::convert<bool>::decode(*align, aligned))
      throw InputError(location_of(*align, map.file()),
                       "surface.align_normal must be true or false");
  }
  if (aligned && tilt)
    map.fail("tilt_deg", "surface takes either 'tilt_deg' or 'align_normal: true', not both");
  if (aligned) rotation = TransformedSurface::rotation_aligning_normal(*surface, dx, dy);
  if (tilt) {
    MapReader t(*tilt, map.file(), "surface.tilt_deg");
    const double ax = t.number("x", 0.0) * std::numbers::pi / 180,
                 ay = t.number("y", 0.0) * std::numbers::pi / 180;
    t.finish();
    rotation = TransformedSurface::rotation_from_tilts(ax, ay);
    // The parent's +z is the side its material faces the tool from: turned 90° or more
    // from the spindle axis, the part would face away (at 90° no height is defined; at
    // 180° the bowls of a mold became domes over material the tool cannot reach, and the
    // job passed).
    if (!(rotation(2, 2) > 1e-9))
      map.fail(
          "tilt_deg",
          "the tilt (" + significant_text(ax * 180 / std::numbers::pi, 6) + "° about x, then " +
              significant_text(ay * 180 / std::numbers::pi, 6) + "° about y) turns the surface " +
              significant_text(
                  std::acos(std::clamp(rotation(2, 2), -1.0, 1.0)) * 180 / std::numbers::pi, 6) +
              "° from the spindle axis: 90° or more, its material would face away from the tool");
  }
  return std::make_unique<TransformedSurface>(std::move(surface), dx, dy, rotation);
}

}  // namespace

std::unique_ptr<Surface> surface_from_yaml(const YAML::Node& node, const std::string& file,
                                           double outer_radius) {
  MapReader map(node, file, "surface");
  const std::string type = map.text("type");
  std::unique_ptr<Surface> surface;
  try {
    surface = read_base(map, type, placed_reach(node, outer_radius));
  } catch (const InputError& e) {
    // Constructors name the parameter; point at it in the file. An error already placed
    // (at a line, or at the file where its nodes carry none: a spec built in memory) is not
    // a parameter's name.
    if (e.where().find(':') != std::string::npos || e.where() == file) throw;
    map.fail(map.has(e.where()) ? e.where() : "type", "surface." + e.where() + " " + e.problem());
  }
  const double base_radius = surface->defined_radius();
  surface = read_placement(map, std::move(surface));
  map.finish();
  // Rounding aside (an edge found to 1e-12 of itself): data that reaches the aperture does.
  if (base_radius * (1 + 1e-12) < outer_radius && !map.has("decenter") && !map.has("tilt_deg") &&
      !map.has("align_normal"))
    map.fail(is_data_type(type)      ? (map.has("iges")   ? "iges"
                                         : map.has("file") ? "file"
                                                           : "type")
             : map.has("conic")     ? "conic"
             : map.has("radius")    ? "radius"
             : map.has("curvature") ? "curvature"
                                    : "type",
             "the surface is undefined beyond r = " + significant_text(base_radius, 6) + " mm (" +
                 (is_data_type(type) ? "the edge of its data in x-y"
                                     : "the conic's square root goes negative") +
                 "), inside the aperture radius " + significant_text(outer_radius, 6) + " mm");
  // Every surface, whatever its type: sampled over the aperture, it must be finite.
  for (int i = 0; i <= 32; ++i)
    for (int j = 0; j < 64; ++j) {
      const double r = outer_radius * i / 32.0, phi = 2 * std::numbers::pi * j / 64.0;
      const double x = r * std::cos(phi), y = r * std::sin(phi);
      double z, zx, zy;
      surface->sag_gradient(x, y, z, zx, zy);
      if (!(std::isfinite(z) && std::isfinite(zx) && std::isfinite(zy)))
        map.fail("type", "the " + type + " surface is undefined at (x, y) = (" + significant_text(x, 6) +
                             ", " + significant_text(y, 6) + ") mm, inside the aperture radius " +
                             significant_text(outer_radius, 6) + " mm");
    }
  return surface;
}

}  // namespace freeturn
