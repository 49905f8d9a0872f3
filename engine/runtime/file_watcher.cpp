#include "engine/runtime/file_watcher.hpp"

#include <algorithm>

namespace voxgi::runtime {

namespace fs = std::filesystem;

FileWatcher::Stamp FileWatcher::stamp(const fs::path& file) {
  Stamp s;
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::is_regular_file(status)) return s;
  s.time = fs::last_write_time(file, ec);
  if (ec) return s;
  s.size = fs::file_size(file, ec);
  if (ec) return s;
  s.exists = true;
  return s;
}

void FileWatcher::watch_file(const fs::path& file) {
  if (std::find(files_.begin(), files_.end(), file) != files_.end()) return;
  files_.push_back(file);
  stamps_[file] = stamp(file);
}

void FileWatcher::watch_tree(const fs::path& folder) {
  trees_.push_back(folder);
  std::map<fs::path, Stamp> found;
  scan_trees(found);
  for (auto& [file, s] : found) stamps_.emplace(file, s);
}

void FileWatcher::scan_trees(std::map<fs::path, Stamp>& into) const {
  for (const fs::path& tree : trees_) {
    std::error_code ec;
    fs::recursive_directory_iterator it(tree, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      std::error_code type_ec;
      if (it->is_regular_file(type_ec)) into[it->path()] = stamp(it->path());
    }
  }
}

std::vector<fs::path> FileWatcher::poll() {
  std::map<fs::path, Stamp> now;
  scan_trees(now);
  for (const fs::path& file : files_) now[file] = stamp(file);
  std::vector<fs::path> changed;
  for (const auto& [file, s] : now) {
    auto it = stamps_.find(file);
    if (it == stamps_.end() || !(it->second == s)) changed.push_back(file);
  }
  for (const auto& [file, s] : stamps_) {
    if (s.exists && !now.count(file)) changed.push_back(file);  // a tree file was removed
  }
  stamps_ = std::move(now);
  return changed;
}

}  // namespace voxgi::runtime
