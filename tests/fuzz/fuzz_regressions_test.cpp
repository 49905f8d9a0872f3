// Inputs the libFuzzer targets (tests/fuzz/libfuzzer) failed on, kept under
// tests/fuzz/regressions/<target>/ once fixed: each must now load or be refused with the
// project's located error, exactly as the target that found it runs it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <typeinfo>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/expression.hpp"
#include "engine/scene/scene.hpp"
#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;
const fs::path kRepo = VOXGI_SOURCE_DIR;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `parse` on every file of tests/fuzz/regressions/<target>; returns how many there were.
int replay(const std::string& target, const std::function<void(const std::string&)>& parse) {
  const fs::path dir = kRepo / "tests" / "fuzz" / "regressions" / target;
  if (!fs::is_directory(dir)) return 0;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++count;
    try {
      parse(read(entry.path()));
    } catch (const graph::GraphError&) {
    } catch (const graph::ExpressionError&) {
    } catch (const scene::SceneError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << " threw " << typeid(e).name() << ": " << e.what();
    }
  }
  return count;
}

TEST(FuzzRegressions, JsonAndGraphFiles) {
  int count = replay("json", fuzz::run_json);
  const fuzz::GraphInput graph_input;
  count += replay("graph", [&](const std::string& text) { graph_input.run(text); });
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/{json,graph}";
}

TEST(FuzzRegressions, ExpressionsAndBenchFiles) {
  const int count = replay("expression", fuzz::run_expression) + replay("bench", fuzz::run_bench);
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/{expression,bench}";
}

TEST(FuzzRegressions, GltfFiles) {
  const fs::path dir = fresh_dir("fuzz_regressions");
  const int count = replay("gltf", [&](const std::string& bytes) { fuzz::run_gltf(bytes, dir); });
  fs::remove_all(dir);
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/gltf";
}

}  // namespace
}  // namespace voxgi::test
