#include "freeturn/post/post_loader.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "freeturn/core/error.hpp"

namespace freeturn {
namespace {

std::string executable_folder() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : exe.parent_path().string();
}

std::vector<std::string> env_folders(const char* variable) {
  std::vector<std::string> out;
  if (const char* v = std::getenv(variable)) {
    std::string s(v);
    std::size_t start = 0;
    while (start <= s.size()) {
      const std::size_t end = s.find(':', start);
      const std::string part = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
      if (!part.empty()) out.push_back(part);
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  return out;
}

std::string library_name(const std::string& name) { return "libfreeturn_post_" + name + ".so"; }

// The folder of libfreeturn.so, when the library is a shared object ("" when it is linked
// into the executable): a program of a shop's own, or Python, finds the plugins and
// machines installed beside the library wherever the program itself lives.
std::string library_folder() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&plugin_search_path), &info) == 0 || !info.dli_fname)
    return {};
  std::error_code ec;
  const auto library = std::filesystem::canonical(info.dli_fname, ec);
  const auto exe = std::filesystem::canonical("/proc/self/exe", ec);
  if (library.empty() || library == exe) return {};
  return library.parent_path().string();
}

// The variable's folders, then beside the library (lib/<below>), then beside the
// executable (bin/../lib/<below>).
std::vector<std::string> search_path(const char* variable, const std::string& below_lib) {
  std::vector<std::string> out = env_folders(variable);
  const auto add = [&](const std::filesystem::path& folder) {
    const std::string normal = folder.lexically_normal().string();
    if (std::find(out.begin(), out.end(), normal) == out.end()) out.push_back(normal);
  };
  if (const std::string lib = library_folder(); !lib.empty())
    add(std::filesystem::path(lib) / below_lib);
  add(std::filesystem::path(executable_folder()) / "../lib" / below_lib);
  return out;
}

}  // namespace

std::vector<std::string> plugin_search_path() { return search_path("FREETURN_PLUGIN_PATH", "freeturn"); }

std::vector<std::string> machine_search_path() {
  return search_path("FREETURN_MACHINE_PATH", "../share/freeturn/machines");
}

std::unique_ptr<PostPlugin> PostPlugin::load(const std::string& name) {
  std::string looked;
  for (const std::string& folder : plugin_search_path()) {
    const std::filesystem::path p = std::filesystem::path(folder) / library_name(name);
    if (std::filesystem::exists(p)) return load_file(p.lexically_normal().string());
    looked += "\n  " + std::filesystem::path(folder).lexically_normal().string();
  }
  throw InputError("post-processor '" + name + "'",
                   "not found: no " + library_name(name) + " in" + looked +
                       "\n(set FREETURN_PLUGIN_PATH to the folder that holds it)");
}

std::unique_ptr<PostPlugin> PostPlugin::load_file(const std::string& path) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* e = dlerror();
    throw InputError(path, std::string("cannot load the post-processor: ") + (e ? e : "unknown error"));
  }
  dlerror();
  void* symbol = dlsym(handle, FREETURN_POST_ENTRY);
  if (symbol == nullptr) {
    dlclose(handle);
    throw InputError(path, "not a freeturn post-processor: it does not export " FREETURN_POST_ENTRY);
  }
  const ft_post* post = reinterpret_cast<ft_post_entry_fn>(symbol)();
  if (post == nullptr || post->abi_version != FREETURN_POST_ABI_VERSION) {
    const int version = post ? post->abi_version : -1;
    dlclose(handle);
    throw InputError(path, "post-processor ABI version " + std::to_string(version) +
                               "; this freeturn needs version " +
                               std::to_string(FREETURN_POST_ABI_VERSION) + " (rebuild the plugin)");
  }
  if (!post->create || !post->begin || !post->blocks || !post->end || !post->destroy) {
    dlclose(handle);
    throw InputError(path, "the post-processor's function table is incomplete");
  }
  return std::unique_ptr<PostPlugin>(new PostPlugin(handle, post, path));
}

PostPlugin::~PostPlugin() {
  if (handle_) dlclose(handle_);
}

std::vector<std::pair<std::string, std::string>> find_plugins() {
  std::vector<std::pair<std::string, std::string>> out;
  std::set<std::string> seen;
  for (const std::string& folder : plugin_search_path()) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
      const std::string file = entry.path().filename().string();
      const std::string prefix = "libfreeturn_post_";
      if (file.rfind(prefix, 0) != 0 || entry.path().extension() != ".so") continue;
      const std::string name = file.substr(prefix.size(), file.size() - prefix.size() - 3);
      if (seen.insert(name).second) out.emplace_back(name, entry.path().lexically_normal().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace freeturn
