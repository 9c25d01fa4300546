#pragma once
// A lathe as the kernel sees it (shared/ARCHITECTURE.md, "Machine axes"): the axis layout
// and, per axis, sign, offset, travel, output decimals and dynamic limits; how C is
// written; the B axis's limits and pivot; how the controller interpolates; how fast it
// takes blocks. Parsed from the machine YAML by the job module; the dialect's own
// settings are passed through to the post-processor untouched.

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/path/cutter_points.hpp"

namespace freeturn {

enum class Axis { kX, kZ, kC, kB };

// The share of each dynamic limit a program may use: the rest is room for the rounding of
// the numbers it is written with (block times to the µs, positions to the nm).
inline constexpr double kDynamicLimitShare = 0.98;
const char* axis_letter(Axis axis);

struct AxisSpec {
  Axis axis = Axis::kX;
  double sign = 1;    // +1 or −1: machine value = sign · kernel value + offset
  double offset = 0;  // mm, or degrees for C and B
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  int decimals = 6;
  double max_velocity = std::numeric_limits<double>::infinity();      // mm/s or °/s
  double max_acceleration = std::numeric_limits<double>::infinity();  // mm/s² or °/s²
};

// A position as the program's word carries it: rounded to nearest at the axis' decimals,
// as the posts write it (plugins/include/freeturn/post_format.hpp). The axes' velocities
// and accelerations a reader of the program finds are those of these positions.
inline double as_written(double value, double scale) {
  return std::nearbyint(value * scale) / scale;
}

struct MachineDescription {
  std::string name;
  std::string plugin;
  std::vector<AxisSpec> axes;  // in program order, e.g. X, Z, C (, B)
  bool c_wrapped = true;       // C written in [0, 360) (else accumulating)
  double b_min_deg = -90, b_max_deg = 90;
  double pivot_distance = 0;   // mm, B pivot to nose centre
  // Where the machine file states each bound (the axis's entry when it leaves one out): a
  // block past a limit is reported at the bound it crosses. travel_places by Axis;
  // b_limit_places for b_axis min_deg and max_deg.
  struct BoundPlaces {
    SourceLocation min, max;
  };
  BoundPlaces travel_places[4];
  BoundPlaces b_limit_places;
  SourceLocation decimals_places[4];  // by Axis: each axis's decimals (its entry when left out)
  Interpolation interpolation = Interpolation::kLinear;
  double max_block_rate = std::numeric_limits<double>::infinity();  // blocks per second
  // How the program states speed: inverse time (each block's duration: G93) or feed per
  // minute (G94; X-Z profile programs only, where it is the path feed).
  bool feed_per_minute = false;
  // The dialect writes no time per block (one block time for the whole program, stated in
  // its header): spirals then run at one constant spindle speed, never a schedule.
  bool constant_block_time = false;
  std::string dialect_settings;  // the YAML text under the dialect's key, for the plugin
  // Where the machine file states them: the file, the dialect's map and each of its keys
  // (a plugin's refusal of a setting is reported at the setting).
  SourceLocation file_place;
  SourceLocation plugin_place;
  SourceLocation dialect_place;
  struct SettingPlace {
    std::string key;
    SourceLocation key_place, value_place;
  };
  std::vector<SettingPlace> dialect_key_places;

  // The place of the dialect setting a plugin's message names ('key'): its key when the
  // message says the setting is unknown, else its value; failing that the dialect's map,
  // else the file.
  SourceLocation place_of_setting_in(const std::string& message) const;

  // Per Axis, 10^decimals: a word's units per machine unit (1 for an axis it does not have),
  // for as_written.
  std::array<double, 4> word_scales() const;
  bool has(Axis axis) const;
  const AxisSpec& spec(Axis axis) const;  // throws std::out_of_range when absent
};

}  // namespace freeturn
