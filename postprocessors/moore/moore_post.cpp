// Moore Nanotech, NanoCAM-style slow-tool-servo programs (shared/notes/nc-formats.md):
// a header (metric, ZX plane, tool offset, C homing with M80), inverse-time feed G93 with
// F the block time in seconds (modal: written when it changes), one "C… X… Z…" line per
// point (B too on 4-axis machines), C wrapped to [0, 360), and a footer that leaves
// C-axis mode (M79). Long programs are split: the main program calls child point files
// with M98(<name>_NNN.nc), each ending in M99. The codes whose meaning public programs do
// not settle (the header and footer lines) come from the machine YAML.
#include <cmath>
#include <cstdio>
#include <string>

#include "freeturn/post_format.hpp"
#include "freeturn/post_plugin.h"
#include "freeturn/post_settings.hpp"

namespace {

struct MoorePost {
  const ft_program_info* info = nullptr;
  const ft_writer* writer = nullptr;
  std::string header, footer, spindle;
  double retract = 1.0, approach_feed = 200, child_blocks = 0;
  int time_decimals = 6;
  bool first = true;
  double last_time = -1;
  double first_z = 0;
  long long in_child = 0;
  int children = 0;
  std::string line;

  bool put(const std::string& s) { return writer->write(writer->context, s.data(), s.size()) == 0; }
};

void* create(const ft_program_info* info, const ft_writer* writer, char* error, size_t size) {
  auto* p = new MoorePost;
  p->info = info;
  p->writer = writer;
  freeturn::post::FlatSettings s;
  std::string message;
  double time_decimals = 6;
  bool ok = s.parse(info->dialect_settings, message) &&
            s.number("retract", 1.0, p->retract, message) &&
            s.number("approach_feed", 200.0, p->approach_feed, message) &&
            s.number("child_blocks", 0.0, p->child_blocks, message) &&
            s.number("time_decimals", 6.0, time_decimals, message);
  p->header = freeturn::post::unescape_lines(
      s.text("header", "G71 G01 G18 G40 G63 G90 G94 G54\\nT0101\\nG53 Z-180.\\nM80\\nG09 C0.0\\nG92 C0.0"));
  p->footer = freeturn::post::unescape_lines(s.text("footer", "G53 Z-180.\\nM79\\nG52\\nT0000\\nM30"));
  p->spindle = s.text("spindle", "M03");
  p->time_decimals = static_cast<int>(time_decimals);
  if (ok && !s.unknown_key().empty()) {
    message = "unknown moore setting '" + s.unknown_key() +
              "' (known: header, footer, spindle, retract, approach_feed, child_blocks, time_decimals)";
    ok = false;
  }
  if (ok && info->layout.count < 3) {
    message = "the moore post writes slow-tool-servo programs: the machine needs a C axis";
    ok = false;
  }
  if (!ok) {
    std::snprintf(error, size, "%s", message.c_str());
    delete p;
    return nullptr;
  }
  return p;
}

int begin(void* handle, char* error, size_t size) {
  auto* p = static_cast<MoorePost*>(handle);
  std::string head = "( " + std::string(p->info->program_name) + " for " + p->info->machine_name +
                     ", written by freeturn )\n" + p->header + "\n";
  char rpm[48];
  head += p->spindle + " S";
  head.append(rpm, static_cast<std::size_t>(freeturn::post::format_fixed(p->info->spindle_rpm, 3, rpm)));
  head += "\n";
  if (!p->put(head)) {
    std::snprintf(error, size, "cannot write the header");
    return 1;
  }
  return 0;
}

// The axis words of a block, in the machine's order, C first as NanoCAM writes them.
bool append_block(MoorePost* p, const ft_block& b) {
  const ft_axis_layout& l = p->info->layout;
  bool ok = true;
  for (const char letter : {'C', 'X', 'Z', 'B'}) {
    for (int i = 0; i < l.count; ++i) {
      if (l.letters[i] != letter) continue;
      const double v = letter == 'X' ? b.x : letter == 'Z' ? b.z : letter == 'C' ? b.c : b.b;
      if (!p->line.empty() && p->line.back() != '\n') p->line.push_back(' ');
      ok = ok && freeturn::post::append_word(p->line, letter, v, l.decimals[i],
                                             letter == 'C' && p->info->c_wrapped);
    }
  }
  return ok;
}

int blocks(void* handle, const ft_block* b, size_t count, char* error, size_t size) {
  auto* p = static_cast<MoorePost*>(handle);
  for (size_t k = 0; k < count; ++k) {
    p->line.clear();
    if (p->first) {
      // Approach in feed per minute, above the first point, then down to it.
      p->first = false;
      p->first_z = b[k].z;
      ft_block above = b[k];
      above.z += p->retract;
      p->line = "G94 G01";
      if (!append_block(p, above)) goto bad;
      p->line += " F";
      freeturn::post::append_number(p->line, p->approach_feed, 3);
      p->line += "\n";
      if (!append_block(p, b[k])) goto bad;
      p->line += "\n";
      if (!p->put(p->line)) goto io;
      continue;
    }
    if (p->child_blocks > 0 && p->in_child == 0) {
      // A new child point file, called from the main program.
      char name[512];
      std::snprintf(name, sizeof name, "%s_%03d.nc", p->info->program_name, ++p->children);
      std::string call = std::string("M98(") + name + ")\n";
      if (p->writer->select_main(p->writer->context) != 0 || !p->put(call) ||
          p->writer->open_file(p->writer->context, name) != 0) {
        std::snprintf(error, size, "cannot start the child program %s", name);
        return 1;
      }
      p->last_time = -1;  // every child states its feed
    }
    if (b[k].time != p->last_time) {
      p->line = "G93 F";
      freeturn::post::append_number(p->line, b[k].time, p->time_decimals);
      p->line += "\n";
      p->last_time = b[k].time;
    }
    if (!append_block(p, b[k])) goto bad;
    p->line += "\n";
    if (p->child_blocks > 0 && ++p->in_child >= static_cast<long long>(p->child_blocks)) {
      p->line += "M99\n";
      p->in_child = 0;
    }
    if (!p->put(p->line)) goto io;
  }
  return 0;
bad:
  std::snprintf(error, size, "a block has an axis value that is not a finite number");
  return 1;
io:
  std::snprintf(error, size, "cannot write a block");
  return 1;
}

int end(void* handle, char* error, size_t size) {
  auto* p = static_cast<MoorePost*>(handle);
  std::string tail;
  if (p->child_blocks > 0 && p->in_child > 0) tail += "M99\n";
  if (!tail.empty() && !p->put(tail)) goto io;
  if (p->children > 0 && p->writer->select_main(p->writer->context) != 0) goto io;
  tail = "G94\nG01 Z";
  freeturn::post::append_number(tail, p->first_z + p->retract, 6);
  tail += " F";
  freeturn::post::append_number(tail, p->approach_feed, 3);
  tail += "\n" + p->footer + "\n";
  if (!p->put(tail)) goto io;
  return 0;
io:
  std::snprintf(error, size, "cannot write the program end");
  return 1;
}

void destroy(void* handle) { delete static_cast<MoorePost*>(handle); }

const ft_post kPost = {FREETURN_POST_ABI_VERSION, "moore", create, begin, blocks, end, destroy};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ft_post* freeturn_post_entry(void) {
  return &kPost;
}
