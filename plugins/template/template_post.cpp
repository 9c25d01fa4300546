// A template post-processor: copy it, rename it, and make its lines your dialect's
// (docs/writing-a-post.md). It builds against the installed headers alone:
//   g++ -std=c++20 -O2 -fPIC -shared -fvisibility=hidden -I<prefix>/include
//       template_post.cpp -o libfreeturn_post_template.so
// It writes one line per block, "X… Z… C… (B…) T…" with each axis at its machine's
// decimals and the block time in seconds, and no approach or retract: a dialect that
// writes them moves at post::clearance_z(info->top_z, info->z_away, retract, decimals),
// clear of the whole part (docs/writing-a-post.md, "The way in and out").
#include <cstdio>
#include <string>

#include "freeturn/post_format.hpp"
#include "freeturn/post_plugin.h"
#include "freeturn/post_settings.hpp"

namespace {

struct TemplatePost {
  const ft_program_info* info = nullptr;
  const ft_writer* writer = nullptr;
  std::string comment = ";";  // a setting: what starts a comment line
  std::string line;           // reused for every block: no allocation per block
};

bool put(TemplatePost* p, const std::string& s) {
  return p->writer->write(p->writer->context, s.data(), s.size()) == 0;
}

void* create(const ft_program_info* info, const ft_writer* writer, char* error, size_t size) {
  auto* p = new TemplatePost;
  p->info = info;
  p->writer = writer;
  freeturn::post::FlatSettings settings;
  std::string message;
  if (!settings.parse(info->dialect_settings, message)) {
    std::snprintf(error, size, "%s", message.c_str());
    delete p;
    return nullptr;
  }
  p->comment = settings.text("comment", ";");
  if (const std::string key = settings.unknown_key(); !key.empty()) {
    std::snprintf(error, size, "unknown template setting '%s' (known: comment)", key.c_str());
    delete p;
    return nullptr;
  }
  return p;
}

int begin(void* handle, char* error, size_t size) {
  auto* p = static_cast<TemplatePost*>(handle);
  if (!put(p, p->comment + " " + p->info->program_name + " for " + p->info->machine_name + "\n")) {
    std::snprintf(error, size, "cannot write the header");
    return 1;
  }
  return 0;
}

int blocks(void* handle, const ft_block* b, size_t count, char* error, size_t size) {
  auto* p = static_cast<TemplatePost*>(handle);
  char number[freeturn::post::kNumberCapacity];
  for (size_t k = 0; k < count; ++k) {
    p->line.clear();
    for (int i = 0; i < p->info->layout.count; ++i) {
      const char letter = p->info->layout.letters[i];
      const double v = letter == 'X' ? b[k].x : letter == 'Z' ? b[k].z : letter == 'C' ? b[k].c : b[k].b;
      const int n = freeturn::post::format_fixed(v, p->info->layout.decimals[i], number);
      if (n == 0) {
        std::snprintf(error, size, "block %zu: %c cannot be written (not finite, or too long)", k, letter);
        return 1;
      }
      if (!p->line.empty()) p->line += ' ';
      p->line += letter;
      p->line.append(number, static_cast<size_t>(n));
    }
    const int n = freeturn::post::format_fixed(b[k].time, 6, number);
    if (n == 0) {
      std::snprintf(error, size, "block %zu: its time cannot be written", k);
      return 1;
    }
    p->line += " T";
    p->line.append(number, static_cast<size_t>(n));
    p->line += '\n';
    if (!put(p, p->line)) {
      std::snprintf(error, size, "cannot write block %zu", k);
      return 1;
    }
  }
  return 0;
}

int end(void* handle, char* error, size_t size) {
  auto* p = static_cast<TemplatePost*>(handle);
  if (!put(p, p->comment + " end\n")) {
    std::snprintf(error, size, "cannot write the footer");
    return 1;
  }
  return 0;
}

void destroy(void* handle) { delete static_cast<TemplatePost*>(handle); }

const ft_post kPost = {FREETURN_POST_ABI_VERSION, "template", create, begin, blocks, end, destroy};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ft_post* freeturn_post_entry(void) {
  return &kPost;
}
