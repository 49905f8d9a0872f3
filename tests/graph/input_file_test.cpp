#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/input_file.hpp"

namespace voxgi::graph {
namespace {

std::string error_of(const std::filesystem::path& path, std::size_t max_bytes) {
  try {
    read_input_file(path, "graph file", max_bytes);
  } catch (const GraphError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return {};
}

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() /
        ("voxgi_input_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(InputFile, ReadsAWholeFileUpToTheBound) {
  const std::string text(100000, 'x');
  EXPECT_EQ(read_input_file(write("a.json", text), "graph file", 100000), text);
  EXPECT_EQ(read_input_file(write("empty.json", ""), "graph file"), "");
}

TEST_F(InputFile, RefusesWhatIsLargerDirectoriesAndMissingFiles) {
  const std::filesystem::path big = write("big.json", std::string(100001, 'x'));
  const std::string too_big = error_of(big, 100000);
  EXPECT_NE(too_big.find(big.string()), std::string::npos) << too_big;
  EXPECT_NE(too_big.find("larger than 100000 bytes: not a graph file"), std::string::npos)
      << too_big;
  EXPECT_NE(error_of(dir_, 100).find("is a directory, expected a graph file"), std::string::npos);
  EXPECT_NE(error_of(dir_ / "missing.json", 100).find("cannot open the graph file"),
            std::string::npos);
}

// A device that never ends is refused after the bound, not read forever.
TEST_F(InputFile, EndlessDeviceStopsAtTheBound) {
  if (!std::filesystem::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero on this system";
  EXPECT_NE(error_of("/dev/zero", 1 << 20).find("larger than 1 MiB: not a graph file"),
            std::string::npos);
}

}  // namespace
}  // namespace voxgi::graph
