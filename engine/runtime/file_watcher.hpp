#pragma once
// Polls modification times of files and of every file under folders, for hot reload. Polling
// instead of inotify: it is portable, cheap for a few hundred files, and sees edits made by
// any program (editors that replace files included).

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace voxgi::runtime {

class FileWatcher {
 public:
  // A file to watch (it may not exist yet: its appearance counts as a change); once.
  void watch_file(const std::filesystem::path& file);
  // Every regular file under `folder`, recursively, including files added later.
  void watch_tree(const std::filesystem::path& folder);

  // Files that changed, appeared or vanished since the previous poll (or since they were
  // added). Never throws: unreadable entries count as missing.
  std::vector<std::filesystem::path> poll();

 private:
  struct Stamp {
    bool exists = false;
    std::filesystem::file_time_type time{};
    uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  static Stamp stamp(const std::filesystem::path& file);
  void scan_trees(std::map<std::filesystem::path, Stamp>& into) const;

  std::vector<std::filesystem::path> files_;
  std::vector<std::filesystem::path> trees_;
  std::map<std::filesystem::path, Stamp> stamps_;
};

}  // namespace voxgi::runtime
