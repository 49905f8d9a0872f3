#include "voxel_test_support.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/gpu/gpu_test_env.hpp"

#include <gtest/gtest.h>

namespace voxgi::test {

size_t VoxelVolumes::texel(int level, const glm::ivec3& w) const {
  const int r = static_cast<int>(resolution);
  const glm::ivec3 world = w + glm::ivec3(info.levels[level].origin_voxel);
  const glm::ivec3 t = ((world % r) + r) % r;
  return (static_cast<size_t>(t.z + level * r) * r + t.y) * r + t.x;
}

glm::dvec3 VoxelVolumes::window_coord(int level, const glm::dvec3& world) const {
  const glm::dvec3 anchor(glm::vec3(info.anchor));
  const glm::dvec3 min_corner(glm::vec3(info.levels[level].min_corner_size));
  const double size = info.levels[level].min_corner_size.w;
  return (world - anchor - min_corner) / size;
}

VoxelRun::VoxelRun(const scene::Scene& scene, std::map<std::string, std::string> overrides,
                   const std::string& graph)
    : scene_(scene) {
  scene_.update_transforms();
  const graph::GraphDesc desc =
      graph::load_graph_file(std::filesystem::path(VOXGI_SOURCE_DIR) / graph);
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  loader.load_for_graph(desc, registry_);
  compiled_ =
      graph::compile(desc, registry_, test_compile_options(scene_, 16, 16, std::move(overrides)));
  gpu_ = std::make_unique<TestGraphGpu>(registry_, compiled_, scene_);
  frames_ = std::make_unique<runtime::FrameDriver>(*gpu_->executor);
}

VoxelRun::~VoxelRun() = default;

void VoxelRun::render(const glm::vec3& camera, bool geometry_changed) {
  runtime::FrameView view;
  view.view = glm::lookAt(camera, camera + glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0, 1, 0));
  view.proj = glm::perspective(1.0f, 1.0f, 0.01f, 100.0f);
  view.position = camera;
  frames_->render(view, 0.0, runtime::FrameChanges{true, false, geometry_changed});
}

void VoxelRun::animate(double time) {
  scene_.animate(time);
  gpu_->gpu_scene->update(scene_);
}

std::string VoxelRun::last_skip_reason() const {
  for (const auto& t : gpu_->executor->timings()) {
    if (t.type == "common.voxelize") return t.skipped;
  }
  return "(no voxelize pass)";
}

double VoxelRun::last_gpu_ms() const {
  for (const auto& t : gpu_->executor->timings()) {
    if (t.type == "common.voxelize") return t.gpu_ms;
  }
  return 0.0;
}

namespace {

std::vector<glm::vec4> decode(const std::vector<uint8_t>& bytes, bool half) {
  std::vector<glm::vec4> out;
  if (half) {
    out.resize(bytes.size() / 8);
    for (size_t i = 0; i < out.size(); ++i) {
      uint16_t h[4];
      std::memcpy(h, bytes.data() + i * 8, 8);
      for (int c = 0; c < 4; ++c) out[i][c] = glm::unpackHalf1x16(h[c]);
    }
  } else {
    out.resize(bytes.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) {
      for (int c = 0; c < 4; ++c) out[i][c] = bytes[i * 4 + size_t(c)] / 255.0f;
    }
  }
  return out;
}

}  // namespace

VoxelVolumes VoxelRun::read() {
  VoxelVolumes v;
  gpu::Image* albedo = gpu_->executor->image("voxel.albedo");
  gpu::Image* normal = gpu_->executor->image("voxel.normal");
  gpu::Image* emission = gpu_->executor->image("voxel.emission");
  gpu::Buffer* info = gpu_->executor->buffer("voxel.clipmap_info");
  v.resolution = albedo->extent().width;
  v.levels = albedo->extent().depth / v.resolution;
  info->download(&v.info, sizeof(v.info));
  v.albedo_bytes = albedo->download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  v.normal_bytes = normal->download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  v.emission_bytes = emission->download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  v.albedo = decode(v.albedo_bytes, false);
  v.normal = decode(v.normal_bytes, true);
  v.emission = decode(v.emission_bytes, true);
  if (gpu::Image* faces = gpu_->executor->image("voxel.faces")) {
    const std::vector<uint8_t> bytes = faces->download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    v.faces.resize(bytes.size() / sizeof(glm::uvec4));
    std::memcpy(v.faces.data(), bytes.data(), v.faces.size() * sizeof(glm::uvec4));
  }
  return v;
}

VoxelFace decode_voxel_face(const glm::uvec4& faces, int group) {
  VoxelFace face;
  face.share = float((faces.w >> (5 * group)) & 31u) / 31.0f;
  const uint32_t bits = (faces[group >> 1] >> (16 * (group & 1))) & 0xFFFFu;
  // The point where the normal crosses the group's cube face, and the plane offset.
  const int axis = group >> 1;
  glm::vec3 n;
  n[axis] = (group & 1) == 0 ? 1.0f : -1.0f;
  n[(axis + 1) % 3] = float(bits & 63u) / 31.0f - 1.0f;
  n[(axis + 2) % 3] = float((bits >> 6) & 63u) / 31.0f - 1.0f;
  face.normal = glm::normalize(n);
  face.plane_offset = float(bits >> 12) / 7.0f - 1.0f;
  return face;
}

bool triangle_overlaps_voxel(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             const glm::ivec3& v, double grow) {
  const glm::dvec3 center = glm::dvec3(v) + 0.5;
  const double h = 0.5 + grow;
  const glm::dvec3 p[3] = {a - center, b - center, c - center};
  auto separated = [&](const glm::dvec3& axis) {
    const double d0 = glm::dot(p[0], axis), d1 = glm::dot(p[1], axis), d2 = glm::dot(p[2], axis);
    const double r = h * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
    return std::min({d0, d1, d2}) > r || std::max({d0, d1, d2}) < -r;
  };
  const glm::dvec3 e[3] = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};
  const glm::dvec3 unit[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const glm::dvec3& u : unit) {
    if (separated(u)) return false;
  }
  for (const glm::dvec3& edge : e) {
    for (const glm::dvec3& u : unit) {
      const glm::dvec3 axis = glm::cross(edge, u);
      if (glm::dot(axis, axis) > 0.0 && separated(axis)) return false;
    }
  }
  const glm::dvec3 n = glm::cross(e[0], e[1]);
  if (glm::dot(n, n) > 0.0 && separated(n)) return false;
  return true;
}

std::vector<WorldTriangle> world_triangles(const scene::Scene& scene) {
  std::vector<WorldTriangle> out;
  for (const scene::Instance& inst : scene.instances()) {
    const scene::Primitive& prim =
        scene.meshes[size_t(inst.mesh)].primitives[size_t(inst.primitive)];
    const glm::dmat4 m(inst.world);
    for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
      WorldTriangle t;
      for (int k = 0; k < 3; ++k) {
        t.p[k] = glm::dvec3(
            m * glm::dvec4(glm::dvec3(prim.vertices[prim.indices[i + k]].position), 1.0));
      }
      out.push_back(t);
    }
  }
  return out;
}

scene::Material diffuse(glm::vec3 color) {
  scene::Material m;
  m.base_color = glm::vec4(color, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.double_sided = true;
  return m;
}

// A few dozen random triangles of all sizes in the unit cube, plus thin diagonal walls.
scene::Scene random_scene(uint32_t seed, const glm::mat4& transform) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  scene::SceneBuilder b("random");
  const int mat = b.add_material(diffuse({0.8f, 0.5f, 0.2f}));
  std::vector<scene::Vertex> vertices;
  std::vector<uint32_t> indices;
  for (int t = 0; t < 40; ++t) {
    const glm::vec3 center(unit(rng), unit(rng), unit(rng));
    const float size = t % 3 == 0 ? 0.6f : (t % 3 == 1 ? 0.15f : 0.03f);
    for (int k = 0; k < 3; ++k) {
      scene::Vertex v;
      v.position = center + size * (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f);
      vertices.push_back(v);
      indices.push_back(static_cast<uint32_t>(indices.size()));
    }
  }
  // A thin diagonal wall (two faces 4 mm apart, turned 45°), and a long diagonal sliver.
  const glm::vec3 wall_a(0.1f, 0.1f, 0.2f), wall_u(0.8f, 0.0f, 0.6f), wall_v(0.0f, 0.8f, 0.1f);
  const glm::vec3 offset = 0.004f * glm::normalize(glm::cross(wall_u, wall_v));
  const glm::vec3 quad[2][4] = {
      {wall_a, wall_a + wall_u, wall_a + wall_u + wall_v, wall_a + wall_v},
      {wall_a + offset, wall_a + wall_v + offset, wall_a + wall_u + wall_v + offset,
       wall_a + wall_u + offset}};
  for (const auto& q : quad) {
    const uint32_t first = static_cast<uint32_t>(vertices.size());
    for (const glm::vec3& p : q) {
      scene::Vertex v;
      v.position = p;
      vertices.push_back(v);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(first + i);
  }
  const uint32_t first = static_cast<uint32_t>(vertices.size());
  for (const glm::vec3& p : {glm::vec3(0.02f, 0.05f, 0.03f), glm::vec3(0.97f, 0.93f, 0.96f),
                             glm::vec3(0.975f, 0.94f, 0.95f)}) {
    scene::Vertex v;
    v.position = p;
    vertices.push_back(v);
  }
  for (uint32_t i : {0u, 1u, 2u}) indices.push_back(first + i);
  b.add_mesh("random", vertices, indices, mat, transform);
  return b.finish();
}

// Compares level `level` of the volumes with the CPU overlap test of every scene triangle.
CoverageStats compare_coverage(const VoxelVolumes& v, const scene::Scene& scene, int level) {
  const int r = static_cast<int>(v.resolution);
  std::vector<uint8_t> required(size_t(r) * r * r, 0), allowed(size_t(r) * r * r, 0);
  for (const WorldTriangle& t : world_triangles(scene)) {
    const glm::dvec3 a = v.window_coord(level, t.p[0]), b = v.window_coord(level, t.p[1]),
                     c = v.window_coord(level, t.p[2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double scale = std::max(glm::dot(b - a, b - a), glm::dot(c - a, c - a));
    if (!(glm::dot(n, n) > 1e-12 * scale * scale)) continue;  // zero area: nothing to cover
    const glm::ivec3 lo =
        glm::clamp(glm::ivec3(glm::floor(glm::min(a, glm::min(b, c)))) - 1, 0, r - 1);
    const glm::ivec3 hi =
        glm::clamp(glm::ivec3(glm::floor(glm::max(a, glm::max(b, c)))) + 1, 0, r - 1);
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const size_t i = (size_t(z) * r + y) * r + x;
          if (triangle_overlaps_voxel(a, b, c, {x, y, z}, -1e-3)) required[i] = 1;
          if (triangle_overlaps_voxel(a, b, c, {x, y, z}, 1e-3)) allowed[i] = 1;
        }
      }
    }
  }
  CoverageStats s;
  for (int z = 0; z < r; ++z) {
    for (int y = 0; y < r; ++y) {
      for (int x = 0; x < r; ++x) {
        const size_t i = (size_t(z) * r + y) * r + x;
        const bool gpu = v.occupied(level, {x, y, z});
        s.required += required[i];
        s.set += gpu;
        if (required[i] && !gpu) ++s.holes;
        if (gpu && !allowed[i]) ++s.false_positives;
      }
    }
  }
  return s;
}

void check_coverage(const char* what, const scene::Scene& scene,
                    std::map<std::string, std::string> overrides) {
  overrides.emplace("voxel.resolution", "32");
  overrides.emplace("voxel.levels", "1");
  VoxelRun run(scene, overrides);
  const auto start = std::chrono::steady_clock::now();
  run.render(glm::vec3(0.5f));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const VoxelVolumes v = run.read();
  const CoverageStats s = compare_coverage(v, scene, 0);
  std::printf(
      "[%s] required %zu, set %zu, holes %zu, false positives %zu (%.3f%%), frame %.1f ms\n", what,
      s.required, s.set, s.holes, s.false_positives,
      s.set ? 100.0 * double(s.false_positives) / double(s.set) : 0.0, ms);
  EXPECT_GT(s.required, 100u) << what;
  EXPECT_EQ(s.holes, 0u) << what << ": voxels the triangles overlap were left empty";
  EXPECT_LE(s.false_positives, s.set / 100) << what << ": more than 1% false positives";
  for (const glm::vec4& n : v.normal) ASSERT_TRUE(std::isfinite(n.x + n.y + n.z + n.w)) << what;
}

}  // namespace voxgi::test
