#pragma once
// Voxel clipmaps built on the CPU for the dvs tests, in the layout of the voxel contract
// (shaders/contracts/voxel_clipmap.glsl): one (R, R, R * L) stack of toroidal levels and the
// 288-byte VoxelClipmapInfo buffer. Tests fill voxels by world position and upload them with
// the dvs_test.voxel_source pass (voxel_source_pass.hpp).

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "passes/contracts/voxel_clipmap.hpp"

namespace voxgi::test {

using ClipmapInfoData = contracts::VoxelClipmapInfo;

struct VoxelValue {
  glm::vec3 albedo{0.0f};
  float opacity = 0.0f;
  glm::vec3 normal{0.0f};  // averaged, any length (zero where faces cancel)
  glm::vec3 emission{0.0f};
};

class VoxelGrid {
 public:
  // Level l has voxels of edge voxel_size * 2^l in a window of R voxels centred on `center`.
  VoxelGrid(uint32_t resolution, uint32_t levels, float voxel_size, glm::vec3 center,
            glm::vec3 anchor = glm::vec3(0.0f));

  uint32_t resolution() const { return r_; }
  uint32_t levels() const { return l_; }
  float size(uint32_t level) const { return info_.levels[level].min_corner_size.w; }
  const ClipmapInfoData& info() const { return info_; }

  // Every voxel of every level: `shape(center, size)` returns the voxel's value (opacity 0:
  // empty). Centres are world positions.
  void fill(const std::function<VoxelValue(glm::vec3 center, float size)>& shape);
  void set(uint32_t level, glm::ivec3 window_voxel, const VoxelValue& value);

  // Texel index (into the R x R x R*L stack) of a window voxel of a level; its world centre.
  size_t texel_index(uint32_t level, glm::ivec3 window_voxel) const;
  glm::vec3 center(uint32_t level, glm::ivec3 window_voxel) const;
  // The window voxel of `level` holding world position p (may be outside 0..R-1).
  glm::ivec3 window_voxel_at(uint32_t level, glm::vec3 p) const;

  // Texel data as the GPU formats want it: rgba8 albedo, rgba16f normal and emission.
  std::vector<uint8_t> albedo_rgba8() const;
  std::vector<uint16_t> normal_rgba16f() const;
  std::vector<uint16_t> emission_rgba16f() const;
  size_t texel_count() const { return values_.size(); }

 private:
  uint32_t r_, l_;
  ClipmapInfoData info_{};
  std::vector<VoxelValue> values_;
};

// RGBA32F texels of an rgba16f or rgba32f download.
glm::vec4 texel_rgba(const std::vector<float>& rgba, size_t index);

}  // namespace voxgi::test
