#pragma once
// The CPU-side scene: plain data loaded from glTF or built procedurally, plus the few
// operations every consumer needs (transforms, animation, instances, bounds, features).

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace voxgi::scene {

// Any problem with a scene source: the message starts with the file (or builtin name) and
// names the offending field.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Also the GPU vertex layout (see GpuScene::vertex_attributes()).
struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz, w = bitangent handedness (±1)
  glm::vec2 uv{0.0f};                         // TEXCOORD_0
  glm::vec2 uv1{0.0f};                        // TEXCOORD_1 (glTF lets any texture pick either set)
  glm::vec4 color{1.0f};                      // COLOR_0, linear RGBA; multiplies the base colour
};
static_assert(sizeof(Vertex) == 72);

struct Primitive {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, counter-clockwise front faces
  int material = -1;              // -1: the default material (white, rough, dielectric)
  glm::vec3 bounds_min{0.0f};     // object space
  glm::vec3 bounds_max{0.0f};
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

struct Texture {
  std::string name;
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t channels = 4;  // always expanded to RGBA
  uint32_t bits = 8;      // 8 or 16 per channel; 16-bit pixels are native-endian uint16
  std::vector<uint8_t> pixels;
  bool srgb = false;  // true for baseColor and emissive use
  bool wrap_repeat = true;
};

enum class AlphaMode { Opaque, Mask, Blend };

// How one material slot maps a surface point to texture coordinates: the TEXCOORD set, then
// KHR_texture_transform's offset, rotation and scale (uv' = T * R * S * uv).
struct TextureMapping {
  int tex_coord = 0;  // 0 or 1
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in uv space
  glm::vec2 scale{1.0f};

  // Rows of the 2×3 matrix: uv' = (dot(row0, (u, v, 1)), dot(row1, (u, v, 1))).
  void matrix_rows(glm::vec3& row0, glm::vec3& row1) const;
  glm::vec2 apply(glm::vec2 uv) const;
};

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};  // factor × KHR_materials_emissive_strength
  float normal_scale = 1.0f;
  float occlusion_strength = 1.0f;
  float alpha_cutoff = 0.5f;
  AlphaMode alpha_mode = AlphaMode::Opaque;
  bool double_sided = false;
  // Indices into Scene::textures; a texture used both as sRGB and linear has two entries.
  int base_color_tex = -1;
  int metallic_roughness_tex = -1;
  int normal_tex = -1;
  int occlusion_tex = -1;
  int emissive_tex = -1;
  // Per slot, in the order above (base colour, metallic-roughness, normal, occlusion, emissive).
  TextureMapping mappings[5];
};

enum class LightType { Directional, Point, Spot };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;  // candela for point/spot, lux for directional
  float range = 0.0f;      // 0 = infinite
  float inner_cone = 0.0f;
  float outer_cone = 0.7853981633974483f;  // pi / 4
  int node = -1;                           // the light shines along the node's -Z
  glm::vec3 position{0.0f};                // world, filled by update_transforms()
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world, where the light points
};

struct Camera {
  std::string name;
  float yfov = 0.7f;  // radians
  float znear = 0.01f;
  float zfar = 1000.0f;   // the loader replaces glTF's "infinite" by a far plane from the bounds
  float aspect = 0.0f;    // 0 = use the viewport
  int node = -1;          // looks along the node's -Z, +Y up
  glm::mat4 world{1.0f};  // filled by update_transforms()
};

struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};
  std::optional<glm::mat4> matrix;  // glTF "matrix" nodes keep it (glTF forbids animating them)
  int mesh = -1;
  int camera = -1;
  int light = -1;
  glm::mat4 world{1.0f};  // filled by update_transforms()
  bool animated = false;  // targeted by an animation channel

  glm::mat4 local() const;
};

enum class AnimationPath { Translation, Rotation, Scale };
enum class Interpolation { Linear, Step, CubicSpline };

struct AnimationChannel {
  int node = -1;
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds, increasing
  // One value per key (xyz or quaternion xyzw); CUBICSPLINE: three per key
  // (in-tangent, value, out-tangent) as glTF stores them.
  std::vector<glm::vec4> values;
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  float duration = 0.0f;  // last key time over all channels; animations loop
};

// One drawable: a primitive placed by a node. A negative-determinant world matrix mirrors the
// mesh; `mirrored` tells consumers that the winding is flipped (GpuScene handles it by
// drawing a winding-swapped copy of the indices, so pipelines need not care).
struct Instance {
  int mesh = -1;
  int primitive = -1;
  int node = -1;
  glm::mat4 world{1.0f};
  bool mirrored = false;
};

struct SceneFeatures {
  bool has_emissive = false;
  bool has_glossy = false;  // a used material with roughness < 0.6 or metallic > 0.1
  bool has_textures = false;
  bool has_animation = false;
  bool has_dynamic_geometry = false;  // an animation moves a node that carries a mesh
  bool has_point_lights = false;
  bool has_spot_lights = false;
  bool has_directional_lights = false;
  uint32_t light_count = 0;
  uint32_t triangle_count = 0;
  uint32_t instance_count = 0;
  glm::vec3 bounds_min{0.0f};
  glm::vec3 bounds_max{0.0f};

  // Keys "scene.has_emissive", ..., "scene.light_count", "scene.triangle_count",
  // "scene.extent" (largest bounds side), "scene.empty"; booleans are 0/1.
  std::map<std::string, double> as_map() const;
};

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 1e-3f;
};

struct Scene {
  std::string name;
  std::string source;  // file path or "builtin:<name>"
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<Node> nodes;
  std::vector<Animation> animations;
  std::vector<std::string> warnings;  // unsupported features, reported and skipped

  // World matrices of all nodes, then light positions/directions and camera worlds.
  void update_transforms();
  // Evaluates all animations at `time_seconds` (looping) and updates transforms. Returns
  // true when any animated node's transform changed since the previous call.
  bool animate(double time_seconds);
  std::vector<Instance> instances() const;
  // World-space bounds over all instances' vertices; (0,0,0) both when there are none.
  void bounds(glm::vec3& mn, glm::vec3& mx) const;
  // The sphere around bounds(), radius at least 1 mm (what lights' cameras are fitted to).
  // Walks every vertex, as bounds() does.
  BoundingSphere bounding_sphere() const;
  SceneFeatures features() const;
  const Camera* find_camera(std::string_view camera_name) const;
};

glm::mat4 view_matrix(const Camera& camera);
// Vulkan clip space: y down, depth 0..1 (GLM_FORCE_DEPTH_ZERO_TO_ONE). With this y flip the
// image is upright and glTF's counter-clockwise front faces stay VK_FRONT_FACE_COUNTER_CLOCKWISE.
glm::mat4 projection_matrix(const Camera& camera, float viewport_aspect);
// A camera that frames the scene bounds from +Z, slightly above; for scenes without one.
Camera default_camera(const Scene& scene);

}  // namespace voxgi::scene
