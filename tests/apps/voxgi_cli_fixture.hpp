#pragma once
// Runs the built `voxgi` executable in a fresh temporary directory per test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "tests/apps/child_process.hpp"

namespace voxgi::test {

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The graph shipped with the sources, for tests that need a valid graph to break.
inline std::string default_graph_text() {
  return read_text(std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "default.json");
}

// The fragment every shipped graph starts from (G-buffer, shadows, direct lighting).
inline std::string foundation_fragment_text() {
  return read_text(std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "common" /
                   "foundation.json");
}

// 1-based line of the first occurrence of `part` in `text`, 0 when absent.
inline int line_of(const std::string& text, const std::string& part) {
  const size_t at = text.find(part);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

class VoxgiCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "voxgi-cli-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr) << "cannot create a temporary directory";
    dir_ = pattern;
  }

  // Kept after a failure so that the files the program wrote can be looked at.
  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "files of the failed test kept in " << dir_.string() << "\n";
    } else if (!dir_.empty()) {
      std::error_code ec;
      std::filesystem::remove_all(dir_, ec);
    }
  }

  ProcessResult voxgi(const std::vector<std::string>& args, ProcessOptions options = {}) {
    options.working_dir = dir_;
    // Mesa warns on every run without it; the warning is noise in the messages under test.
    if (!std::getenv("XDG_RUNTIME_DIR") && !options.env.count("XDG_RUNTIME_DIR")) {
      options.env["XDG_RUNTIME_DIR"] = dir_.string();
    }
    return run_process(VOXGI_EXE, args, options);
  }

  // `voxgi render` on a small image with the validation layer on, plus `extra` options.
  ProcessResult render(const std::vector<std::string>& extra, ProcessOptions options = {}) {
    std::vector<std::string> args = {"render", "--width", "64", "--height", "64", "--validation"};
    args.insert(args.end(), extra.begin(), extra.end());
    return voxgi(args, std::move(options));
  }

  std::filesystem::path dir_;
};

// The program ended by itself (no crash, no hang) with `code`.
inline ::testing::AssertionResult exited_with(const ProcessResult& result, int code) {
  if (result.exited() && result.exit_code == code) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected exit code " << code << ", got " << result.describe();
}

// Every part appears in `stream` (the program's stdout or stderr).
inline ::testing::AssertionResult has_all(const ProcessResult& result, const std::string& stream,
                                          const std::vector<std::string>& parts) {
  for (const std::string& part : parts) {
    if (!contains(stream, part)) {
      return ::testing::AssertionFailure() << "missing \"" << part << "\"\n" << result.describe();
    }
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult stderr_has(const ProcessResult& result,
                                             const std::vector<std::string>& parts) {
  return has_all(result, result.err, parts);
}

inline ::testing::AssertionResult stdout_has(const ProcessResult& result,
                                             const std::vector<std::string>& parts) {
  return has_all(result, result.out, parts);
}

}  // namespace voxgi::test
