#include "engine/scene/gpu_bvh.hpp"

#include <algorithm>
#include <cmath>

#include "engine/gpu/context.hpp"

namespace voxgi::scene {
namespace {

uint32_t material_index(const Scene& scene, const Primitive& primitive) {
  return primitive.material >= 0 && primitive.material < static_cast<int>(scene.materials.size())
             ? static_cast<uint32_t>(primitive.material)
             : static_cast<uint32_t>(scene.materials.size());  // GpuScene's default material
}

const Primitive& primitive_of(const Scene& scene, const Instance& instance) {
  return scene.meshes[static_cast<size_t>(instance.mesh)]
      .primitives[static_cast<size_t>(instance.primitive)];
}

float triangle_area(const BvhTriangle& t) {
  return 0.5f * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
}

template <typename T>
std::unique_ptr<gpu::Buffer> make_storage(gpu::Context& context, std::vector<T> values,
                                          const char* name) {
  if (values.empty()) values.resize(1);
  auto buffer = std::make_unique<gpu::Buffer>(context, values.size() * sizeof(T),
                                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              gpu::MemoryUsage::GpuOnly, name);
  buffer->upload_vector(values);
  return buffer;
}

}  // namespace

EmitterTable build_emitter_table(const Scene& scene, const Bvh& bvh) {
  EmitterTable table;
  const std::vector<BvhTriangle>& triangles = bvh.triangles();
  table.pdf_area.assign(triangles.size(), 0.0f);
  std::vector<double> power;
  for (uint32_t i = 0; i < triangles.size(); ++i) {
    const Primitive& primitive = primitive_of(scene, bvh.instances()[triangles[i].instance]);
    const uint32_t m = material_index(scene, primitive);
    if (m >= scene.materials.size()) continue;
    const Material& material = scene.materials[m];
    const glm::vec3 e = material.emissive;
    const double strength = std::max({e.x, e.y, e.z});
    const double area = triangle_area(triangles[i]);
    if (!(strength > 0.0) || !std::isfinite(strength) || !(area > 0.0) || !std::isfinite(area)) {
      continue;
    }
    table.emitters.push_back({i, 0.0f});
    power.push_back(strength * area);
  }
  double total = 0.0;
  for (double p : power) total += p;
  double running = 0.0;
  for (size_t k = 0; k < table.emitters.size(); ++k) {
    running += power[k];
    table.emitters[k].cdf = static_cast<float>(running / total);
    const double probability = power[k] / total;
    table.pdf_area[table.emitters[k].triangle] =
        static_cast<float>(probability / triangle_area(triangles[table.emitters[k].triangle]));
  }
  if (!table.emitters.empty()) table.emitters.back().cdf = 1.0f;
  return table;
}

GpuBvh::GpuBvh(gpu::Context& context, const Scene& scene, const Bvh& bvh) : context_(&context) {
  upload(scene, bvh);
}

GpuBvh::~GpuBvh() = default;

void GpuBvh::update(const Scene& scene, const Bvh& bvh) {
  upload(scene, bvh);
}

void GpuBvh::upload(const Scene& scene, const Bvh& bvh) {
  std::vector<GpuBvhNode> nodes;
  nodes.reserve(bvh.nodes().size());
  for (const BvhNode& n : bvh.nodes())
    nodes.push_back({n.bounds_min, n.first, n.bounds_max, n.count});
  if (nodes.empty()) {
    // A box no ray enters (min > max), marked as an empty leaf.
    nodes.push_back({glm::vec3(1.0f), 0u, glm::vec3(-1.0f), 0u});
  }

  const std::vector<BvhTriangle>& triangles = bvh.triangles();
  const EmitterTable table = build_emitter_table(scene, bvh);
  std::vector<GpuBvhTriangle> positions;
  std::vector<GpuBvhShading> shading;
  positions.reserve(triangles.size());
  shading.reserve(triangles.size());
  for (uint32_t i = 0; i < triangles.size(); ++i) {
    const BvhTriangle& t = triangles[i];
    const Instance& instance = bvh.instances()[t.instance];
    positions.push_back({glm::vec4(t.v0, instance.mirrored ? -1.0f : 1.0f), glm::vec4(t.v1, 0.0f),
                         glm::vec4(t.v2, 0.0f)});

    const Primitive& primitive = primitive_of(scene, instance);
    const glm::mat3 linear(instance.world);
    const float det = glm::determinant(linear);
    const glm::mat3 normal_matrix = std::abs(det) > 1e-30f && std::isfinite(det)
                                        ? glm::transpose(glm::inverse(linear))
                                        : glm::mat3(1.0f);
    GpuBvhShading s{};
    glm::vec2 uv[3], uv1[3];
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t index = primitive.indices[t.index * 3 + k];
      const Vertex vertex =
          index < primitive.vertices.size() ? primitive.vertices[index] : Vertex{};
      s.normal[k] = glm::vec4(normal_matrix * vertex.normal, 0.0f);
      const float handedness = instance.mirrored ? -vertex.tangent.w : vertex.tangent.w;
      s.tangent[k] = glm::vec4(linear * glm::vec3(vertex.tangent), handedness);
      uv[k] = vertex.uv;
      uv1[k] = vertex.uv1;
      s.color[k] = vertex.color;
    }
    s.uv01 = glm::vec4(uv[0], uv[1]);
    s.uv2 = uv[2];
    s.uv1_01 = glm::vec4(uv1[0], uv1[1]);
    s.uv1_2 = glm::vec4(uv1[2], 0.0f, 0.0f);
    s.material = material_index(scene, primitive);
    s.emitter_pdf_area = table.pdf_area[i];
    shading.push_back(s);
  }

  node_count_ = static_cast<uint32_t>(bvh.nodes().size());
  emitter_count_ = static_cast<uint32_t>(table.emitters.size());
  origin_ = glm::vec3(bvh.origin());
  // Re-uploads reuse the buffers when the sizes match (a refit never changes them).
  auto put = [&](std::unique_ptr<gpu::Buffer>& buffer, auto values, const char* name) {
    using T = typename decltype(values)::value_type;
    if (values.empty()) values.resize(1);
    if (buffer && buffer->size() == values.size() * sizeof(T)) {
      buffer->upload_vector(values);
    } else {
      buffer = make_storage(*context_, std::move(values), name);
    }
  };
  put(nodes_, std::move(nodes), "bvh.nodes");
  put(triangles_, std::move(positions), "bvh.triangles");
  put(shading_, std::move(shading), "bvh.shading");
  put(emitters_, table.emitters, "bvh.emitters");
}

}  // namespace voxgi::scene
