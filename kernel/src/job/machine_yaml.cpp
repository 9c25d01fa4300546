#include "freeturn/job/machine_yaml.hpp"

#include <cmath>
#include <numbers>

#include "freeturn/job/yaml_reader.hpp"

namespace freeturn {
namespace {

// Why a dynamic limit under its floor is refused: the program would be written as asked.
const std::string kTypo = "a machine this slow would take years over one part (a typo?)";

Axis axis_from(const std::string& name, MapReader& map) {
  if (name == "X") return Axis::kX;
  if (name == "Z") return Axis::kZ;
  if (name == "C") return Axis::kC;
  if (name == "B") return Axis::kB;
  map.fail("name", "axis name must be X, Z, C or B, not '" + name + "'");
}

}  // namespace

MachineDescription load_machine(const std::string& path, std::uintmax_t max_bytes) {
  const YAML::Node root = load_yaml_file(path, max_bytes);
  MapReader map(root, path, "machine");
  MachineDescription m;
  m.file_place = SourceLocation{path, 0, 0};
  m.name = map.file_name("name");
  m.plugin = map.text("plugin");
  // It names a shared library in the plugin folder: a name, never a path.
  for (const char ch : m.plugin)
    if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-') ||
        m.plugin.size() > 64)
      map.fail("plugin", "machine.plugin '" + m.plugin +
                             "' must be a post-processor's name: lower-case letters, digits, '_' "
                             "and '-', at most 64 (a name, not a path)");
  m.plugin_place = location_of(root["plugin"], path);
  const YAML::Node axes = map.child("axes");
  if (!axes.IsSequence() || axes.size() < 2 || axes.size() > 4)
    throw InputError(location_of(axes, path), "machine.axes must list 2 to 4 axes");
  for (std::size_t i = 0; i < axes.size(); ++i) {
    MapReader a(axes[i], path, "machine.axes[" + std::to_string(i) + "]");
    AxisSpec s;
    s.axis = axis_from(a.text("name"), a);
    s.sign = a.number("sign", 1.0);
    if (s.sign != 1 && s.sign != -1) a.fail("sign", "sign must be 1 or -1");
    s.offset = a.number("offset", 0.0);
    s.min = a.number("min", -std::numeric_limits<double>::infinity());
    s.max = a.number("max", std::numeric_limits<double>::infinity());
    if (a.has("min") && a.has("max") && !(s.min < s.max)) a.fail("max", "max must exceed min");
    m.travel_places[static_cast<int>(s.axis)] = {a.place("min"), a.place("max")};
    const double decimals = a.number("decimals", 6.0);
    if (decimals != std::floor(decimals) || decimals < 0 || decimals > 12)
      a.fail("decimals", "decimals must be an integer from 0 to 12");
    s.decimals = static_cast<int>(decimals);
    m.decimals_places[static_cast<int>(s.axis)] = a.place("decimals");
    // Limits below these are typos (a per-second limit of 1e-12 would be a program of blocks
    // years long, which the scheduler would write as asked): left out, a limit is none.
    const std::string per_second = s.axis == Axis::kC || s.axis == Axis::kB ? " °/s" : " mm/s";
    s.max_velocity = a.at_least("max_velocity", std::numeric_limits<double>::infinity(), 1e-3,
                                per_second, kTypo);
    s.max_acceleration = a.at_least("max_acceleration", std::numeric_limits<double>::infinity(),
                                    1e-3, per_second + "²", kTypo);
    a.finish();
    for (const AxisSpec& other : m.axes)
      if (other.axis == s.axis) a.fail("name", std::string("axis ") + axis_letter(s.axis) + " is listed twice");
    m.axes.push_back(s);
  }
  if (!m.has(Axis::kX) || !m.has(Axis::kZ))
    throw InputError(location_of(axes, path), "machine.axes must include X and Z");
  if (m.has(Axis::kB) && !m.has(Axis::kC))
    throw InputError(location_of(axes, path), "a machine with B needs C");
  if (map.has("c_axis")) {
    const std::string c = map.text("c_axis");
    if (c != "wrapped" && c != "accumulating")
      map.fail("c_axis", "c_axis must be wrapped or accumulating, not '" + c + "'");
    m.c_wrapped = c == "wrapped";
  }
  if (const auto b = map.optional_child("b_axis")) {
    if (!m.has(Axis::kB)) map.fail("b_axis", "b_axis settings need a B axis in machine.axes");
    MapReader br(*b, path, "machine.b_axis");
    m.b_min_deg = br.number("min_deg");
    m.b_max_deg = br.number("max_deg");
    if (!(m.b_min_deg < m.b_max_deg)) br.fail("max_deg", "max_deg must exceed min_deg");
    m.b_limit_places = {br.place("min_deg"), br.place("max_deg")};
    m.pivot_distance = br.non_negative("pivot_distance", 0.0);
    br.finish();
  } else if (m.has(Axis::kB)) {
    map.fail("axes", "a B axis needs b_axis: {min_deg, max_deg, pivot_distance}");
  }
  if (map.has("interpolation")) {
    const std::string i = map.text("interpolation");
    if (i != "linear" && i != "pvt")
      map.fail("interpolation", "interpolation must be linear or pvt, not '" + i + "'");
    m.interpolation = i == "pvt" ? Interpolation::kCubic : Interpolation::kLinear;
  }
  m.max_block_rate = map.at_least("max_block_rate", std::numeric_limits<double>::infinity(), 1,
                                  " blocks/s", kTypo);
  if (map.has("feed_mode")) {
    const std::string f = map.text("feed_mode");
    if (f != "inverse_time" && f != "per_minute")
      map.fail("feed_mode", "feed_mode must be inverse_time or per_minute, not '" + f + "'");
    if (f == "per_minute" && m.has(Axis::kC))
      map.fail("feed_mode", "feed_mode per_minute cannot time C-axis moves: use inverse_time");
    m.feed_per_minute = f == "per_minute";
  }
  if (map.has("block_times")) {
    const std::string b = map.text("block_times");
    if (b != "varying" && b != "constant")
      map.fail("block_times", "block_times must be varying or constant, not '" + b + "'");
    m.constant_block_time = b == "constant";
  }
  if (const auto dialect = map.optional_child(m.plugin)) {
    // Plugins take a flat map of scalars, handed over as "key: value" lines with line
    // breaks and backslashes escaped (\n, \\), so a template can span lines.
    if (!dialect->IsMap())
      throw InputError(location_of(*dialect, path), "machine." + m.plugin + " must be a map");
    m.dialect_place = location_of(*dialect, path);
    for (auto it = dialect->begin(); it != dialect->end(); ++it) {
      m.dialect_key_places.push_back(
          {it->first.Scalar(), location_of(it->first, path), location_of(it->second, path)});
      if (!it->second.IsScalar())
        throw InputError(location_of(it->second, path),
                         "machine." + m.plugin + "." + it->first.Scalar() +
                             " must be a single value (a number or a string)");
      std::string value;
      for (char ch : it->second.Scalar()) {
        if (ch == '\\') value += "\\\\";
        else if (ch == '\n') value += "\\n";
        else value += ch;
      }
      m.dialect_settings += it->first.Scalar() + ": " + value + "\n";
    }
  }
  map.finish();
  return m;
}

}  // namespace freeturn
