#include "freeturn/pipeline/installed_posts.hpp"

#include <filesystem>

#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/post/post_loader.hpp"

namespace freeturn {

std::vector<InstalledPost> installed_posts(std::uintmax_t max_yaml_bytes) {
  std::vector<InstalledPost> out;
  for (const auto& [name, path] : find_plugins()) {
    InstalledPost post;
    post.name = name;
    post.path = path;
    try {
      PostPlugin::load_file(path);
    } catch (const InputError& e) {
      post.status = e.problem();
    }
    for (const std::string& folder : machine_search_path()) {
      std::error_code ec;
      for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        if (entry.path().extension() != ".yaml") continue;
        try {
          MachineDescription m = load_machine(entry.path().string(), max_yaml_bytes);
          if (m.plugin == name) post.machines.push_back(std::move(m));
        } catch (const InputError& e) {
          post.unreadable_machines.push_back(e.what());
        }
      }
    }
    out.push_back(std::move(post));
  }
  return out;
}

}  // namespace freeturn
