#include "engine/gpu/shader_includer.hpp"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace voxgi::gpu {

namespace fs = std::filesystem;

std::optional<std::string> read_text_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return std::nullopt;
  return text.str();
}

std::optional<fs::path> resolve_include(const std::string& name, const fs::path& includer,
                                        bool local, const std::vector<fs::path>& roots) {
  std::error_code error;
  auto usable = [&](const fs::path& candidate) { return fs::is_regular_file(candidate, error); };
  if (local && !includer.empty()) {
    fs::path candidate = (includer.parent_path() / name).lexically_normal();
    if (usable(candidate)) return candidate;
  }
  for (const fs::path& root : roots) {
    fs::path candidate = (root / name).lexically_normal();
    if (usable(candidate)) return candidate;
  }
  return std::nullopt;
}

namespace {

void collect(const fs::path& file, const std::string& source, const std::vector<fs::path>& roots,
             std::set<fs::path>& seen, std::vector<std::pair<fs::path, std::string>>& out) {
  static const std::regex include_line(R"(^[ \t]*#[ \t]*include[ \t]*([<"])([^">]+)[">])");
  std::istringstream lines(source);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch match;
    if (!std::regex_search(line, match, include_line)) continue;
    auto resolved = resolve_include(match[2].str(), file, match[1].str() == "\"", roots);
    if (!resolved || !seen.insert(*resolved).second) continue;
    auto text = read_text_file(*resolved);
    if (!text) continue;
    out.emplace_back(*resolved, *text);
    collect(*resolved, *text, roots, seen, out);
  }
}

}  // namespace

std::vector<std::pair<fs::path, std::string>> collect_includes(const fs::path& main,
                                                               const std::string& main_source,
                                                               const std::vector<fs::path>& roots) {
  std::set<fs::path> seen{main};
  std::vector<std::pair<fs::path, std::string>> out;
  collect(main, main_source, roots, seen, out);
  return out;
}

namespace {

struct IncludeData {
  std::string text;
};

}  // namespace

ShaderIncluder::IncludeResult* ShaderIncluder::include(const char* header, const char* includer,
                                                       size_t depth, bool local) {
  // Include guards are the shader's business; this only stops runaway recursion.
  if (depth > 64) return nullptr;
  auto resolved = resolve_include(header, fs::path(includer ? includer : ""), local, roots_);
  if (!resolved) return nullptr;
  auto text = read_text_file(*resolved);
  if (!text) return nullptr;
  auto* data = new IncludeData{std::move(*text)};
  std::string name = resolved->string();
  if (includer && !included_by_.count(name)) included_by_[name] = includer;
  return new IncludeResult(name, data->text.data(), data->text.size(), data);
}

ShaderIncluder::IncludeResult* ShaderIncluder::includeLocal(const char* header,
                                                            const char* includer, size_t depth) {
  return include(header, includer, depth, true);
}

ShaderIncluder::IncludeResult* ShaderIncluder::includeSystem(const char* header,
                                                             const char* includer, size_t depth) {
  return include(header, includer, depth, false);
}

void ShaderIncluder::releaseInclude(IncludeResult* result) {
  if (!result) return;
  delete static_cast<IncludeData*>(result->userData);
  delete result;
}

std::string ShaderIncluder::include_chain(const std::string& file) const {
  std::string chain;
  std::string current = file;
  for (int guard = 0; guard < 64; ++guard) {
    auto found = included_by_.find(current);
    if (found == included_by_.end()) break;
    chain += (chain.empty() ? "included from " : ", included from ") + found->second;
    current = found->second;
  }
  return chain;
}

}  // namespace voxgi::gpu
