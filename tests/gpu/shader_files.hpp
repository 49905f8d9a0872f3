#pragma once
// Writing small shader sources into a test's temp dir.

#include <filesystem>
#include <fstream>
#include <string>

namespace voxgi::test {

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << text;
}

}  // namespace voxgi::test
