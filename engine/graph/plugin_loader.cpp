#include "engine/graph/plugin_loader.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::graph {

namespace fs = std::filesystem;

namespace {
constexpr const char* kPrefix = "libvoxgi_passes_";
constexpr const char* kSuffix = ".so";
}  // namespace

PluginLoader::PluginLoader(std::vector<fs::path> search_dirs) {
  // The same directory reached twice (the executable's lib folder is often also the build
  // tree's plugin folder) is searched and listed once.
  for (fs::path& dir : search_dirs) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(dir, ec);
    if (ec) key = dir.lexically_normal();
    bool seen = false;
    for (const fs::path& kept : search_dirs_) {
      std::error_code kept_ec;
      fs::path kept_key = fs::weakly_canonical(kept, kept_ec);
      if (kept_ec) kept_key = kept.lexically_normal();
      seen = seen || kept_key == key;
    }
    if (!seen) search_dirs_.push_back(std::move(dir));
  }
}

std::vector<fs::path> PluginLoader::default_search_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("VOXGI_PLUGIN_PATH")) {
    std::string list = env;
    size_t start = 0;
    while (start <= list.size()) {
      const size_t colon = std::min(list.find(':', start), list.size());
      if (colon > start) dirs.emplace_back(list.substr(start, colon - start));
      start = colon + 1;
    }
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back((exe.parent_path() / ".." / "lib" / "voxgi").lexically_normal());
#ifdef VOXGI_PLUGIN_DIR
  dirs.emplace_back(VOXGI_PLUGIN_DIR);
#endif
  return dirs;
}

std::string PluginLoader::library_file_name(const std::string& family) {
  return kPrefix + family + kSuffix;
}

std::string PluginLoader::searched_dirs_text() const {
  if (search_dirs_.empty()) return "no directories (set VOXGI_PLUGIN_PATH)";
  std::string text;
  for (const fs::path& dir : search_dirs_) {
    if (!text.empty()) text += ", ";
    text += dir.string();
  }
  return text;
}

void PluginLoader::load_family(const std::string& family, Registry& registry) {
  if (loaded_.count(family)) return;
  const std::string file_name = library_file_name(family);
  for (const fs::path& dir : search_dirs_) {
    std::error_code ec;
    const fs::path candidate = dir / file_name;
    if (fs::is_regular_file(candidate, ec)) {
      load_library(family, candidate, registry);
      return;
    }
  }
  throw PluginError("pass family '" + family + "': plugin library " + file_name +
                    " not found; searched: " + searched_dirs_text());
}

void PluginLoader::load_library(const std::string& family, const fs::path& file,
                                Registry& registry) {
  // RTLD_LOCAL: families cannot clash on symbols; RTLD_NOW: missing symbols fail here, not later.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw PluginError("pass family '" + family + "': cannot load " + file.string() + ": " +
                      (why ? why : "unknown error") + " (searched: " + searched_dirs_text() + ")");
  }
  auto abi_fn =
      reinterpret_cast<VoxgiPluginAbiVersionFn>(dlsym(handle, "voxgi_plugin_abi_version"));
  auto register_fn =
      reinterpret_cast<VoxgiPluginRegisterFn>(dlsym(handle, "voxgi_plugin_register"));
  if (!abi_fn || !register_fn) {
    throw PluginError("pass family '" + family + "': " + file.string() +
                      " does not export the entry point " +
                      (!abi_fn ? "voxgi_plugin_abi_version()" : "voxgi_plugin_register()") +
                      " (searched: " + searched_dirs_text() + ")");
  }
  const uint32_t found = abi_fn();
  if (found != kPluginAbiVersion) {
    throw PluginError("pass family '" + family + "': " + file.string() +
                      " was built for plugin ABI version " + std::to_string(found) +
                      ", expected version " + std::to_string(kPluginAbiVersion) +
                      " (rebuild the plugin; searched: " + searched_dirs_text() + ")");
  }
  try {
    register_fn(registry);
  } catch (const std::exception& e) {
    throw PluginError("pass family '" + family + "': " + file.string() +
                      " failed to register its passes: " + e.what());
  }
  loaded_.insert(family);
}

void PluginLoader::load_for_graph(const GraphDesc& desc, Registry& registry) {
  // A family with no library is a mistake in the graph file: name the file, line, column and
  // pass, the families that do exist, and the closest of them.
  const std::map<std::string, fs::path> available = available_families();
  DiagnosticList diagnostics;
  std::set<std::string> reported;
  for (const PassDesc& pass : desc.passes) {
    const size_t dot = pass.type.find('.');
    if (dot == std::string::npos || dot == 0) continue;  // the compiler reports those
    const std::string family = pass.type.substr(0, dot);
    if (loaded_.count(family) || available.count(family) || !reported.insert(family).second) {
      continue;
    }
    std::vector<std::string> names;
    std::string list;
    for (const auto& [name, file] : available) {
      names.push_back(name);
      list += (list.empty() ? "" : ", ") + name;
    }
    diagnostics.error(pass.type_loc, pass.name, "type",
                      "unknown pass family '" + family + "' in pass type '" + pass.type + "': no " +
                          library_file_name(family) + " in " + searched_dirs_text() +
                          " (families there: " + (list.empty() ? std::string("none") : list) + ")",
                      did_you_mean(family, names));
  }
  diagnostics.throw_if_any();
  for (const std::string& family : desc.families()) load_family(family, registry);
}

std::map<std::string, fs::path> PluginLoader::available_families() const {
  std::map<std::string, fs::path> found;
  for (const fs::path& dir : search_dirs_) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      const std::string prefix = kPrefix;
      const std::string suffix = kSuffix;
      if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
        continue;
      }
      const std::string family =
          name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
      found.emplace(family, entry.path());  // earlier directories win
    }
  }
  return found;
}

void PluginLoader::load_all(Registry& registry) {
  for (const auto& [family, file] : available_families()) {
    if (!loaded_.count(family)) load_library(family, file, registry);
  }
}

}  // namespace voxgi::graph
