// freeturn plugins: the post-processors found and the machines that use them.
#include <cstdio>
#include <string>

#include "cli_options.hpp"
#include "commands.hpp"
#include "freeturn/freeturn.hpp"

namespace freeturn::cli {

int run_plugins(const PluginsArgs&) {
  const std::vector<InstalledPost> posts = installed_posts(yaml_byte_bound());
  if (posts.empty()) std::printf("no post-processors found\n");
  for (const InstalledPost& post : posts) {
    std::printf("%s  (%s)  %s\n", post.name.c_str(), post.path.c_str(), post.status.c_str());
    for (const MachineDescription& m : post.machines) {
      std::string layout;
      for (const AxisSpec& a : m.axes) layout += axis_letter(a.axis);
      const std::string b = m.has(Axis::kB) ? ", B " + std::to_string(static_cast<int>(m.b_min_deg)) +
                                                  "…" + std::to_string(static_cast<int>(m.b_max_deg)) + "°"
                                            : "";
      std::printf("    %-24s axes %-5s C %s%s\n", m.name.c_str(), layout.c_str(),
                  m.has(Axis::kC) ? (m.c_wrapped ? "wrapped" : "accumulating") : "-", b.c_str());
    }
    for (const std::string& e : post.unreadable_machines) std::printf("    %s\n", e.c_str());
  }
  return kExitOk;
}

}  // namespace freeturn::cli
