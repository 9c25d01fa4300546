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

std::string escape_control_bytes(std::string_view text, bool keep_newlines) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if ((byte < 0x20 && !(keep_newlines && ch == '\n')) || byte == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else {
      out += ch;
    }
  }
  return out;
}

namespace {
std::string join(const std::string& where, const std::string& what) {
  return where.empty() ? what : where + ": " + what;
}
}  // namespace

InputError::InputError(std::string where, const std::string& what)
    : InputError(escape_control_bytes(where), escape_control_bytes(what, true), 0) {}

InputError::InputError(std::string where, std::string what, int)
    : std::runtime_error(join(where, what)), where_(std::move(where)), problem_(std::move(what)) {}

InputError::InputError(const SourceLocation& where, const std::string& what)
    : InputError(where.to_string(), what) {}

}  // namespace freeturn
