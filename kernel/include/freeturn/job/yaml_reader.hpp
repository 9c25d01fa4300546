#pragma once
// Strict reading of YAML maps: every value is checked for type and range, every key the
// schema does not know is an error, and every error names file:line:col.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/job/yaml_limits.hpp"

namespace freeturn {

// The location of a node in its file (yaml-cpp marks are 0-based; ours are 1-based).
SourceLocation location_of(const YAML::Node& node, const std::string& file);

// Parses a whole YAML file, strictly: a regular file of at most max_bytes, one document,
// no duplicate key in any map, no quoted value left open past its line, no byte-order mark
// past the start, no control character, and no more values through aliases than the text
// could hold written out (a floor of a million). Every refusal (and a syntax error) is an
// InputError at its line and column, or at the file for its kind and size.
YAML::Node load_yaml_file(const std::string& path, std::uintmax_t max_bytes = kMaxYamlBytes);

// The same for YAML text held in memory; `name` stands for the file in messages.
YAML::Node load_yaml_text(const std::string& text, const std::string& name,
                          std::uintmax_t max_bytes = kMaxYamlBytes);

// Reads one YAML map. Call finish() after the last read: it rejects the keys that were
// never asked for.
class MapReader {
 public:
  // `what` names the map in messages ("surface", "aperture").
  MapReader(const YAML::Node& node, std::string file, std::string what);

  bool has(const std::string& key) const;
  const YAML::Node& node() const { return node_; }
  const std::string& file() const { return file_; }

  // The node under `key` (marked as used); an error if absent.
  YAML::Node child(const std::string& key);
  std::optional<YAML::Node> optional_child(const std::string& key);

  // A finite number.
  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  // A finite number > 0.
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  // A finite number >= 0.
  double non_negative(const std::string& key, double fallback);
  // A finite number >= lo, with no upper bound; `why` says what a smaller one would do.
  double at_least(const std::string& key, double fallback, double lo, const std::string& unit,
                  const std::string& why);
  // A finite number in (lo, hi] (`open_low`) or [lo, hi]; `unit` follows the bounds in the
  // message ("°", " mm").
  double in_range(const std::string& key, double fallback, double lo, double hi, bool open_low,
                  const std::string& unit);
  double in_range(const std::string& key, double lo, double hi, bool open_low,
                  const std::string& unit);  // required
  // A non-empty string.
  std::string text(const std::string& key);
  // A string that names output files (the job's name, the machine's): at most 100
  // characters (a file system takes 255 bytes for the name with its suffixes), letters,
  // digits, '-', '_' and '.', not starting with '.', so never a path or a hidden file.
  std::string file_name(const std::string& key);

  // Rejects keys that were not read.
  void finish() const;

  // The place of the value of `key`, or of the map if the key is absent.
  SourceLocation place(const std::string& key) const;
  // An error located at the value of `key` (or at the map if the key is absent).
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  double read_number(const YAML::Node& value, const std::string& key) const;
  // Throws at `key` itself when its value is empty ("radius:" and nothing after it):
  // yaml-cpp marks an empty value at the next token, often the next line's key.
  void refuse_empty(const YAML::Node& value, const std::string& key,
                    const std::string& needed) const;

  YAML::Node node_;
  std::string file_;
  std::string what_;
  std::set<std::string> used_;
};

}  // namespace freeturn
