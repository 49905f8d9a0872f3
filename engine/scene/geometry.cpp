#include "engine/scene/geometry.hpp"

#include <cmath>
#include <limits>

namespace voxgi::scene {

namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Normalized v, or `fallback` when v is too short or not finite.
glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  if (!finite(v)) return fallback;
  const float len = glm::length(v);
  if (!(len > 1e-20f) || !std::isfinite(len)) return fallback;
  return v / len;
}

glm::vec3 face_normal_unnormalized(const Primitive& p, size_t tri) {
  const glm::vec3& a = p.vertices[p.indices[tri * 3]].position;
  const glm::vec3& b = p.vertices[p.indices[tri * 3 + 1]].position;
  const glm::vec3& c = p.vertices[p.indices[tri * 3 + 2]].position;
  return glm::cross(b - a, c - a);
}

}  // namespace

glm::vec3 any_perpendicular(const glm::vec3& n) {
  const glm::vec3 axis =
      std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return safe_normalize(glm::cross(axis, n), glm::vec3(0.0f, 0.0f, 1.0f));
}

void make_flat_normals(Primitive& primitive) {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  vertices.reserve(primitive.indices.size());
  indices.reserve(primitive.indices.size());
  const size_t triangles = primitive.indices.size() / 3;
  for (size_t t = 0; t < triangles; ++t) {
    const glm::vec3 n =
        safe_normalize(face_normal_unnormalized(primitive, t), glm::vec3(0.0f, 1.0f, 0.0f));
    for (int k = 0; k < 3; ++k) {
      Vertex v = primitive.vertices[primitive.indices[t * 3 + static_cast<size_t>(k)]];
      v.normal = n;
      indices.push_back(static_cast<uint32_t>(vertices.size()));
      vertices.push_back(v);
    }
  }
  primitive.vertices = std::move(vertices);
  primitive.indices = std::move(indices);
}

void repair_normals(Primitive& primitive) {
  std::vector<size_t> broken;
  for (size_t i = 0; i < primitive.vertices.size(); ++i) {
    glm::vec3& n = primitive.vertices[i].normal;
    const glm::vec3 fixed = safe_normalize(n, glm::vec3(0.0f));
    if (fixed == glm::vec3(0.0f)) broken.push_back(i);
    n = fixed;
  }
  if (broken.empty()) return;
  // Area-weighted face normals around each vertex (the cross product's length is 2 × area).
  std::vector<glm::vec3> accumulated(primitive.vertices.size(), glm::vec3(0.0f));
  const size_t triangles = primitive.indices.size() / 3;
  for (size_t t = 0; t < triangles; ++t) {
    glm::vec3 face = face_normal_unnormalized(primitive, t);
    if (!finite(face)) continue;
    for (int k = 0; k < 3; ++k)
      accumulated[primitive.indices[t * 3 + static_cast<size_t>(k)]] += face;
  }
  for (size_t i : broken) {
    primitive.vertices[i].normal = safe_normalize(accumulated[i], glm::vec3(0.0f, 1.0f, 0.0f));
  }
}

void generate_tangents(Primitive& primitive) {
  const size_t count = primitive.vertices.size();
  std::vector<glm::vec3> tangents(count, glm::vec3(0.0f));
  std::vector<glm::vec3> bitangents(count, glm::vec3(0.0f));
  const size_t triangles = primitive.indices.size() / 3;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t i0 = primitive.indices[t * 3], i1 = primitive.indices[t * 3 + 1],
                   i2 = primitive.indices[t * 3 + 2];
    const Vertex &v0 = primitive.vertices[i0], &v1 = primitive.vertices[i1],
                 &v2 = primitive.vertices[i2];
    const glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
    const glm::vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
    const float det = d1.x * d2.y - d2.x * d1.y;
    // Collinear or repeated UVs give no tangent frame: skip, the fallback below handles it.
    if (!(std::abs(det) > 1e-12f) || !std::isfinite(det)) continue;
    const float r = 1.0f / det;
    const glm::vec3 tangent = (e1 * d2.y - e2 * d1.y) * r;
    const glm::vec3 bitangent = (e2 * d1.x - e1 * d2.x) * r;
    if (!finite(tangent) || !finite(bitangent)) continue;
    for (uint32_t i : {i0, i1, i2}) {
      tangents[i] += tangent;
      bitangents[i] += bitangent;
    }
  }
  for (size_t i = 0; i < count; ++i) {
    Vertex& v = primitive.vertices[i];
    const glm::vec3 n = safe_normalize(v.normal, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 t = tangents[i] - n * glm::dot(n, tangents[i]);
    const glm::vec3 unit = safe_normalize(t, glm::vec3(0.0f));
    if (unit == glm::vec3(0.0f)) {
      v.tangent = glm::vec4(any_perpendicular(n), 1.0f);
      continue;
    }
    const float handedness = glm::dot(glm::cross(n, unit), bitangents[i]) < 0.0f ? -1.0f : 1.0f;
    v.tangent = glm::vec4(unit, handedness);
  }
}

void repair_tangents(Primitive& primitive) {
  for (Vertex& v : primitive.vertices) {
    const glm::vec3 t(v.tangent);
    const glm::vec3 ortho = t - v.normal * glm::dot(v.normal, t);
    const glm::vec3 unit = safe_normalize(ortho, glm::vec3(0.0f));
    if (unit == glm::vec3(0.0f) || !std::isfinite(v.tangent.w)) {
      generate_tangents(primitive);
      return;
    }
    v.tangent = glm::vec4(unit, v.tangent.w < 0.0f ? -1.0f : 1.0f);
  }
}

void compute_bounds(Primitive& primitive) {
  if (primitive.vertices.empty()) {
    primitive.bounds_min = primitive.bounds_max = glm::vec3(0.0f);
    return;
  }
  primitive.bounds_min = glm::vec3(std::numeric_limits<float>::max());
  primitive.bounds_max = glm::vec3(std::numeric_limits<float>::lowest());
  for (const Vertex& v : primitive.vertices) {
    primitive.bounds_min = glm::min(primitive.bounds_min, v.position);
    primitive.bounds_max = glm::max(primitive.bounds_max, v.position);
  }
}

std::vector<uint32_t> flip_winding(const std::vector<uint32_t>& indices) {
  std::vector<uint32_t> flipped = indices;
  for (size_t t = 0; t + 2 < flipped.size(); t += 3) std::swap(flipped[t + 1], flipped[t + 2]);
  return flipped;
}

}  // namespace voxgi::scene
