#include "engine/scene/scene_builder.hpp"

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include <cmath>

#include "engine/scene/geometry.hpp"

namespace voxgi::scene {

glm::quat rotation_towards(glm::vec3 direction, glm::vec3 up) {
  const float len = glm::length(direction);
  if (!(len > 1e-20f) || !std::isfinite(len)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  const glm::vec3 d = direction / len;
  // An up vector parallel to the direction has no defined roll: pick another one.
  if (std::abs(glm::dot(d, glm::normalize(up))) > 0.999f) {
    up = std::abs(d.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  }
  return glm::quatLookAtRH(d, up);  // maps local -Z to d and local +Y towards up
}

SceneBuilder::SceneBuilder(std::string name) {
  scene_.name = name;
  scene_.source = "builtin:" + name;
}

void SceneBuilder::fail(const std::string& field, const std::string& what) const {
  throw SceneError(scene_.source + ": " + field + ": " + what);
}

int SceneBuilder::add_material(const Material& material) {
  scene_.materials.push_back(material);
  return static_cast<int>(scene_.materials.size()) - 1;
}

int SceneBuilder::add_texture(Texture texture) {
  const size_t expected =
      size_t(texture.width) * texture.height * 4 * (texture.bits == 16 ? 2u : 1u);
  if (texture.channels != 4 || (texture.bits != 8 && texture.bits != 16) || texture.width == 0 ||
      texture.height == 0 || texture.pixels.size() != expected) {
    fail("textures[" + std::to_string(scene_.textures.size()) + "] \"" + texture.name + "\"",
         "expected RGBA 8 or 16 bit pixels of width × height × 4 × bits/8 = " +
             std::to_string(expected) + " bytes");
  }
  scene_.textures.push_back(std::move(texture));
  return static_cast<int>(scene_.textures.size()) - 1;
}

int SceneBuilder::add_node(const std::string& name, const glm::mat4& transform) {
  Node node;
  node.name = name;
  if (transform != glm::mat4(1.0f)) {
    glm::vec3 scale, translation, skew;
    glm::quat rotation;
    glm::vec4 perspective;
    bool exact = glm::decompose(transform, scale, rotation, translation, skew, perspective);
    if (exact) {
      Node trs;
      trs.translation = translation;
      trs.rotation = rotation;
      trs.scale = scale;
      const glm::mat4 back = trs.local();
      for (int c = 0; c < 4 && exact; ++c) {
        for (int r = 0; r < 4; ++r) {
          if (std::abs(back[c][r] - transform[c][r]) > 1e-5f * (1.0f + std::abs(transform[c][r]))) {
            exact = false;
            break;
          }
        }
      }
    }
    if (exact) {
      node.translation = translation;
      node.rotation = rotation;
      node.scale = scale;
    } else {
      node.matrix = transform;
    }
  }
  scene_.nodes.push_back(std::move(node));
  return static_cast<int>(scene_.nodes.size()) - 1;
}

void SceneBuilder::set_parent(int child, int parent) {
  const int count = static_cast<int>(scene_.nodes.size());
  if (child < 0 || child >= count || parent < 0 || parent >= count || child == parent) {
    fail("nodes", "set_parent(" + std::to_string(child) + ", " + std::to_string(parent) +
                      "): node out of range or the same node");
  }
  // Refuse cycles: the parent must not be a descendant of the child.
  for (int n = parent; n >= 0; n = scene_.nodes[size_t(n)].parent) {
    if (n == child) fail("nodes[" + std::to_string(child) + "]", "set_parent would make a cycle");
  }
  Node& node = scene_.nodes[size_t(child)];
  if (node.parent >= 0) {
    auto& siblings = scene_.nodes[size_t(node.parent)].children;
    std::erase(siblings, child);
  }
  node.parent = parent;
  scene_.nodes[size_t(parent)].children.push_back(child);
}

int SceneBuilder::add_mesh(const std::string& name, std::vector<Vertex> vertices,
                           std::vector<uint32_t> indices, int material,
                           const glm::mat4& transform) {
  const std::string field = "meshes[" + std::to_string(scene_.meshes.size()) + "] \"" + name + "\"";
  if (material >= static_cast<int>(scene_.materials.size())) {
    fail(field + ".material", "material " + std::to_string(material) + " out of range (" +
                                  std::to_string(scene_.materials.size()) + " materials)");
  }
  if (indices.size() % 3 != 0) fail(field + ".indices", "count must be a multiple of 3");
  for (uint32_t index : indices) {
    if (index >= vertices.size()) {
      fail(field + ".indices", "index " + std::to_string(index) + " out of range (" +
                                   std::to_string(vertices.size()) + " vertices)");
    }
  }
  Primitive primitive;
  primitive.vertices = std::move(vertices);
  primitive.indices = std::move(indices);
  primitive.material = material;
  repair_normals(primitive);
  generate_tangents(primitive);
  compute_bounds(primitive);
  Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(std::move(primitive));
  scene_.meshes.push_back(std::move(mesh));
  const int node = add_node(name, transform);
  scene_.nodes[size_t(node)].mesh = static_cast<int>(scene_.meshes.size()) - 1;
  return node;
}

int SceneBuilder::add_quad(const std::string& name, glm::vec3 origin, glm::vec3 edge_u,
                           glm::vec3 edge_v, int material) {
  const glm::vec3 normal = glm::cross(edge_u, edge_v);
  std::vector<Vertex> vertices(4);
  const glm::vec3 corners[4] = {origin, origin + edge_u, origin + edge_u + edge_v, origin + edge_v};
  const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    vertices[size_t(i)].position = corners[i];
    vertices[size_t(i)].normal = normal;  // normalized (or repaired) by add_mesh
    vertices[size_t(i)].uv = uvs[i];
  }
  return add_mesh(name, std::move(vertices), {0, 1, 2, 0, 2, 3}, material);
}

int SceneBuilder::add_box(const std::string& name, glm::vec3 center, glm::vec3 size, int material,
                          float rotation_y) {
  // A unit cube's six faces as quads (origin, u, v) facing outwards, then scaled and placed
  // by the node so the normals stay exact.
  struct Face {
    glm::vec3 origin, u, v;
  };
  const Face faces[6] = {
      {{0.5f, -0.5f, 0.5f}, {0, 0, -1}, {0, 1, 0}},   // +X
      {{-0.5f, -0.5f, -0.5f}, {0, 0, 1}, {0, 1, 0}},  // -X
      {{-0.5f, 0.5f, 0.5f}, {1, 0, 0}, {0, 0, -1}},   // +Y
      {{-0.5f, -0.5f, -0.5f}, {1, 0, 0}, {0, 0, 1}},  // -Y
      {{-0.5f, -0.5f, 0.5f}, {1, 0, 0}, {0, 1, 0}},   // +Z
      {{0.5f, -0.5f, -0.5f}, {-1, 0, 0}, {0, 1, 0}},  // -Z
  };
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Face& face : faces) {
    const glm::vec3 corners[4] = {face.origin, face.origin + face.u, face.origin + face.u + face.v,
                                  face.origin + face.v};
    const uint32_t base = static_cast<uint32_t>(vertices.size());
    for (int i = 0; i < 4; ++i) {
      Vertex vertex;
      vertex.position = corners[i];
      vertex.normal = glm::cross(face.u, face.v);
      vertex.uv = uvs[i];
      vertices.push_back(vertex);
    }
    for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
  }
  const glm::mat4 transform =
      glm::translate(glm::mat4(1.0f), center) *
      glm::rotate(glm::mat4(1.0f), rotation_y, glm::vec3(0.0f, 1.0f, 0.0f)) *
      glm::scale(glm::mat4(1.0f), size);
  return add_mesh(name, std::move(vertices), std::move(indices), material, transform);
}

int SceneBuilder::add_light(const Light& light, glm::vec3 position, glm::vec3 direction) {
  const int node = add_node(light.name);
  Node& n = scene_.nodes[size_t(node)];
  n.translation = position;
  n.rotation = rotation_towards(direction);
  n.light = static_cast<int>(scene_.lights.size());
  Light copy = light;
  copy.node = node;
  scene_.lights.push_back(std::move(copy));
  return node;
}

int SceneBuilder::add_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov,
                             glm::vec3 up) {
  const int node = add_node(name);
  Node& n = scene_.nodes[size_t(node)];
  n.translation = eye;
  n.rotation = rotation_towards(target - eye, up);
  Camera camera;
  camera.name = name;
  camera.yfov = yfov;
  camera.zfar = 0.0f;  // set from the bounds in finish()
  camera.node = node;
  n.camera = static_cast<int>(scene_.cameras.size());
  scene_.cameras.push_back(std::move(camera));
  return node;
}

Scene SceneBuilder::finish() {
  scene_.update_transforms();
  glm::vec3 mn, mx;
  scene_.bounds(mn, mx);
  const float radius = 0.5f * glm::length(mx - mn);
  for (Camera& camera : scene_.cameras) {
    if (camera.zfar > camera.znear) continue;
    const float distance = glm::length(glm::vec3(camera.world[3]) - 0.5f * (mn + mx));
    camera.zfar = std::max((distance + radius) * 1.5f, camera.znear * 1000.0f);
  }
  return std::move(scene_);
}

}  // namespace voxgi::scene
