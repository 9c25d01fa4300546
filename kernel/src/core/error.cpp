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
// A UTF-8 sequence at `text[i]` that a terminal acts on rather than shows: a C1 control
// (U+0080 to U+009F; U+009B is an 8-bit CSI to some terminals) or a bidirectional format
// character (U+200E, U+200F, U+202A to U+202E, U+2066 to U+2069), which can make a quoted
// name read as another. Its length in bytes (0 for anything else) and its code point.
struct Invisible {
  std::size_t length = 0;
  unsigned code = 0;
};
Invisible invisible_sequence_at(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  if (i + 1 < text.size() && byte(0) == 0xc2 && byte(1) >= 0x80 && byte(1) <= 0x9f)
    return {2, byte(1)};  // U+0080 to U+009F: the second byte is the code point
  if (i + 2 < text.size() && byte(0) == 0xe2 &&
      ((byte(1) == 0x80 &&
        (byte(2) == 0x8e || byte(2) == 0x8f || (byte(2) >= 0xaa && byte(2) <= 0xae))) ||
       (byte(1) == 0x81 && byte(2) >= 0xa6 && byte(2) <= 0xa9)))
    return {3, 0x2000u | ((byte(1) & 0x3fu) << 6) | (byte(2) & 0x3fu)};  // U+2000 to U+207F
  return {};
}

std::string join(const std::string& where, const std::string& what) {
  return where.empty() ? what : where + ": " + what;
}
}  // namespace

std::string escape_control_bytes(std::string_view text, bool keep_newlines) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte < 0x20 && !(keep_newlines && text[i] == '\n')) || byte == 0x7f) {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else if (const Invisible invisible = invisible_sequence_at(text, i); invisible.length > 0) {
      out += "\\u";
      for (int shift = 12; shift >= 0; shift -= 4) out += kHex[(invisible.code >> shift) & 0xf];
      i += invisible.length - 1;
    } else {
      out += text[i];
    }
  }
  return out;
}

InputError::InputError(std::string where, const std::string& what)
    : InputError(escape_control_bytes(where), escape_control_bytes(what, true), 0) {}

InputError::InputError(std::string where, std::string what, int)
    : std::runtime_error(join(where, what)), where_(std::move(where)), problem_(std::move(what)) {}

InputError::InputError(const SourceLocation& where, const std::string& what)
    : InputError(where.to_string(), what) {}

}  // namespace freeturn
