// freeturn plugins: the post-processors found and the machines that use them.
#include <cstdio>
#include <filesystem>

#include "cli_options.hpp"
#include "commands.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/post/post_loader.hpp"

namespace freeturn::cli {

int run_plugins(const std::vector<std::string>& args) {
  if (!args.empty()) {
    std::fprintf(stderr, "usage: freeturn plugins\n");
    return kExitBadInput;
  }
  const std::uintmax_t yaml_bound = yaml_byte_bound();
  const auto plugins = find_plugins();
  if (plugins.empty()) std::printf("no post-processors found\n");
  for (const auto& [name, path] : plugins) {
    std::string status = "ok";
    try {
      PostPlugin::load_file(path);
    } catch (const InputError& e) {
      status = e.problem();
    }
    std::printf("%s  (%s)  %s\n", name.c_str(), path.c_str(), status.c_str());
    for (const std::string& folder : machine_search_path()) {
      std::error_code ec;
      for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        if (entry.path().extension() != ".yaml") continue;
        try {
          const MachineDescription m = load_machine(entry.path().string(), yaml_bound);
          if (m.plugin != name) continue;
          std::string layout;
          for (const AxisSpec& a : m.axes) layout += axis_letter(a.axis);
          std::printf("    %-24s axes %-5s C %s%s\n", m.name.c_str(), layout.c_str(),
                      m.has(Axis::kC) ? (m.c_wrapped ? "wrapped" : "accumulating") : "-",
                      m.has(Axis::kB) ? (", B " + std::to_string(static_cast<int>(m.b_min_deg)) + "…" +
                                         std::to_string(static_cast<int>(m.b_max_deg)) + "°")
                                            .c_str()
                                      : "");
        } catch (const InputError& e) {
          std::printf("    %s: %s\n", entry.path().string().c_str(), e.what());
        }
      }
    }
  }
  return kExitOk;
}

}  // namespace freeturn::cli
