#pragma once
// Procedural scene construction for built-in scenes and generated test scenes. Every
// add_* call places its object under a new root node and returns that node's index.

#include <string>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string name);

  int add_material(const Material& material);  // returns the material index
  int add_texture(Texture texture);            // returns the texture index

  // One primitive under a node with `transform` (decomposed into TRS when it has no shear,
  // else kept as a matrix). Normals are repaired and tangents generated, so the vertex data
  // may come with zero normals and degenerate triangles. Throws SceneError for indices out
  // of range or a material that does not exist.
  int add_mesh(const std::string& name, std::vector<Vertex> vertices, std::vector<uint32_t> indices,
               int material, const glm::mat4& transform = glm::mat4(1.0f));
  // The parallelogram origin, origin+u, origin+u+v, origin+v, facing normalize(cross(u, v)).
  int add_quad(const std::string& name, glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v,
               int material);
  // An axis-aligned box of `size` around `center`, turned by `rotation_y` radians about +Y.
  int add_box(const std::string& name, glm::vec3 center, glm::vec3 size, int material,
              float rotation_y = 0.0f);
  // `position` is ignored for directional lights except as the node's place; `direction`
  // is where the light points (ignored for point lights).
  int add_light(const Light& light, glm::vec3 position,
                glm::vec3 direction = glm::vec3(0.0f, -1.0f, 0.0f));
  int add_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov,
                 glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f));
  // A root node without content, e.g. a parent for animation tests.
  int add_node(const std::string& name, const glm::mat4& transform = glm::mat4(1.0f));
  void set_parent(int child, int parent);

  Scene& scene() { return scene_; }  // for edits the helpers do not cover (animations)
  // Computes transforms and gives cameras without a far plane one from the bounds.
  Scene finish();

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& what) const;

  Scene scene_;
};

// The rotation that turns a node's -Z axis towards `direction` (any length > 0).
glm::quat rotation_towards(glm::vec3 direction, glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f));

}  // namespace voxgi::scene
