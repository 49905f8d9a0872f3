// The example family (tests/example) on the test device: a device-feature condition picks the
// tracing pass, rays through the scene's BVH service count hits, and an indirect dispatch of
// that many groups marks them. Any validation message fails the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/bvh.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

const std::filesystem::path kSource = VOXGI_SOURCE_DIR;

// The hits trace_args.comp counts, traced on the CPU BVH with the same rays.
uint32_t expected_hits(const scene::Scene& scene) {
  const scene::Bvh bvh = scene::Bvh::build(scene);
  if (bvh.empty()) return 0;
  const scene::BvhNode& root = bvh.nodes()[0];
  const glm::vec3 centre = 0.5f * (root.bounds_min + root.bounds_max);
  const glm::vec3 extent = root.bounds_max - root.bounds_min;
  uint32_t hits = 0;
  for (uint32_t i = 0; i < 64; ++i) {
    const glm::vec2 cell =
        (glm::vec2(static_cast<float>(i % 8), static_cast<float>(i / 8)) + 0.5f) / 8.0f * 2.0f -
        1.0f;
    const glm::vec3 o(centre.x + cell.x * extent.x, root.bounds_max.y + 1.0f,
                      centre.z + cell.y * extent.z);
    if (bvh.intersect(glm::dvec3(o) + bvh.origin(), glm::vec3(0.0f, -1.0f, 0.0f), 0.0f, 1e30f)) {
      ++hits;
    }
  }
  return hits;
}

class ExampleFamilyTest : public GpuTest {};

TEST_F(ExampleFamilyTest, IndirectDispatchOfHitsThroughTheSceneBvh) {
  const scene::Scene scene = scene::make_builtin_scene("cornell");
  graph::Registry registry;
  graph::PluginLoader loader({EXAMPLE_PLUGIN_DIR});
  const graph::GraphDesc desc = graph::load_graph_file(kSource / "tests/example/example.json");
  loader.load_for_graph(desc, registry);
  graph::CompileOptions options;
  options.scene_features = scene.features().as_map();
  graph::use_device(options, context());
  const graph::CompiledGraph compiled = graph::compile(desc, registry, options);

  // The device feature decides which tracing pass runs.
  const bool ray_query = context().features().ray_query;
  ASSERT_EQ(compiled.device_conditions.size(), 2u);
  EXPECT_NE(compiled.find_pass(ray_query ? "trace_rq" : "trace"), nullptr);
  EXPECT_NE(compiled.find_culled(ray_query ? "trace" : "trace_rq"), nullptr);
  // The arguments reach the dispatch through the draw-indirect stage.
  const graph::CompiledPass* mark = compiled.find_pass("mark");
  ASSERT_NE(mark, nullptr);
  const int args = compiled.find_resource("args");
  bool indirect_barrier = false;
  for (const graph::Barrier& b : mark->barriers) {
    indirect_barrier = indirect_barrier || (b.resource == args &&
                                            b.dst_stages == VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT &&
                                            b.dst_access == VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  }
  EXPECT_TRUE(indirect_barrier);
  EXPECT_TRUE(compiled.resources[static_cast<size_t>(args)].buffer_usage &
              VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);

  gpu::ShaderCompiler shaders({kSource / "tests/example/shaders", kSource / "shaders"}, "");
  scene::GpuScene gpu_scene(context(), scene);
  graph::Executor executor(context(), shaders, registry);
  executor.build(compiled, scene, gpu_scene);
  EXPECT_TRUE(gpu_scene.has_bvh()) << "the trace pass binds the scene's BVH service";
  for (int frame = 0; frame < 2; ++frame) {
    executor.render({});
    context().wait_idle();
    const uint32_t hits = executor.buffer("args")->download_vector<uint32_t>(4)[0];
    EXPECT_EQ(hits, expected_hits(scene));
    // The footprint of the box is a quarter of the grid.
    EXPECT_GT(hits, 0u);
    EXPECT_LT(hits, 64u);
    const std::vector<uint32_t> marks = executor.buffer("marks")->download_vector<uint32_t>(64);
    for (uint32_t i = 0; i < 64; ++i) {
      ASSERT_EQ(marks[i], i < hits ? i + 1 : 0u) << "mark " << i << " of " << hits << " hits";
    }
  }
}

}  // namespace
}  // namespace voxgi::test
