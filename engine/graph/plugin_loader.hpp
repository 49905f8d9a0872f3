#pragma once
// Finds and loads pass family plugins (libvoxgi_passes_<family>.so) and lets them register
// their pass types. Libraries stay loaded for the life of the process: pass objects and their
// vtables live in them.

#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/graph/graph_desc.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::graph {

class PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class PluginLoader {
 public:
  explicit PluginLoader(std::vector<std::filesystem::path> search_dirs);

  // $VOXGI_PLUGIN_PATH (colon-separated), then <dir of the executable>/../lib/voxgi, then the
  // plugin directory of the build tree.
  static std::vector<std::filesystem::path> default_search_dirs();
  static std::string library_file_name(const std::string& family);

  const std::vector<std::filesystem::path>& search_dirs() const { return search_dirs_; }

  // Loads one family once; later calls for the same family do nothing. Throws PluginError.
  void load_family(const std::string& family, Registry& registry);
  // Every family named by a pass type "family.pass" in the graph. A family with no library in
  // the search directories throws GraphError located at the pass's "type"; a library that
  // cannot be loaded throws PluginError.
  void load_for_graph(const GraphDesc& desc, Registry& registry);
  // The families whose libraries the search directories hold (first directory wins).
  std::map<std::string, std::filesystem::path> available_families() const;
  // Every libvoxgi_passes_*.so in the search directories (first one found per family wins).
  void load_all(Registry& registry);

  const std::set<std::string>& loaded_families() const { return loaded_; }

 private:
  void load_library(const std::string& family, const std::filesystem::path& file,
                    Registry& registry);
  std::string searched_dirs_text() const;

  std::vector<std::filesystem::path> search_dirs_;
  std::set<std::string> loaded_;
};

}  // namespace voxgi::graph
