#include "freeturn/job/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "freeturn/core/number_text.hpp"
#include "freeturn/core/utf8.hpp"

#include <yaml-cpp/depthguard.h>

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

namespace {

// Line and column (1-based) of a byte offset.
SourceLocation location_at(const std::string& text, std::size_t offset, const std::string& file) {
  SourceLocation loc{file, 1, 1};
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++loc.line;
      loc.column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++loc.column;  // a column per character, not per UTF-8 continuation byte
    }
  }
  return loc;
}

// Bytes no YAML file of ours means: a byte-order mark past the start (a file pasted into
// another), NUL and other control characters (a binary file).
void refuse_stray_bytes(const std::string& text, const std::string& file) {
  const std::size_t bom = text.find("\xEF\xBB\xBF", 1);
  if (bom != std::string::npos)
    throw InputError(location_at(text, bom, file),
                     "a byte-order mark inside the file (two files joined?); it may only "
                     "open the file");
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char ch = static_cast<unsigned char>(text[i]);
    if ((ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') || ch == 0x7F) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X", ch);
      throw InputError(location_at(text, i, file),
                       std::string("a control character (") + code +
                           ") in the file: not a YAML text file");
    }
    // YAML is UTF-8 here: a Latin-1 "für" would reach the report as bytes no reader of
    // UTF-8 (JSON, HTML) accepts.
    if (ch >= 0x80) {
      const std::size_t n = utf8_length(text, i);
      if (n == 0) {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02X", ch);
        throw InputError(location_at(text, i, file),
                         std::string("the byte ") + code +
                             " is not UTF-8 (a Latin-1 or Windows-1252 character?): save the "
                             "file as UTF-8");
      }
      i += n - 1;
    }
  }
}

// The file's text and where each line starts, so that a node's mark (0-based line and
// column) finds its byte at once: searched from the top for every scalar, a 4 MiB file of
// short lines would take minutes.
struct SourceText {
  const std::string& text;
  std::vector<std::size_t> line_starts;

  explicit SourceText(const std::string& t) : text(t) {
    line_starts.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts.push_back(i + 1);
  }
  std::size_t offset_of(int line, int column) const {
    if (line < 0 || static_cast<std::size_t>(line) >= line_starts.size()) return text.size();
    return std::min(text.size(), line_starts[static_cast<std::size_t>(line)] + column);
  }
};

// A quoted scalar must close on the line it opens: a missing quote otherwise swallows the
// keys that follow it, and the file reads as something else. (Line breaks in a value are
// written as \n, or as a block scalar.)
void refuse_open_quote(const YAML::Node& node, const SourceText& source, const std::string& file) {
  const YAML::Mark m = node.Mark();
  if (m.line < 0) return;
  const std::string& text = source.text;
  std::size_t i = source.offset_of(m.line, m.column);
  if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) return;
  const char quote = text[i];
  for (++i; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '\n' || ch == '\r') break;
    if (quote == '"' && ch == '\\') {
      ++i;
      continue;
    }
    if (ch == quote) {
      if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;  // '' is a quote inside a single-quoted value
        continue;
      }
      return;
    }
  }
  throw InputError(SourceLocation{file, m.line + 1, m.column + 1},
                   std::string("the value opened by ") + quote +
                       " does not close on its line (a missing closing quote?)");
}

// How many values the walk below may visit. An alias (`*name`) stands for its anchor's whole
// value, so nine aliases of nine aliases of ... a 554-byte file stands for 9^12 values,
// and a walk of them (this one, or a reader's) would not end in a lifetime. Written out,
// a file of n bytes holds at most about 2n values (a key and an empty value take two
// bytes, "a:"); a file that reuses a block through aliases a few times stays far below
// the floor of a million, which takes a fraction of a second to walk.
std::size_t value_budget(const std::string& text) {
  return std::max<std::size_t>(1'000'000, 2 * text.size() + 64);
}

// Walks the tree: duplicate keys and quoted values left open; `budget`, the values still
// allowed (value_budget).
void check_tree(const YAML::Node& node, const SourceText& text, const std::string& file, int depth,
                std::size_t& budget) {
  if (depth > kMaxYamlDepth)
    throw InputError(location_of(node, file),
                     "nested more than " + std::to_string(kMaxYamlDepth) + " levels deep");
  if (budget == 0)
    throw InputError(location_of(node, file),
                     "the file stands for more values than it could hold written out: its "
                     "aliases ('*name') repeat their anchors' values into the millions; write "
                     "the values out, or reuse fewer of them");
  --budget;
  if (node.IsScalar()) {
    if (node.Tag() == "!") refuse_open_quote(node, text, file);
    return;
  }
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) check_tree(item, text, file, depth + 1, budget);
    return;
  }
  if (!node.IsMap()) return;
  std::set<std::string> keys;
  for (auto it = node.begin(); it != node.end(); ++it) {
    check_tree(it->first, text, file, depth + 1, budget);
    if (it->first.IsScalar() && !keys.insert(it->first.Scalar()).second)
      throw InputError(location_of(it->first, file),
                       "the key '" + it->first.Scalar() +
                           "' appears twice in this map (the first would silently win)");
    check_tree(it->second, text, file, depth + 1, budget);
  }
}

// A document marker ("---" or "..." at the start of a line, then a blank or the end of the
// line: YAML ends any scalar there) after content, or content after a "...", begins a
// second document. The first document may open with "---".
void refuse_second_document(const std::string& text, const std::string& file) {
  bool content = false, ended = false;
  int line = 0;
  for (std::size_t at = 0; at < text.size(); at = std::min(text.find('\n', at), text.size()) + 1) {
    ++line;
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string_view l(text.data() + at, end - at);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    const auto marker = [&](std::string_view m) {
      return l.starts_with(m) && (l.size() == 3 || l[3] == ' ' || l[3] == '\t');
    };
    const std::size_t first = l.find_first_not_of(" \t");
    const bool blank = first == std::string_view::npos || l[first] == '#';
    if (marker("---") && !content && !ended) {
      content = true;  // the first document's explicit start
      continue;
    }
    if (marker("---") || (ended && !blank))
      throw InputError(SourceLocation{file, line, 1},
                       "a second YAML document: a job or machine file holds one");
    if (marker("...")) {
      ended = true;
      continue;
    }
    if (!blank) content = true;
  }
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(path, "no such file");
  if (std::filesystem::is_directory(status))
    throw InputError(path, "is a directory, not a YAML file");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, "is not a regular file (a device, pipe or socket): give a YAML file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read the file's size");
  if (size > max_bytes)
    throw InputError(path, "the file has " + std::to_string(size) + " bytes, over the " +
                               std::to_string(max_bytes) +
                               "-byte bound for a YAML file (docs/robustness.md)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return load_yaml_text(buffer.str(), path, max_bytes);
}

YAML::Node load_yaml_text(const std::string& text, const std::string& path, std::uintmax_t max_bytes) {
  if (text.size() > max_bytes)
    throw InputError(path, "the text has " + std::to_string(text.size()) + " bytes, over the " +
                               std::to_string(max_bytes) + "-byte bound for YAML");
  refuse_stray_bytes(text, path);
  refuse_second_document(text, path);
  YAML::Node root;
  try {
    // Load, not LoadAll: LoadAll (yaml-cpp 0.7) can loop without end on a stray ',' at the
    // top level; the markers above settle how many documents there are.
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own bound on nesting, met before check_tree's: its message says "bad file".
    SourceLocation loc{path, e.mark.line + 1, e.mark.column + 1};
    throw InputError(loc, "the YAML is nested more than " + std::to_string(kMaxYamlDepth) +
                              " levels deep (" + std::to_string(e.depth()) + " here)");
  } catch (const YAML::ParserException& e) {
    SourceLocation loc{path, e.mark.line + 1, e.mark.column + 1};
    throw InputError(loc, "YAML syntax error: " + e.msg);
  }
  std::size_t budget = value_budget(text);
  check_tree(root, SourceText(text), path, 0, budget);
  return root;
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

void MapReader::refuse_empty(const YAML::Node& value, const std::string& key,
                             const std::string& needed) const {
  if (!value.IsNull()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key)
      throw InputError(location_of(it->first, file_),
                       what_ + "." + key + " has no value: it must be " + needed);
}

double MapReader::read_number(const YAML::Node& value, const std::string& key) const {
  refuse_empty(value, key, "a number");
  const SourceLocation loc = location_of(value, file_);
  if (!value.IsScalar()) throw InputError(loc, what_ + "." + key + " must be a number");
  double v;
  const std::string& s = value.Scalar();
  // yaml-cpp reads numbers through a stream in the global C++ locale (a German one stops
  // at the '.' of "1.25"): the number is read locale-free; yaml-cpp only names the YAML
  // forms of infinity and NaN (".inf", ".nan"), which must never reach the geometry.
  if (!parse_number(s, v)) {
    double special;
    if (!YAML::convert<double>::decode(value, special) || std::isfinite(special))
      throw InputError(loc, what_ + "." + key + " must be a number, not '" + s + "'");
    v = special;
  }
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

double MapReader::at_least(const std::string& key, double fallback, double lo,
                           const std::string& unit, const std::string& why) {
  auto value = optional_child(key);
  if (!value) return fallback;
  const double v = read_number(*value, key);
  if (!(v >= lo))
    throw InputError(location_of(*value, file_), what_ + "." + key + " must be at least " +
                                                     significant_text(lo, 6) + unit + ", not " +
                                                     value->Scalar() + ": " + why);
  return v;
}

double MapReader::in_range(const std::string& key, double fallback, double lo, double hi,
                           bool open_low, const std::string& unit) {
  auto value = optional_child(key);
  if (!value) return fallback;
  const double v = read_number(*value, key);
  if (!(open_low ? v > lo : v >= lo) || !(v <= hi)) {
    const std::string bounds = (open_low ? "(" : "[") + significant_text(lo, 6) + ", " +
                               significant_text(hi, 6) + "]" + unit;
    throw InputError(location_of(*value, file_), what_ + "." + key + " must be within " +
                                                     bounds + ", not " + value->Scalar());
  }
  return v;
}

double MapReader::in_range(const std::string& key, double lo, double hi, bool open_low,
                           const std::string& unit) {
  child(key);  // an error when it is missing
  return in_range(key, 0.0, lo, hi, open_low, unit);
}

std::string MapReader::text(const std::string& key) {
  const YAML::Node value = child(key);
  refuse_empty(value, key, "a non-empty string");
  if (!value.IsScalar() || value.Scalar().empty())
    throw InputError(location_of(value, file_), what_ + "." + key + " must be a non-empty string");
  return value.Scalar();
}

std::string MapReader::file_name(const std::string& key) {
  std::string name = text(key);
  if (name.size() > 100)
    fail(key, what_ + " " + key + " has " + std::to_string(name.size()) +
                  " characters; it names files, so at most 100");
  const auto allowed = [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           ch == '-' || ch == '_' || ch == '.';
  };
  if (!std::all_of(name.begin(), name.end(), allowed))
    fail(key, what_ + " " + key + " '" + escape_control_bytes(name) +
                  "' must use only letters, digits, '-', '_' and '.' (it names files)");
  // A file whose name begins with '.' is hidden, and one that begins with '-' is read as
  // an option by the commands a user runs on it (`rm -rf.moore….nc`).
  if (name[0] == '.' || name[0] == '-')
    fail(key, what_ + " " + key + " '" + name +
                  "' must begin with a letter, a digit or '_' (it names files: a leading '" +
                  name[0] + "' " + (name[0] == '.' ? "hides them" : "reads as a command's option") +
                  ")");
  return name;
}

void MapReader::finish() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (!used_.count(key))
      throw InputError(location_of(it->first, file_), "unknown key '" + key + "' in " + what_);
  }
}

SourceLocation MapReader::place(const std::string& key) const {
  YAML::Node value = std::as_const(node_)[key];
  return location_of(value ? value : node_, file_);
}

void MapReader::fail(const std::string& key, const std::string& what) const {
  throw InputError(place(key), what);
}

}  // namespace freeturn
