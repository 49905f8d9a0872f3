#pragma once
// The BVH on the GPU, for compute-shader ray tracing (shaders/lib/bvh_traversal.glsl): node
// and triangle storage buffers, the triangles' shading attributes (world-space normals,
// tangents, uvs, material) and a table of emissive triangles for light sampling.
//
// Everything is in the BVH's frame: world space minus Bvh::origin(), so that rays of a scene
// far from the world origin keep their precision. Shaders subtract origin() from world
// positions (the camera) before tracing.

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/scene/bvh.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::gpu {
class Context;
}

namespace voxgi::scene {

// std430 mirrors of the structs in shaders/lib/bvh_traversal.glsl. Keep them in step.
struct GpuBvhNode {
  glm::vec3 bounds_min;
  uint32_t first;  // inner: first child; leaf: first triangle
  glm::vec3 bounds_max;
  uint32_t count;  // 0: inner node
};
static_assert(sizeof(GpuBvhNode) == 32);

struct GpuBvhTriangle {
  // xyz relative to the BVH origin. v0.w: which side of cross(v1 - v0, v2 - v0) is the glTF
  // front (counter-clockwise winding): +1, or -1 under a mirroring transform, whose winding
  // is clockwise. v1.w, v2.w unused.
  glm::vec4 v0, v1, v2;
};
static_assert(sizeof(GpuBvhTriangle) == 48);

struct GpuBvhShading {
  glm::vec4 normal[3];   // world space, not normalised; w unused
  glm::vec4 tangent[3];  // world space xyz, w: bitangent sign (mirroring applied)
  glm::vec4 uv01;        // uv of vertex 0 (xy) and 1 (zw)
  glm::vec2 uv2;
  uint32_t material;  // index into GpuScene's material buffer
  // Probability density per unit area with which light sampling picks a point of this
  // triangle (selection probability / area); 0 when it is not an emitter.
  float emitter_pdf_area;
  glm::vec4 uv1_01;    // TEXCOORD_1 of vertex 0 (xy) and 1 (zw)
  glm::vec4 uv1_2;     // xy: TEXCOORD_1 of vertex 2; zw unused
  glm::vec4 color[3];  // COLOR_0 (linear RGBA) per vertex
};
static_assert(sizeof(GpuBvhShading) == 208);

// Emissive triangles, picked in proportion to emitted power (area × max emissive component).
struct GpuEmitter {
  uint32_t triangle;  // index into the triangle buffer
  float cdf;          // inclusive cumulative probability; the last one is 1
};
static_assert(sizeof(GpuEmitter) == 8);

class GpuBvh {
 public:
  // Uploads (waits for the queue). An empty BVH gets one node that no ray hits.
  GpuBvh(gpu::Context& context, const Scene& scene, const Bvh& bvh);
  ~GpuBvh();
  GpuBvh(const GpuBvh&) = delete;
  GpuBvh& operator=(const GpuBvh&) = delete;

  // After Bvh::refit(): re-uploads nodes, triangles, shading and the emitter table. Call it
  // between frames, not while one using the buffers is in flight.
  void update(const Scene& scene, const Bvh& bvh);

  const gpu::Buffer& nodes() const { return *nodes_; }
  const gpu::Buffer& triangles() const { return *triangles_; }
  const gpu::Buffer& shading() const { return *shading_; }
  const gpu::Buffer& emitters() const { return *emitters_; }
  uint32_t node_count() const { return node_count_; }  // 0 for an empty scene
  uint32_t emitter_count() const { return emitter_count_; }
  glm::vec3 origin() const { return origin_; }

 private:
  void upload(const Scene& scene, const Bvh& bvh);

  gpu::Context* context_;
  std::unique_ptr<gpu::Buffer> nodes_, triangles_, shading_, emitters_;
  uint32_t node_count_ = 0;
  uint32_t emitter_count_ = 0;
  glm::vec3 origin_{0.0f};
};

// The emitter table and each triangle's emitter density, as GpuBvh uploads them.
struct EmitterTable {
  std::vector<GpuEmitter> emitters;
  std::vector<float> pdf_area;  // per BVH triangle
};
EmitterTable build_emitter_table(const Scene& scene, const Bvh& bvh);

}  // namespace voxgi::scene
