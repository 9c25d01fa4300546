#include "freeturn/machine/machine.hpp"

#include <cmath>
#include <stdexcept>

namespace freeturn {

const char* axis_letter(Axis axis) {
  static const char* const kLetters[] = {"X", "Z", "C", "B"};
  return kLetters[static_cast<int>(axis)];
}

SourceLocation MachineDescription::place_of_setting_in(const std::string& message) const {
  const bool unknown = message.rfind("unknown setting", 0) == 0;
  for (const SettingPlace& s : dialect_key_places)
    if (message.find("'" + s.key + "'") != std::string::npos)
      return unknown ? s.key_place : s.value_place;
  return dialect_place.file.empty() ? file_place : dialect_place;
}

std::array<double, 4> MachineDescription::word_scales() const {
  std::array<double, 4> scales = {1, 1, 1, 1};
  for (const AxisSpec& a : axes)
    scales[static_cast<std::size_t>(a.axis)] = std::pow(10.0, a.decimals);
  return scales;
}

bool MachineDescription::has(Axis axis) const {
  for (const AxisSpec& a : axes)
    if (a.axis == axis) return true;
  return false;
}

const AxisSpec& MachineDescription::spec(Axis axis) const {
  for (const AxisSpec& a : axes)
    if (a.axis == axis) return a;
  throw std::out_of_range(std::string("machine has no ") + axis_letter(axis) + " axis");
}

}  // namespace freeturn
