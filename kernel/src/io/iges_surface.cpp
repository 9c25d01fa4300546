#include "freeturn/io/iges_surface.hpp"

#include "freeturn/core/number_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/io/input_file.hpp"

namespace freeturn {
namespace {

struct Record {
  std::string data;  // columns 1-72
  int file_line = 0;
};

struct Sections {
  std::vector<Record> global, directory, parameter;
};

Sections read_sections(const std::string& path) {
  require_regular_file(path, "an IGES file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0, 0}, "cannot open the IGES file");
  Sections s;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line.size() < 73)
      throw InputError(SourceLocation{path, n, static_cast<int>(line.size()) + 1},
                       "IGES records are 80 columns with the section letter in column 73; "
                       "this line has " +
                           std::to_string(line.size()) + " characters");
    const char section = line[72];
    const Record r{line.substr(0, 72), n};
    switch (section) {
      case 'S': case 'T': break;
      case 'G': s.global.push_back(r); break;
      case 'D': s.directory.push_back(r); break;
      case 'P': s.parameter.push_back(r); break;
      case 'B': case 'C':
        throw InputError(SourceLocation{path, n, 73},
                         "binary or compressed IGES is not supported; export fixed ASCII");
      default:
        throw InputError(SourceLocation{path, n, 73},
                         std::string("unknown IGES section letter '") + section + "'");
    }
  }
  if (s.directory.empty())
    throw InputError(SourceLocation{path, 0, 0}, "no directory section: not an IGES file");
  return s;
}

// A section's free-format text: its records' data columns laid end to end, `width`
// characters each (72 in the global section, 64 in the parameter section), and where each
// character came from.
struct SectionText {
  std::string text;
  std::string path;
  std::vector<int> file_lines;  // of each record, in order
  std::size_t width = 72;

  void add(const Record& r) {
    text += r.data.substr(0, width);
    text.resize((file_lines.size() + 1) * width, ' ');  // records hold at least 72 columns
    file_lines.push_back(r.file_line);
  }
  // The file's line and 1-based column of the character at `offset` (the last one's, past
  // the end).
  SourceLocation at(std::size_t offset) const {
    if (file_lines.empty()) return SourceLocation{path, 0, 0};
    const std::size_t record = std::min(offset / width, file_lines.size() - 1);
    const std::size_t column = std::min(offset - record * width, width - 1);
    return SourceLocation{path, file_lines[record], static_cast<int>(column) + 1};
  }
};

// A free-format field and the offset in its section's text where it starts (after blanks).
struct Field {
  std::string text;
  std::size_t offset = 0;
};

// Splits free-format data into fields at `delimiter`, up to `terminator`, honouring
// Hollerith strings (nH…), which may contain either character. A string that claims more
// characters than the section holds is an error at its count.
std::vector<Field> split_fields(const SectionText& section, char delimiter, char terminator) {
  const std::string& text = section.text;
  std::vector<Field> fields;
  Field field;
  const auto start_of = [&](std::size_t i) {  // the first non-blank from i, within the field
    std::size_t k = i;
    while (k < text.size() && text[k] == ' ') ++k;
    return k;
  };
  std::size_t field_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if ((ch == 'H' || ch == 'h') && !field.text.empty()) {
      std::size_t digits = 0;
      while (digits < field.text.size() && field.text[digits] == ' ') ++digits;
      const std::string count = field.text.substr(digits);
      if (!count.empty() && count.find_first_not_of("0123456789") == std::string::npos) {
        std::size_t len = 0;
        const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), len);
        if (error != std::errc() || end != count.data() + count.size() || len > text.size() - i - 1)
          throw InputError(
              section.at(start_of(field_start)),
              "a Hollerith string of " + count + " characters runs past the end of the section");
        field.text = text.substr(i + 1, len);
        i += len;
        continue;
      }
    }
    if (ch == delimiter || ch == terminator) {
      field.offset = std::min(start_of(field_start), i);
      fields.push_back(std::move(field));
      field = Field{};
      field_start = i + 1;
      if (ch == terminator) return fields;
      continue;
    }
    field.text += ch;
  }
  field.offset = std::min(start_of(field_start), text.size());
  fields.push_back(std::move(field));
  return fields;
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(' ');
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(' ') - a + 1);
}

// An entity's parameters read in order, each error at its field's line and column.
class ParameterReader {
 public:
  // `entity` names the entity in messages ("entity 128 (directory line 1)").
  ParameterReader(SectionText section, std::vector<Field> fields, std::string entity)
      : section_(std::move(section)), fields_(std::move(fields)), entity_(std::move(entity)) {}

  double real(const std::string& what) {
    const Field& f = next(what);
    std::string t = trim(f.text);
    for (char& ch : t)
      if (ch == 'D' || ch == 'd') ch = 'E';
    double value = 0;
    if (!parse_finite(t, value))
      throw InputError(section_.at(f.offset),
                       entity_ + ": " + what + " must be a number, not '" + t + "'");
    return value;
  }
  std::size_t remaining() const { return fields_.size() - index_; }
  // Where the k-th parameter (0 the entity type: the entity as a whole) is; past the last,
  // where the data ends.
  SourceLocation at_field(std::size_t k) const {
    if (fields_.empty()) return section_.at(0);
    return section_.at(k < fields_.size() ? fields_[k].offset : fields_.back().offset);
  }
  std::size_t index() const { return index_; }  // of the next parameter to read

  int integer(const std::string& what) {
    const double v = real(what);
    if (v != std::floor(v) || std::abs(v) > 1e9)
      throw InputError(section_.at(fields_[index_ - 1].offset),
                       entity_ + ": " + what + " must be an integer");
    return static_cast<int>(v);
  }

 private:
  const Field& next(const std::string& what) {
    if (index_ >= fields_.size())
      throw InputError(section_.at(fields_.empty() ? 0 : fields_.back().offset),
                       entity_ + ": the parameter data ends before " + what);
    return fields_[index_++];
  }
  SectionText section_;
  std::vector<Field> fields_;
  std::size_t index_ = 0;
  std::string entity_;
};

struct Directory {
  int type = 0, parameter_start = 0, parameter_count = 0, transform = 0, form = 0;
  int line = 0;  // sequence number of its first record
  int file_line = 0;
};

int directory_field(const Record& r, int field, const std::string& path) {
  const std::string t = trim(r.data.substr(static_cast<std::size_t>(8 * field), 8));
  if (t.empty()) return 0;
  int value = 0;
  if (!parse_int(t, value))
    throw InputError(SourceLocation{path, r.file_line, 8 * field + 1},
                     "directory field " + std::to_string(field + 1) + " must be an integer, not '" +
                         t + "'");
  return value;
}

class IgesFile {
 public:
  explicit IgesFile(const std::string& path) : path_(path), sections_(read_sections(path)) {
    read_global();
    if (sections_.directory.size() % 2 != 0)
      throw InputError(SourceLocation{path_, sections_.directory.back().file_line, 1},
                       "the directory section has an odd number of records");
    for (std::size_t k = 0; k < sections_.directory.size(); k += 2) {
      const Record& a = sections_.directory[k];
      const Record& b = sections_.directory[k + 1];
      Directory d;
      d.type = directory_field(a, 0, path_);
      d.parameter_start = directory_field(a, 1, path_);
      d.transform = directory_field(a, 6, path_);
      d.parameter_count = directory_field(b, 3, path_);
      d.form = directory_field(b, 4, path_);
      d.line = static_cast<int>(k) + 1;
      d.file_line = a.file_line;
      entries_[d.line] = d;
    }
  }

  const std::map<int, Directory>& entries() const { return entries_; }

  ParameterReader parameters(const Directory& d) const {
    if (d.parameter_start < 1 || d.parameter_count < 1 ||
        static_cast<std::size_t>(d.parameter_start - 1 + d.parameter_count) >
            sections_.parameter.size())
      throw InputError(SourceLocation{path_, d.file_line, 9},
                       "the entity's parameter data pointer is outside the parameter section");
    // Columns 65-72 of a parameter record point back at the directory entry.
    SectionText section{{}, path_, {}, 64};
    for (int k = 0; k < d.parameter_count; ++k)
      section.add(sections_.parameter[static_cast<std::size_t>(d.parameter_start - 1 + k)]);
    std::vector<Field> fields = split_fields(section, delimiter_, terminator_);
    return ParameterReader(
        std::move(section), std::move(fields),
        "entity " + std::to_string(d.type) + " (directory line " + std::to_string(d.line) + ")");
  }

  // x ↦ R x + t of the entity's transformation chain (entity 124).
  // `from` is the directory entry that points at it (its line in the file).
  void transformation(int line, int from, Eigen::Matrix3d& r, Eigen::Vector3d& t,
                      int depth = 0) const {
    r.setIdentity();
    t.setZero();
    if (line == 0) return;
    const auto it = entries_.find(line);
    // The pointer is the directory entry's seventh field, columns 49-56.
    if (it == entries_.end() || it->second.type != 124 || depth > 16)
      throw InputError(SourceLocation{path_, from, 49},
                       "transformation pointer " + std::to_string(line) +
                           " does not name a transformation matrix (entity 124)");
    ParameterReader p = parameters(it->second);
    p.integer("the entity type");
    static const char* const kNames[3][4] = {
        {"R11", "R12", "R13", "T1"}, {"R21", "R22", "R23", "T2"}, {"R31", "R32", "R33", "T3"}};
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) r(row, col) = p.real(kNames[row][col]);
      t(row) = p.real(kNames[row][3]);
    }
    Eigen::Matrix3d r_outer;
    Eigen::Vector3d t_outer;
    transformation(it->second.transform, it->second.file_line, r_outer, t_outer, depth + 1);
    t = r_outer * t + t_outer;
    r = r_outer * r;
  }

  double millimetres_per_unit() const { return mm_per_unit_; }
  const std::string& path() const { return path_; }

 private:
  void read_global() {
    SectionText section{{}, path_, {}, 72};
    for (const Record& r : sections_.global) section.add(r);
    const std::string& text = section.text;
    // Fields 1 and 2 name the delimiters ("1H," and "1H;"), or are empty for the defaults.
    if (text.size() >= 3 && (text[0] == '1') && (text[1] == 'H' || text[1] == 'h'))
      delimiter_ = text[2];
    const std::vector<Field> g = split_fields(section, delimiter_, '\0');
    if (g.size() >= 2 && g[1].text.size() == 1) terminator_ = g[1].text[0];
    const std::vector<Field> fields = split_fields(section, delimiter_, terminator_);
    const auto field = [&](std::size_t k) { return k < fields.size() ? trim(fields[k].text) : ""; };
    // Where field k is, or where the section's text ends if it holds fewer fields.
    const auto field_at = [&](std::size_t k) {
      return section.at(k < fields.size() ? fields[k].offset : text.size());
    };
    const std::string scale = field(12), unit = field(13);
    std::string scale_number = scale;
    for (char& ch : scale_number)
      if (ch == 'D' || ch == 'd') ch = 'E';
    double scale_value = 1.0;
    if (!scale.empty() && (!parse_finite(scale_number, scale_value) || scale_value != 1.0))
      throw InputError(field_at(12), "model space scale " + scale + " is not supported (only 1.0)");
    static const std::map<int, double> kMillimetres = {{1, 25.4}, {2, 1.0},     {4, 304.8},
                                                       {6, 1000}, {8, 0.0254}, {9, 0.001},
                                                       {10, 10},  {11, 2.54e-5}};
    int flag = 2;
    const bool flag_read = unit.empty() || parse_int(unit, flag);
    const auto it = kMillimetres.find(flag);
    if (!flag_read || it == kMillimetres.end())
      throw InputError(field_at(13), "units flag " + unit + " is not supported (use 2 = mm)");
    // Field 15 names the unit. A file whose flag and name disagree was edited by hand or
    // written wrongly; which one is meant cannot be told, and 25.4× is no small error.
    static const std::map<int, std::vector<std::string>> kNames = {
        {1, {"IN", "INCH"}}, {2, {"MM"}},  {4, {"FT"}},  {6, {"M"}},
        {8, {"MIL"}},        {9, {"UM"}},  {10, {"CM"}}, {11, {"UIN"}}};
    std::string name = field(14);
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    if (!name.empty()) {
      const std::vector<std::string>& names = kNames.at(flag);
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw InputError(field_at(14), "the global section's units flag " + std::to_string(flag) +
                                           " (" + names.front() +
                                           ") disagrees with its units name '" + field(14) +
                                           "': correct one of them");
    }
    mm_per_unit_ = it->second;
  }

  std::string path_;
  Sections sections_;
  char delimiter_ = ',', terminator_ = ';';
  double mm_per_unit_ = 1.0;
  std::map<int, Directory> entries_;
};

nurbs::NurbsSurface read_entity_128(const IgesFile& file, const Directory& d) {
  ParameterReader p = file.parameters(d);
  if (p.integer("the entity type") != 128)
    throw InputError(p.at_field(0), "directory line " + std::to_string(d.line) +
                                        " points at parameters of another entity");
  const int k1 = p.integer("K1"), k2 = p.integer("K2"), m1 = p.integer("M1"),
            m2 = p.integer("M2");
  if (k1 < 1 || k2 < 1 || m1 < 1 || m2 < 1 || m1 > k1 || m2 > k2)
    throw InputError(p.at_field(1),
                     "entity 128 needs 1 ≤ M ≤ K in both directions (K1=" + std::to_string(k1) +
                         ", M1=" + std::to_string(m1) + ", K2=" + std::to_string(k2) +
                         ", M2=" + std::to_string(m2) + ")");
  for (int k = 1; k <= 5; ++k) p.integer("PROP" + std::to_string(k));
  // The counts decide the sizes below: they must be backed by that much data before
  // anything is allocated (a damaged K1 would otherwise ask for gigabytes).
  const long long needed = (static_cast<long long>(k1) + m1 + 2) + (static_cast<long long>(k2) + m2 + 2) +
                           4 * (static_cast<long long>(k1) + 1) * (static_cast<long long>(k2) + 1) + 4;
  if (needed > static_cast<long long>(p.remaining()))
    throw InputError(p.at_field(0),
                     "entity 128 with K1=" + std::to_string(k1) + ", K2=" + std::to_string(k2) +
                         ", M1=" + std::to_string(m1) + ", M2=" + std::to_string(m2) + " needs " +
                         std::to_string(needed) + " more parameters; the entity holds " +
                         std::to_string(p.remaining()));
  const std::size_t first_knot = p.index();
  std::vector<double> s(static_cast<std::size_t>(k1 + m1 + 2)), t(static_cast<std::size_t>(k2 + m2 + 2));
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = p.real("knot S(" + std::to_string(k) + ")");
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = p.real("knot T(" + std::to_string(k) + ")");
  const int nu = k1 + 1, nv = k2 + 1;
  std::vector<double> w(static_cast<std::size_t>(nu * nv));
  std::vector<nurbs::Vector3d> points(w.size());
  // The file runs the u index fastest; the net is row-major with u as the row.
  for (int k = 0; k < nu * nv; ++k)
    w[static_cast<std::size_t>((k % nu) * nv + k / nu)] = p.real("weight " + std::to_string(k));
  Eigen::Matrix3d r;
  Eigen::Vector3d shift;
  file.transformation(d.transform, d.file_line, r, shift);
  const double mm = file.millimetres_per_unit();
  for (int k = 0; k < nu * nv; ++k) {
    nurbs::Vector3d x;
    for (int c = 0; c < 3; ++c) x[c] = p.real("control point " + std::to_string(k));
    points[static_cast<std::size_t>((k % nu) * nv + k / nu)] = mm * (r * x + shift);
  }
  const std::size_t range = p.index();
  const double u0 = p.real("U0"), u1 = p.real("U1"), v0 = p.real("V0"), v1 = p.real("V1");
  nurbs::NurbsSurface surface;
  try {
    surface = nurbs::NurbsSurface(m1, m2, s, t, points, w);
  } catch (const InputError& e) {
    throw InputError(p.at_field(first_knot), "entity 128 (directory line " +
                                                 std::to_string(d.line) + "): " + e.where() + " " +
                                                 e.problem());
  }
  const double tol_u = 1e-9 * (surface.back_u() - surface.front_u());
  const double tol_v = 1e-9 * (surface.back_v() - surface.front_v());
  if (std::abs(u0 - surface.front_u()) > tol_u || std::abs(u1 - surface.back_u()) > tol_u ||
      std::abs(v0 - surface.front_v()) > tol_v || std::abs(v1 - surface.back_v()) > tol_v)
    throw InputError(p.at_field(range),
                     "entity 128 (directory line " + std::to_string(d.line) +
                         ") uses a parameter range narrower than its knots; sub-patches are "
                         "not supported (export the untrimmed surface)");
  return surface;
}

}  // namespace

std::vector<IgesSurfaceEntry> read_iges_surfaces(const std::string& path) {
  const IgesFile file(path);
  std::vector<IgesSurfaceEntry> out;
  for (const auto& [line, d] : file.entries())
    if (d.type == 128) out.push_back({line, read_entity_128(file, d)});
  return out;
}

nurbs::NurbsSurface read_iges_surface(const std::string& path, int directory_line) {
  std::vector<IgesSurfaceEntry> all = read_iges_surfaces(path);
  std::string lines;
  for (const IgesSurfaceEntry& e : all) lines += (lines.empty() ? "" : ", ") + std::to_string(e.directory_line);
  if (directory_line > 0) {
    for (IgesSurfaceEntry& e : all)
      if (e.directory_line == directory_line) return std::move(e.surface);
    throw InputError(path, "no rational B-spline surface (entity 128) at directory line " +
                               std::to_string(directory_line) + " (there are: " +
                               (lines.empty() ? "none" : lines) + ")");
  }
  if (all.empty()) throw InputError(path, "the file has no rational B-spline surface (entity 128)");
  if (all.size() > 1)
    throw InputError(path, "the file has " + std::to_string(all.size()) +
                               " B-spline surfaces (entity 128, directory lines " + lines +
                               "); choose one with 'entity'");
  return std::move(all.front().surface);
}

}  // namespace freeturn
