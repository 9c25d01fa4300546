#include "freeturn/job/yaml_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

namespace freeturn {

SourceLocation location_of(const YAML::Node& node, const std::string& file) {
  SourceLocation loc{file, 0, 0};
  if (node.IsDefined()) {
    const YAML::Mark m = node.Mark();
    if (m.line >= 0) {
      loc.line = m.line + 1;
      loc.column = m.column + 1;
    }
  }
  return loc;
}

YAML::Node load_yaml_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return YAML::Load(text.str());
  } catch (const YAML::ParserException& e) {
    SourceLocation loc{path, e.mark.line + 1, e.mark.column + 1};
    throw InputError(loc, "YAML syntax error: " + e.msg);
  }
}

MapReader::MapReader(const YAML::Node& node, std::string file, std::string what)
    : node_(node), file_(std::move(file)), what_(std::move(what)) {
  if (!node_.IsMap())
    throw InputError(location_of(node_, file_), what_ + " must be a map of keys to values");
}

bool MapReader::has(const std::string& key) const {
  return static_cast<bool>(node_[key]);
}  // const: no insert

YAML::Node MapReader::child(const std::string& key) {
  used_.insert(key);
  YAML::Node value = std::as_const(node_)[key];
  if (!value)
    throw InputError(location_of(node_, file_), what_ + " is missing the key '" + key + "'");
  return value;
}

std::optional<YAML::Node> MapReader::optional_child(const std::string& key) {
  used_.insert(key);
  YAML::Node value = std::as_const(node_)[key];
  if (!value) return std::nullopt;
  return value;
}

double MapReader::read_number(const YAML::Node& value, const std::string& key) const {
  const SourceLocation loc = location_of(value, file_);
  if (!value.IsScalar()) throw InputError(loc, what_ + "." + key + " must be a number");
  double v;
  const std::string& s = value.Scalar();
  // yaml-cpp accepts ".nan"/".inf" as doubles; they must never reach the geometry.
  if (!YAML::convert<double>::decode(value, v))
    throw InputError(loc, what_ + "." + key + " must be a number, not '" + s + "'");
  if (!std::isfinite(v))
    throw InputError(loc, what_ + "." + key + " must be a finite number, not '" + s + "'");
  return v;
}

double MapReader::number(const std::string& key) {
  return read_number(child(key), key);
}

double MapReader::number(const std::string& key, double fallback) {
  auto value = optional_child(key);
  return value ? read_number(*value, key) : fallback;
}

double MapReader::positive(const std::string& key) {
  const YAML::Node value = child(key);
  const double v = read_number(value, key);
  if (!(v > 0))
    throw InputError(location_of(value, file_),
                     what_ + "." + key + " must be greater than 0, not " + value.Scalar());
  return v;
}

double MapReader::positive(const std::string& key, double fallback) {
  if (has(key)) return positive(key);
  used_.insert(key);
  return fallback;
}

double MapReader::non_negative(const std::string& key, double fallback) {
  auto value = optional_child(key);
  if (!value) return fallback;
  const double v = read_number(*value, key);
  if (v < 0)
    throw InputError(location_of(*value, file_),
                     what_ + "." + key + " must not be negative, not " + value->Scalar());
  return v;
}

std::string MapReader::text(const std::string& key) {
  const YAML::Node value = child(key);
  if (!value.IsScalar() || value.Scalar().empty())
    throw InputError(location_of(value, file_), what_ + "." + key + " must be a non-empty string");
  return value.Scalar();
}

void MapReader::finish() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (!used_.count(key))
      throw InputError(location_of(it->first, file_), "unknown key '" + key + "' in " + what_);
  }
}

void MapReader::fail(const std::string& key, const std::string& what) const {
  YAML::Node value = std::as_const(node_)[key];
  throw InputError(location_of(value ? value : node_, file_), what);
}

}  // namespace freeturn
