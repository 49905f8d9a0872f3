#pragma once
// Runs tests/common/graphs/voxelize.json on a scene made by a test and reads the clipmap
// volumes back; plus the CPU triangle/voxel overlap test the voxelization tests compare with.

#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "passes/common/voxel_clipmap_window.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "tests/common/test_graph_gpu.hpp"

namespace voxgi::test {

// One group of a faces texel (contracts/voxel_volumes.glsl), decoded: share 0 for none.
struct VoxelFace {
  glm::vec3 normal{0.0f};
  float share = 0.0f;
  float plane_offset = 0.0f;  // voxels, to the group's frontmost plane (rounded up)
};
VoxelFace decode_voxel_face(const glm::uvec4& faces, int group);

struct VoxelVolumes {
  uint32_t resolution = 0;
  uint32_t levels = 0;
  contracts::VoxelClipmapInfo info{};
  std::vector<uint8_t> albedo_bytes, normal_bytes, emission_bytes;  // raw texels
  std::vector<glm::vec4> albedo, normal, emission;                  // decoded
  std::vector<glm::uvec4> faces;  // packed (contracts/voxel_volumes.glsl); empty without them

  // Texel index of window voxel `w` of `level` through the toroidal mapping of `info`.
  size_t texel(int level, const glm::ivec3& w) const;
  // Window coordinates (voxels of `level`) of a world point, from `info`, in double.
  glm::dvec3 window_coord(int level, const glm::dvec3& world) const;
  bool occupied(int level, const glm::ivec3& w) const { return normal[texel(level, w)].w > 0.5f; }
};

class VoxelRun {
 public:
  // overrides: graph parameters ("voxel.resolution") and pass parameters ("voxelize.strategy").
  // graph: relative to the source tree.
  VoxelRun(const scene::Scene& scene, std::map<std::string, std::string> overrides,
           const std::string& graph = "tests/common/graphs/voxelize.json");
  ~VoxelRun();

  // Renders one frame with the camera at `camera`; geometry_changed after Scene::animate().
  void render(const glm::vec3& camera, bool geometry_changed = false);
  // Evaluates the scene's animations at `time` and uploads the moved instances.
  void animate(double time);
  VoxelVolumes read();
  // The voxelize pass's skip reason in the last frame (empty when it ran).
  std::string last_skip_reason() const;
  double last_gpu_ms() const;
  scene::Scene& scene() { return scene_; }

 private:
  scene::Scene scene_;
  graph::Registry registry_;
  graph::CompiledGraph compiled_;
  std::unique_ptr<TestGraphGpu> gpu_;
  std::unique_ptr<runtime::FrameDriver> frames_;
};

// Whether the triangle overlaps the voxel [v, v + 1]^3 grown by `grow` on each side (negative
// shrinks it): the 13-axis separating axis test, in double.
bool triangle_overlaps_voxel(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             const glm::ivec3& v, double grow);

// Every world-space triangle of the scene's instances.
struct WorldTriangle {
  glm::dvec3 p[3];
};
std::vector<WorldTriangle> world_triangles(const scene::Scene& scene);

// A diffuse, double-sided material.
scene::Material diffuse(glm::vec3 color);
// A few dozen random triangles of all sizes in the unit cube, plus a thin diagonal wall (two
// faces 4 mm apart) and a long diagonal sliver, placed by `transform`.
scene::Scene random_scene(uint32_t seed, const glm::mat4& transform);

struct CoverageStats {
  size_t required = 0;         // voxels the CPU finds overlapped (robustly)
  size_t holes = 0;            // required but not set
  size_t set = 0;              // voxels the GPU set
  size_t false_positives = 0;  // set but not touched even by a slightly grown voxel
};
// Compares level `level` of the volumes with the CPU overlap test of every scene triangle.
CoverageStats compare_coverage(const VoxelVolumes& v, const scene::Scene& scene, int level);
// Voxelizes `scene` at 32^3, one level, and expects no holes and at most 1% false positives
// (printed with `what`), and finite normals.
void check_coverage(const char* what, const scene::Scene& scene,
                    std::map<std::string, std::string> overrides);

}  // namespace voxgi::test
