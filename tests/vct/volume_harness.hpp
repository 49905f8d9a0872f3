#pragma once
// Test harness for the vct passes on volumes the test writes itself: a test-only pass type
// ("vcttest.volumes") uploads CPU clipmap data (clipmap info, albedo, normal, emission,
// radiance) into the graph's resources, so injection, filtering and cone tracing can be
// checked against analytic answers without a voxelizer. A probe compute shader
// (tests/vct/shaders/probe.comp) evaluates contracts/cone_trace.glsl at chosen points.

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/pass.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "passes/contracts/voxel_clipmap.hpp"

namespace voxgi::test {

// The clipmap description the vct passes read (passes/contracts/voxel_clipmap.hpp).
using ClipmapInfo = contracts::VoxelClipmapInfo;

// A clipmap of R^3 x L voxels as RGBA floats, addressed by level and window voxel with the
// toroidal wrap of voxel_clipmap.glsl. For an integer format (faces) each float holds the bits
// of a 32-bit word (glm::uintBitsToFloat).
struct CpuClipmap {
  int resolution = 0;
  int levels = 0;
  std::vector<glm::vec4> texels;  // x fastest, then y, then z (z = level * R + wrapped z)

  CpuClipmap() = default;
  CpuClipmap(int r, int l)
      : resolution(r), levels(l), texels(size_t(r) * r * r * l, glm::vec4(0)) {}
  size_t index(glm::ivec3 texel) const {
    return (size_t(texel.z) * resolution + texel.y) * resolution + texel.x;
  }
  glm::vec4& at(glm::ivec3 texel) { return texels[index(texel)]; }
  const glm::vec4& at(glm::ivec3 texel) const { return texels[index(texel)]; }
};

// The texel of window voxel `window` of `level` (toroidal, as voxel_texel() in GLSL).
glm::ivec3 clipmap_texel(const ClipmapInfo& info, glm::ivec3 window, int level);

// Level l of a single-anchor clipmap: voxel size base * 2^l, windows centred on `centre`
// snapped to whole voxels (origin_voxel = round(centre / size) - R/2).
ClipmapInfo make_clipmap_info(int resolution, int levels, float base_voxel, glm::vec3 centre,
                              glm::vec3 anchor = glm::vec3(0.0f));

// A faces texel (contracts/voxel_volumes.glsl) of axis-aligned groups, as CpuClipmap holds an
// integer texel: (group 0..5 = +X, -X, +Y, -Y, +Z, -Z, area share in 31sts).
glm::vec4 faces_texel(const std::vector<std::pair<int, uint32_t>>& groups);

// What "vcttest.volumes" uploads. Bump `version` after a change to upload again; otherwise
// the pass skips (so downstream skip logic can be tested).
struct VolumeData {
  ClipmapInfo info{};
  std::map<std::string, CpuClipmap> volumes;  // by output slot: albedo, normal, emission, faces,
                                              // light_shares, radiance
  uint64_t version = 1;
};

// Registers "vcttest.volumes" into `registry`; the passes read `data` at execute().
void register_volume_pass(graph::Registry& registry, const VolumeData* data);

// A graph from JSON text, with the vct (and common) plugins plus the test pass type.
class VolumeGraph {
 public:
  VolumeGraph(const std::string& graph_json, const VolumeData* data, scene::Scene scene,
              uint32_t width = 64, uint32_t height = 64,
              std::map<std::string, std::string> overrides = {});
  ~VolumeGraph();

  // Renders `frames` frames with `camera` (view from eye to target, 60 degree fov).
  void render(int frames = 1, bool lights_changed = false);
  void set_camera(glm::vec3 eye, glm::vec3 target);

  // RGBA floats of one mip of a graph image resource (3D: the whole mip).
  std::vector<glm::vec4> download(const std::string& resource, uint32_t mip = 0);
  graph::Executor& executor() { return *executor_; }
  const graph::CompiledGraph& compiled() const { return compiled_; }
  gpu::ShaderCompiler& shaders() { return *shaders_; }
  // The skip reason of pass `name` in the last frame ("" when it ran).
  std::string skipped(const std::string& pass) const;

 private:
  graph::Registry registry_;
  graph::CompiledGraph compiled_;
  scene::Scene scene_;
  std::unique_ptr<gpu::ShaderCompiler> shaders_;
  std::unique_ptr<scene::GpuScene> gpu_scene_;
  std::unique_ptr<graph::Executor> executor_;
  glm::vec3 eye_{0.0f, 0.0f, 5.0f};
  glm::vec3 target_{0.0f};
  uint32_t width_, height_;
  std::unique_ptr<runtime::FrameDriver> frames_;
};

// One probe of the cone-trace library: a point and a normal (diffuse) or cone direction.
struct Probe {
  glm::vec3 position;
  glm::vec3 direction;
};
struct ProbeResult {
  glm::vec3 irradiance;  // diffuse mode: E; cone mode: radiance along the cone
  float visibility;      // diffuse mode: AO visibility; cone mode: 1 - opacity
};
struct ProbeSettings {
  bool single_cone = false;  // true: one cone along `direction`
  // true: each probe returns one lane direction of a diffuse cone (xyz, tangent space, z the
  // normal) and its weight in the gather (w): position = (turn in radians, ring position, cone
  // index), direction.x = the lane's index. No volume is read.
  bool lane_layout = false;
  float tan_half_angle = 0.577f;
  int diffuse_cones = 6;
  float step_factor = 1.0f;
  float max_distance = 1e6f;
  float ao_falloff = 0.0f;
  float normal_offset = 0.0f;  // metres
  float start_distance = 0.0f;
  bool anisotropic = true;
  int lanes = 1;  // of a cone capped near its receiver (1: the axis, as the source documents)
};

// Runs the probe shader against the graph's clipmap info buffer and filtered volumes
// (`filtered` or the six directional resources given in order +X..-Z).
std::vector<ProbeResult> run_probes(VolumeGraph& graph, const std::string& info_resource,
                                    const std::vector<std::string>& volume_resources,
                                    const std::vector<Probe>& probes, const ProbeSettings& s);

}  // namespace voxgi::test
