// Precitech Nanoform (UPx controller), DIFFSYS-style data (shared/notes/nc-formats.md):
// ';' comment lines, then one "C…X…Z…" line per point with no spaces. Public facts are
// thin, so every code around the data — the header, switching PVT on, the footer — is a
// template in the machine YAML. The data lines carry no time: the controller runs them
// at one block time (PVT, paper 001), given in the header from the program's constant
// block time; a program whose block times vary is refused unless `time_word` names a
// word to carry each block's time. Profile programs (X and Z only) run at the job's feed,
// stated once as a feed line.
#include <cmath>
#include <cstdio>
#include <string>

#include "freeturn/post_format.hpp"
#include "freeturn/post_plugin.h"
#include "freeturn/post_settings.hpp"

namespace {

struct PrecitechPost {
  const ft_program_info* info = nullptr;
  const ft_writer* writer = nullptr;
  std::string header, footer, time_word, feed_line;
  bool profile = false;
  bool first = true;
  double block_time = -1;
  std::string line;

  bool put(const std::string& s) { return writer->write(writer->context, s.data(), s.size()) == 0; }
};

void* create(const ft_program_info* info, const ft_writer* writer, char* error, size_t size) {
  auto* p = new PrecitechPost;
  p->info = info;
  p->writer = writer;
  freeturn::post::FlatSettings s;
  std::string message;
  bool ok = s.parse(info->dialect_settings, message);
  p->header = freeturn::post::unescape_lines(s.text("header", "; PVT mode\\n; G08"));
  p->footer = freeturn::post::unescape_lines(s.text("footer", "; end\\nM30"));
  p->time_word = s.text("time_word", "");
  p->feed_line = s.text("feed_line", "G01 F");
  p->profile = true;
  for (int i = 0; i < info->layout.count; ++i)
    if (info->layout.letters[i] == 'C') p->profile = false;
  if (ok && !s.unknown_key().empty()) {
    message = "unknown precitech setting '" + s.unknown_key() + "' (known: header, footer, time_word, feed_line)";
    ok = false;
  }
  if (ok && p->time_word.size() > 1) {
    message = "time_word must be one letter";
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
  auto* p = static_cast<PrecitechPost*>(handle);
  std::string head = "; " + std::string(p->info->program_name) + " for " + p->info->machine_name +
                     ", written by freeturn\n; interpolation " +
                     (p->info->interpolation == 1 ? "PVT" : "linear") + "\n" + p->header + "\n";
  if (p->profile) {
    head += p->feed_line;
    freeturn::post::append_number(head, p->info->feed, 3);
    head += "\n";
  }
  if (!p->put(head)) {
    std::snprintf(error, size, "cannot write the header");
    return 1;
  }
  return 0;
}

int blocks(void* handle, const ft_block* b, size_t count, char* error, size_t size) {
  auto* p = static_cast<PrecitechPost*>(handle);
  const ft_axis_layout& l = p->info->layout;
  for (size_t k = 0; k < count; ++k) {
    p->line.clear();
    if (!p->first && p->time_word.empty() && !p->profile) {
      if (p->block_time < 0) {
        p->block_time = b[k].time;
        p->line = "; block time ";
        freeturn::post::append_number(p->line, b[k].time, 9);
        p->line += " s\n";
      } else if (std::abs(b[k].time - p->block_time) > 1e-9 * p->block_time) {
        std::snprintf(error, size,
                      "block times vary (%.9g s, then %.9g s) and this dialect writes none: use "
                      "equal-angle points, or set time_word in the machine's precitech settings",
                      p->block_time, b[k].time);
        return 1;
      }
    }
    for (const char letter : {'C', 'X', 'Z', 'B'})
      for (int i = 0; i < l.count; ++i)
        if (l.letters[i] == letter) {
          const double v = letter == 'X' ? b[k].x : letter == 'Z' ? b[k].z : letter == 'C' ? b[k].c : b[k].b;
          if (!freeturn::post::append_word(p->line, letter, v, l.decimals[i],
                                           letter == 'C' && p->info->c_wrapped)) {
            std::snprintf(error, size, "block %zu: %c is not a finite number", k, letter);
            return 1;
          }
        }
    if (!p->first && !p->time_word.empty())
      freeturn::post::append_word(p->line, p->time_word[0], b[k].time, 9);
    p->first = false;
    p->line += '\n';
    if (!p->put(p->line)) {
      std::snprintf(error, size, "cannot write block %zu", k);
      return 1;
    }
  }
  return 0;
}

int end(void* handle, char* error, size_t size) {
  auto* p = static_cast<PrecitechPost*>(handle);
  if (!p->put(p->footer + "\n")) {
    std::snprintf(error, size, "cannot write the program end");
    return 1;
  }
  return 0;
}

void destroy(void* handle) { delete static_cast<PrecitechPost*>(handle); }

const ft_post kPost = {FREETURN_POST_ABI_VERSION, "precitech", create, begin, blocks, end, destroy};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ft_post* freeturn_post_entry(void) {
  return &kPost;
}
