// ISO 6983 / RS-274 G-code that LinuxCNC's interpreter accepts (shared/notes/nc-formats.md):
// G21 (metric; never G71, a lathe cycle in LinuxCNC 2.9), G18 (ZX plane), G8 (radius
// mode), inverse-time feed G93 with F on every G1 line (F = 1 / block time in minutes),
// C accumulating, no Moore-only codes. Comments in parentheses.
#include <cstdio>
#include <cstring>
#include <string>

#include "freeturn/post_format.hpp"
#include "freeturn/post_plugin.h"
#include "freeturn/post_settings.hpp"

namespace {

struct IsoPost {
  const ft_program_info* info = nullptr;
  const ft_writer* writer = nullptr;
  double retract = 1.0;        // mm above the first point for the approach
  double approach_feed = 20;   // mm/min for the plunge to the first point
  double first_z = 0;
  bool first = true;
  std::string line;

  bool put(const std::string& s) { return writer->write(writer->context, s.data(), s.size()) == 0; }

  void append_axis(char letter, double value, int decimals) {
    char buf[48];
    buf[0] = letter;
    const int n = letter == 'C' && info->c_wrapped
                      ? freeturn::post::format_wrapped_degrees(value, decimals, buf + 1)
                      : freeturn::post::format_fixed(value, decimals, buf + 1);
    line.push_back(' ');
    line.append(buf, static_cast<std::size_t>(n + 1));
  }

  // The axis words of a block in the machine's order.
  bool append_axes(const ft_block& b, char* error, std::size_t size) {
    for (int i = 0; i < info->layout.count; ++i) {
      const char letter = info->layout.letters[i];
      const double v = letter == 'X' ? b.x : letter == 'Z' ? b.z : letter == 'C' ? b.c : b.b;
      if (!std::isfinite(v)) {
        std::snprintf(error, size, "axis %c is not a finite number", letter);
        return false;
      }
      append_axis(letter, v, info->layout.decimals[i]);
    }
    return true;
  }
};

void* create(const ft_program_info* info, const ft_writer* writer, char* error, size_t size) {
  auto* p = new IsoPost;
  p->info = info;
  p->writer = writer;
  freeturn::post::FlatSettings settings;
  std::string message;
  if (!settings.parse(info->dialect_settings, message) ||
      !settings.number("retract", 1.0, p->retract, message) ||
      !settings.number("approach_feed", 20.0, p->approach_feed, message)) {
    std::snprintf(error, size, "%s", message.c_str());
    delete p;
    return nullptr;
  }
  if (const std::string key = settings.unknown_key(); !key.empty()) {
    std::snprintf(error, size, "unknown iso setting '%s' (known: retract, approach_feed)", key.c_str());
    delete p;
    return nullptr;
  }
  return p;
}

int begin(void* handle, char* error, size_t size) {
  auto* p = static_cast<IsoPost*>(handle);
  std::string head = "%\n(" + std::string(p->info->program_name) + " for " + p->info->machine_name +
                     ", written by freeturn)\n";
  head += "G21 G18 G8 G90 G40 G94\n";
  if (!p->put(head)) {
    std::snprintf(error, size, "cannot write the program header");
    return 1;
  }
  return 0;
}

int blocks(void* handle, const ft_block* b, size_t count, char* error, size_t size) {
  auto* p = static_cast<IsoPost*>(handle);
  for (size_t k = 0; k < count; ++k) {
    p->line.clear();
    if (p->first) {
      // Approach: up, over, then down at a slow feed, then inverse-time feed.
      p->first = false;
      p->first_z = b[k].z;
      p->line = "G0";
      p->append_axis('Z', b[k].z + p->retract, 6);
      p->line += "\nG0";
      ft_block over = b[k];
      for (int i = 0; i < p->info->layout.count; ++i) {
        const char letter = p->info->layout.letters[i];
        if (letter == 'Z') continue;
        const double v = letter == 'X' ? over.x : letter == 'C' ? over.c : over.b;
        p->append_axis(letter, v, p->info->layout.decimals[i]);
      }
      p->line += "\nG1";
      p->append_axis('Z', b[k].z, 6);
      p->line += " F";
      char buf[48];
      p->line.append(buf, static_cast<std::size_t>(freeturn::post::format_fixed(p->approach_feed, 3, buf)));
      p->line += "\nG93\n";
    } else {
      if (!(b[k].time > 0)) {
        std::snprintf(error, size, "block %zu has no duration", k);
        return 1;
      }
      p->line = "G1";
      if (!p->append_axes(b[k], error, size)) return 1;
      // LinuxCNC's G93: F = 1 / (block time in minutes), on every G1 line.
      p->line += " F";
      char buf[48];
      p->line.append(buf, static_cast<std::size_t>(freeturn::post::format_fixed(60.0 / b[k].time, 6, buf)));
      p->line += '\n';
    }
    if (!p->put(p->line)) {
      std::snprintf(error, size, "cannot write block %zu", k);
      return 1;
    }
  }
  return 0;
}

int end(void* handle, char* error, size_t size) {
  auto* p = static_cast<IsoPost*>(handle);
  std::string tail = "G94\nG0";
  char buf[48];
  tail += " Z";
  tail.append(buf, static_cast<std::size_t>(freeturn::post::format_fixed(p->first_z + p->retract, 6, buf)));
  tail += "\nM2\n%\n";
  if (!p->put(tail)) {
    std::snprintf(error, size, "cannot write the program end");
    return 1;
  }
  return 0;
}

void destroy(void* handle) { delete static_cast<IsoPost*>(handle); }

const ft_post kPost = {FREETURN_POST_ABI_VERSION, "iso", create, begin, blocks, end, destroy};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ft_post* freeturn_post_entry(void) {
  return &kPost;
}
