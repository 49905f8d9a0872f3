#include "voxel_grid.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace voxgi::test {

VoxelGrid::VoxelGrid(uint32_t resolution, uint32_t levels, float voxel_size, glm::vec3 center,
                     glm::vec3 anchor)
    : r_(resolution), l_(levels) {
  info_.anchor = glm::vec4(anchor, 0.0f);
  info_.dims = glm::uvec4(resolution, levels, 0, 0);
  for (uint32_t l = 0; l < levels; ++l) {
    const float size = voxel_size * static_cast<float>(1u << l);
    const glm::ivec3 origin =
        glm::ivec3(glm::floor((center - anchor) / size)) - glm::ivec3(static_cast<int>(r_ / 2));
    info_.levels[l].origin_voxel = glm::ivec4(origin, 1);
    info_.levels[l].min_corner_size = glm::vec4(glm::vec3(origin) * size, size);
  }
  values_.resize(static_cast<size_t>(r_) * r_ * r_ * l_);
}

size_t VoxelGrid::texel_index(uint32_t level, glm::ivec3 window_voxel) const {
  const int r = static_cast<int>(r_);
  const glm::ivec3 world = window_voxel + glm::ivec3(info_.levels[level].origin_voxel);
  const glm::ivec3 t = ((world % r) + r) % r;
  const size_t z = static_cast<size_t>(t.z) + static_cast<size_t>(level) * r_;
  return (z * r_ + static_cast<size_t>(t.y)) * r_ + static_cast<size_t>(t.x);
}

glm::vec3 VoxelGrid::center(uint32_t level, glm::ivec3 window_voxel) const {
  const contracts::VoxelClipmapLevelInfo& lv = info_.levels[level];
  return glm::vec3(info_.anchor) + glm::vec3(lv.min_corner_size) +
         (glm::vec3(window_voxel) + 0.5f) * lv.min_corner_size.w;
}

glm::ivec3 VoxelGrid::window_voxel_at(uint32_t level, glm::vec3 p) const {
  const contracts::VoxelClipmapLevelInfo& lv = info_.levels[level];
  return glm::ivec3(glm::floor((p - glm::vec3(info_.anchor) - glm::vec3(lv.min_corner_size)) /
                               lv.min_corner_size.w));
}

void VoxelGrid::fill(const std::function<VoxelValue(glm::vec3, float)>& shape) {
  const int r = static_cast<int>(r_);
  for (uint32_t l = 0; l < l_; ++l) {
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const glm::ivec3 v(x, y, z);
          values_[texel_index(l, v)] = shape(center(l, v), size(l));
        }
      }
    }
  }
}

void VoxelGrid::set(uint32_t level, glm::ivec3 window_voxel, const VoxelValue& value) {
  values_[texel_index(level, window_voxel)] = value;
}

std::vector<uint8_t> VoxelGrid::albedo_rgba8() const {
  std::vector<uint8_t> out(values_.size() * 4);
  auto unorm = [](float v) {
    return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  for (size_t i = 0; i < values_.size(); ++i) {
    out[i * 4 + 0] = unorm(values_[i].albedo.r);
    out[i * 4 + 1] = unorm(values_[i].albedo.g);
    out[i * 4 + 2] = unorm(values_[i].albedo.b);
    out[i * 4 + 3] = unorm(values_[i].opacity);
  }
  return out;
}

std::vector<uint16_t> VoxelGrid::normal_rgba16f() const {
  std::vector<uint16_t> out(values_.size() * 4);
  for (size_t i = 0; i < values_.size(); ++i) {
    const glm::vec4 v(values_[i].normal, values_[i].opacity > 0.0f ? 1.0f : 0.0f);
    for (int c = 0; c < 4; ++c) out[i * 4 + static_cast<size_t>(c)] = glm::packHalf1x16(v[c]);
  }
  return out;
}

std::vector<uint16_t> VoxelGrid::emission_rgba16f() const {
  std::vector<uint16_t> out(values_.size() * 4);
  for (size_t i = 0; i < values_.size(); ++i) {
    const glm::vec4 v(values_[i].emission, 0.0f);
    for (int c = 0; c < 4; ++c) out[i * 4 + static_cast<size_t>(c)] = glm::packHalf1x16(v[c]);
  }
  return out;
}

glm::vec4 texel_rgba(const std::vector<float>& rgba, size_t index) {
  return {rgba[index * 4], rgba[index * 4 + 1], rgba[index * 4 + 2], rgba[index * 4 + 3]};
}

}  // namespace voxgi::test
