// Mutation fuzzing of every parser a user's files reach: graph files (parsed and compiled
// against the real pass types), expressions, bench files and glTF (JSON and GLB). Each input
// must either load or be refused with the project's located error; any other exception (an
// out-of-range access caught by the standard library, bad_alloc, a parser's own exception
// type) fails, and the input is kept as fuzz-failure-* in the working directory. A crash or
// a hang fails the ctest entry. Deterministic: the same seeds give the same inputs.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "apps/voxgi/bench_spec.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/diagnostics.hpp"
#include "engine/graph/expression.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"
#include "tests/fuzz/input_mutator.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

const std::filesystem::path kRepo = VOXGI_SOURCE_DIR;
// VOXGI_FUZZ_MUTATIONS runs longer locally (docs/inputs.md).
int mutations_per_seed() {
  const char* text = std::getenv("VOXGI_FUZZ_MUTATIONS");
  const int count = text ? std::atoi(text) : 0;
  return count > 0 ? count : 4000;
}
const int kMutationsPerSeed = mutations_per_seed();

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `parse` on `count` mutations of each seed; only `Allowed` exceptions may escape it.
template <typename Parse>
void fuzz(const std::string& name, const std::vector<std::string>& seeds, uint32_t seed,
          Parse parse) {
  InputMutator mutator(seed);
  int refused = 0;
  for (size_t s = 0; s < seeds.size(); ++s) {
    for (int i = 0; i < kMutationsPerSeed; ++i) {
      const std::string input = mutator.mutate(seeds[s]);
      try {
        parse(input);
      } catch (const graph::GraphError&) {
        ++refused;
      } catch (const graph::ExpressionError&) {
        ++refused;
      } catch (const scene::SceneError&) {
        ++refused;
      } catch (const std::exception& e) {
        const std::string kept =
            keep_failing_input(name + "-" + std::to_string(s) + "-" + std::to_string(i), input);
        ADD_FAILURE() << name << ": seed " << s << " mutation " << i << " threw "
                      << typeid(e).name() << ": " << e.what() << " (input kept in " << kept << ")";
        return;
      }
    }
  }
  // Most mutations break a file; if none did, the mutator is not reaching the parser.
  EXPECT_GT(refused, kMutationsPerSeed / 4) << name;
}

TEST(InputFuzz, GraphFilesParseAndCompileOrAreRefused) {
  graph::Registry registry;
  graph::PluginLoader(graph::PluginLoader::default_search_dirs()).load_all(registry);
  const scene::Scene cornell = scene::make_builtin_scene("cornell");
  graph::CompileOptions options;
  options.viewport_width = 64;
  options.viewport_height = 64;
  options.scene_features = cornell.features().as_map();
  std::vector<std::string> seeds;
  for (const char* file : {"default.json", "vct.json", "dvs.json", "lpv.json", "reference.json"}) {
    seeds.push_back(read(kRepo / "graphs" / file));
  }
  fuzz("graph", seeds, 1, [&](const std::string& text) {
    const graph::GraphDesc desc = graph::parse_graph(text, "fuzz.json");
    graph::compile(desc, registry, options);
  });
}

TEST(InputFuzz, ExpressionsEvaluateOrAreRefused) {
  graph::ExpressionEnv env;
  env.params = {{"voxel.resolution", 64}, {"shadow.max_lights", 4}};
  env.identifiers = {{"viewport", 800}, {"scene.light_count", 2}, {"scene.has_glossy", 0}};
  const std::vector<std::string> seeds = {
      "6 * max(1, min(scene.light_count, ${shadow.max_lights}))",
      "${voxel.resolution} * ${voxel.resolution} * ${voxel.resolution} * 60",
      "scene.has_glossy && !(viewport / 2 >= 400 || -1 < 0)"};
  fuzz("expression", seeds, 2,
       [&](const std::string& text) { graph::evaluate_expression(text, env); });
}

TEST(InputFuzz, BenchFilesParseOrAreRefused) {
  const std::vector<std::string> seeds = {read(kRepo / "graphs" / "bench.json"),
                                          read(kRepo / "docs" / "bench-report" / "bench.json")};
  fuzz("bench", seeds, 3, [&](const std::string& text) {
    const cli::BenchSpec spec = cli::parse_bench(text, kRepo / "graphs" / "fuzz-bench.json", kRepo);
    cli::expand_configurations(spec);
  });
}

// A glTF with a node hierarchy, a camera, a light, a material and indices; mutated as .gltf
// text (its buffer in a .bin next to it) and as GLB bytes.
TEST(InputFuzz, GltfFilesLoadOrAreRefused) {
  const std::filesystem::path dir = fresh_dir("fuzz_gltf");
  GltfWriter w = hierarchy_document();
  w.write_gltf(dir / "seed.gltf");
  const std::vector<uint8_t> glb = w.glb_bytes();
  scene::load_gltf(dir / "seed.gltf");  // the seeds themselves load

  fuzz("gltf", {read(dir / "seed.gltf")}, 4, [&](const std::string& text) {
    std::ofstream(dir / "mutated.gltf", std::ios::binary) << text;
    scene::load_gltf(dir / "mutated.gltf");
  });
  fuzz("glb", {std::string(glb.begin(), glb.end())}, 5, [&](const std::string& bytes) {
    std::ofstream(dir / "mutated.glb", std::ios::binary) << bytes;
    scene::load_gltf(dir / "mutated.glb");
  });
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxgi::test
