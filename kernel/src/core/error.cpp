#include "freeturn/core/error.hpp"

namespace freeturn {

std::string SourceLocation::to_string() const {
  std::string s = file;
  if (line > 0) {
    if (!s.empty()) s += ':';
    s += std::to_string(line);
    if (column > 0) {
      s += ':';
      s += std::to_string(column);
    }
  }
  return s;
}

namespace {
std::string join(const std::string& where, const std::string& what) {
  return where.empty() ? what : where + ": " + what;
}
}  // namespace

InputError::InputError(std::string where, const std::string& what)
    : std::runtime_error(join(where, what)), where_(std::move(where)), problem_(what) {}

InputError::InputError(const SourceLocation& where, const std::string& what)
    : InputError(where.to_string(), what) {}

}  // namespace freeturn
