#pragma once
// Host side of the post-processor ABI: finds `libfreeturn_post_<name>.so`, loads it with
// dlopen, checks the ABI version and the entry symbol, and drives it.
//
// Search order: every folder in FREETURN_PLUGIN_PATH (colon-separated), then
// <folder of the freeturn executable>/../lib/freeturn (the build tree and the install
// prefix both put plugins there).

#include <memory>
#include <string>
#include <vector>

#include "freeturn/post_plugin.h"

namespace freeturn {

std::vector<std::string> plugin_search_path();
// Machine YAMLs: FREETURN_MACHINE_PATH, then <exe>/../share/freeturn/machines.
std::vector<std::string> machine_search_path();

class PostPlugin {
 public:
  // Throws InputError: not found (listing where it looked), not loadable (dlerror), no
  // entry symbol, or another ABI version.
  static std::unique_ptr<PostPlugin> load(const std::string& name);
  // The same for one file.
  static std::unique_ptr<PostPlugin> load_file(const std::string& path);
  ~PostPlugin();
  PostPlugin(const PostPlugin&) = delete;
  PostPlugin& operator=(const PostPlugin&) = delete;

  const ft_post& post() const { return *post_; }
  const std::string& path() const { return path_; }

 private:
  PostPlugin(void* handle, const ft_post* post, std::string path)
      : handle_(handle), post_(post), path_(std::move(path)) {}
  void* handle_;
  const ft_post* post_;
  std::string path_;
};

// Every plugin found on the search path (name, file), first occurrence wins.
std::vector<std::pair<std::string, std::string>> find_plugins();

}  // namespace freeturn
