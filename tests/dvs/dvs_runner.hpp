#pragma once
// Runs a graph for the dvs tests on the test GPU context: loads the plugin families the graph
// names, adds the test-only pass type dvs_test.voxel_source (uploads a VoxelGrid into the
// voxel resources, as common.voxelize would write them) and lets tests move lights between
// frames and read back volumes.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/pass.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "tests/common/test_graph_gpu.hpp"
#include "voxel_grid.hpp"

namespace voxgi::test {

// What dvs_test.voxel_source uploads; bump `revision` after changing the grid.
struct VoxelSourceData {
  std::unique_ptr<VoxelGrid> grid;
  uint64_t revision = 1;
};

class DvsRunner {
 public:
  // `graph_text`: a graph file's text; `graph_path`: a graph file relative to the source tree
  // (used when graph_text is empty).
  struct Setup {
    std::string graph_text;
    std::string graph_path;
    scene::Scene scene;
    uint32_t width = 64;
    uint32_t height = 64;
    std::map<std::string, std::string> overrides;
    std::shared_ptr<VoxelSourceData> voxels;  // for graphs using dvs_test.voxel_source
  };
  explicit DvsRunner(Setup setup);
  ~DvsRunner();

  // One frame; `lights_changed`/`geometry_changed` are forced true on the first frame.
  void render(bool lights_changed = false, bool geometry_changed = false);
  // Moves light `index` to `position` (its node's translation) and uploads the lights.
  void move_light(size_t index, glm::vec3 position);

  // mip 0 of an image output as RGBA32F, texel after texel.
  std::vector<float> read(const std::string& output);
  // "" when the pass ran in the last frame, else its skip reason.
  std::string skipped(const std::string& pass) const;
  bool ran(const std::string& pass) const;
  graph::Executor& executor() { return *gpu_->executor; }
  scene::Scene& scene() { return scene_; }
  const scene::Camera& camera() const { return camera_; }

 private:
  Setup setup_;
  scene::Scene scene_;
  scene::Camera camera_;
  graph::Registry registry_;
  graph::CompiledGraph compiled_;
  std::unique_ptr<TestGraphGpu> gpu_;
  std::unique_ptr<runtime::FrameDriver> frames_;
};

// Registers dvs_test.voxel_source reading from `data`.
void register_voxel_source(graph::Registry& registry, std::shared_ptr<VoxelSourceData> data);

}  // namespace voxgi::test
