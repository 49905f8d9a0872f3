// voxgi bench voxel-light --scene S: how well one voxel's injected direct light can stand for
// the light on the surfaces inside it, per voxel size, by exact sampling on the CPU. It
// isolates the model vct.inject and dvs.voxel_lighting share: a voxel's surfaces are lit as
// one plane with the voxel's averaged normal, times the fraction of the voxel the light
// reaches.
//
// Points are spread over every triangle by area; each is lit by the scene's first directional
// light with its geometric normal, its visibility found by a ray through the scene BVH. Per
// voxel the exact value is the area mean of max(n . l, 0) x visibility. The injected model
// takes the voxel's mean normal as the voxelizer forms it (the plain mean over the triangles
// that write the voxel, one write per triangle), normalized, and multiplies its clamped
// cosine by a visibility. Which visibility the injections' shadow lookups stand for lies
// between two that are printed: the area mean over all the voxel's surfaces (surfaces turned
// away from the light count as unlit, so together with the cosine they count twice), and the
// area mean over the surfaces that face the light (what lookups just in front of the mean
// surface plane see where that plane faces the light). Printed per voxel edge: the mean of
// the exact value over voxels, the model's bias with each visibility, with an area-weighted
// mean normal and with the voxelizer's faces (each facing lit on its own, weighted by triangle
// count or by area), and the same split by how far the writers' normals agree.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "apps/voxgi/bench_subcommands.hpp"
#include "apps/voxgi/cli_args.hpp"
#include "engine/runtime/scene_source.hpp"
#include "engine/scene/bvh.hpp"

namespace voxgi::cli {
namespace {

struct SurfacePoint {
  glm::dvec3 position;  // world
  glm::vec3 normal;     // geometric, unit
  uint32_t triangle = 0;
  float area = 0.0f;  // of the triangle this point stands for
  float visible = 0.0f;
};

struct VoxelSums {
  double area = 0.0;
  double lit = 0.0;                   // area x max(n.l, 0) x visibility
  double visible = 0.0;               // area x visibility
  double facing_area = 0.0;           // area of the surfaces facing the light
  double facing_visible = 0.0;        // their area x visibility
  glm::dvec3 area_normal_sum{0.0};    // area x normal
  glm::dvec3 writer_normal_sum{0.0};  // one unit normal per triangle in the voxel
  std::unordered_set<uint32_t> triangles;
  // Per group of the faces volume (the signed axis a normal leans furthest along): the
  // writers' normal sum and count, the light-facing area and its area x visibility.
  std::array<glm::dvec3, 6> group_normal_sum{};
  std::array<double, 6> group_writers{}, group_area{}, group_facing_area{}, group_facing_visible{};
};

// The group of the faces volume a unit normal falls in (contracts/voxel_volumes.glsl).
int face_group(glm::vec3 n) {
  const glm::vec3 a = glm::abs(n);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return axis * 2 + (n[axis] < 0.0f ? 1 : 0);
}

struct Totals {
  size_t voxels = 0;
  double exact = 0.0;
  double model = 0.0;             // writers' mean normal, mean visibility of all surfaces
  double facing_model = 0.0;      // writers' mean normal, visibility of the light-facing ones
  double area_model = 0.0;        // area-weighted mean normal, light-facing visibility
  double group_model = 0.0;       // each facing group as a plane, its own light-facing visibility
  double group_area_model = 0.0;  // the same, groups weighted by their area
};

std::vector<SurfacePoint> sample_surfaces(const scene::Bvh& bvh, double finest_edge,
                                          int samples_per_face) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<SurfacePoint> points;
  const auto& triangles = bvh.triangles();
  const double face_area = finest_edge * finest_edge;
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    const scene::BvhTriangle& tri = triangles[t];
    const glm::vec3 cross = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    const float area = 0.5f * glm::length(cross);
    if (!(area > 0.0f) || !std::isfinite(area)) continue;
    // Expected count by area; the fraction decided at random so that small triangles count.
    const double expected = double(area) / face_area * samples_per_face;
    int count = int(expected);
    if (uniform(rng) < expected - count) ++count;
    for (int i = 0; i < count; ++i) {
      float u = uniform(rng), v = uniform(rng);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      const glm::vec3 p = tri.v0 + u * (tri.v1 - tri.v0) + v * (tri.v2 - tri.v0);
      points.push_back({glm::dvec3(p) + bvh.origin(), cross / (2.0f * area), t,
                        float(double(area) / expected), 0.0f});
    }
  }
  return points;
}

// Visibility towards l from the side of each point's surface that faces it (both faces of a
// triangle are lit, as the path tracer does).
void trace_visibility(const scene::Bvh& bvh, glm::vec3 l, float lift,
                      std::vector<SurfacePoint>& points) {
  const unsigned workers = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < workers; ++w) {
    threads.emplace_back([&, w] {
      for (size_t i = w; i < points.size(); i += workers) {
        SurfacePoint& q = points[i];
        const glm::vec3 side = glm::dot(q.normal, l) >= 0.0f ? q.normal : -q.normal;
        const glm::dvec3 origin = q.position + glm::dvec3(side * lift);
        q.visible = bvh.intersect(origin, l, 0.0f, 1e30f) ? 0.0f : 1.0f;
      }
    });
  }
  for (std::thread& t : threads) t.join();
}

// vct.inject's cosine for a mean normal: that of its direction; a voxel whose writers cancel
// (|mean| < VOXEL_NORMAL_MIN_LENGTH = 0.25) is lit as facing the light.
double injected_cosine(glm::dvec3 mean, glm::vec3 l) {
  const double length = glm::length(mean);
  return length < 0.25 ? 1.0 : std::max(0.0, glm::dot(mean / length, glm::dvec3(l)));
}

// Voxels per axis on either side of the world origin that voxel_key can tell apart. The grid
// is anchored to the world, as the voxel clipmaps are.
constexpr double kMaxCellsFromOrigin = 1048576.0;  // 2^20: 21 bits per axis

uint64_t voxel_key(glm::dvec3 p, double edge) {
  const glm::dvec3 cell = glm::floor(p / edge) + kMaxCellsFromOrigin;
  return (uint64_t(cell.x) << 42) | (uint64_t(cell.y) << 21) | uint64_t(cell.z);
}

}  // namespace

int bench_voxel_light_command(const std::vector<std::string>& argv) {
  Args args("voxgi bench voxel-light",
            {{"scene", true, false, "cornell|PATH.gltf|PATH.glb",
              "scene with a directional light (default cornell)"},
             {"voxel-mm", true, false, "MM", "finest voxel edge in millimetres (default 80)"},
             {"sizes", true, false, "N", "voxel edges measured, doubling (default 6)"},
             {"samples", true, false, "N", "surface points per finest voxel face (default 16)"},
             {"help", false, false, "", "show this help"}});
  args.parse(argv);
  if (args.flag("help")) {
    std::cout << "usage: voxgi bench voxel-light [options]\n" << args.help();
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("voxgi bench voxel-light: unexpected argument '" + args.positional().front() +
                     "'");
  }
  const double finest = args.integer("voxel-mm", 80, 1, 100000) * 1e-3;
  const int sizes = args.integer("sizes", 6, 1, 16);
  const int samples = args.integer("samples", 16, 1, 1024);
  const std::string source = args.value_or("scene", "cornell");
  const scene::Scene scene = runtime::load_scene(source);
  const auto sun = std::find_if(scene.lights.begin(), scene.lights.end(), [](const auto& light) {
    return light.type == scene::LightType::Directional;
  });
  if (sun == scene.lights.end()) {
    throw scene::SceneError("voxgi bench voxel-light: scene '" + source +
                            "' has no directional light (it measures the light of one)");
  }
  const glm::vec3 l = -glm::normalize(sun->direction);
  const scene::Bvh bvh = scene::Bvh::build(scene);
  // Refuse what would not fit, before allocating it: the points' memory, and voxel keys.
  constexpr double kMaxPoints = 1e8;
  double surface_area = 0.0;
  for (const scene::BvhTriangle& tri : bvh.triangles()) {
    const double area = 0.5 * glm::length(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
    if (std::isfinite(area)) surface_area += area;
  }
  if (!(surface_area > 0.0)) {
    throw scene::SceneError("voxgi bench voxel-light: scene '" + source + "' has no surfaces");
  }
  const double expected_points = surface_area / (finest * finest) * samples;
  if (!(expected_points <= kMaxPoints)) {
    throw UsageError("voxgi bench voxel-light: --voxel-mm and --samples ask for " +
                     std::to_string(static_cast<long long>(expected_points)) +
                     " surface points on this scene (at most 100000000): use a larger "
                     "--voxel-mm or fewer --samples");
  }
  glm::vec3 low, high;
  scene.bounds(low, high);
  const double reach = std::max(glm::length(glm::dvec3(low)), glm::length(glm::dvec3(high)));
  if (!(reach / finest < kMaxCellsFromOrigin)) {
    throw UsageError(
        "voxgi bench voxel-light: --voxel-mm is too small for where this scene lies "
        "(more than 2^20 voxels from the world origin)");
  }
  std::vector<SurfacePoint> points = sample_surfaces(bvh, finest, samples);
  trace_visibility(bvh, l, float(1e-3 * finest), points);
  std::printf("scene %s, light towards (%.3f, %.3f, %.3f), %zu surface points\n",
              scene.source.c_str(), l.x, l.y, l.z, points.size());
  std::printf(
      "model: the clamped cosine of the voxel's mean normal (normalized) x a visibility. Bias of\n"
      "the mean over voxels for: all = writers' mean normal (the voxelizer's: a plain mean over\n"
      "the voxel's triangles) x the mean visibility of all its surfaces; facing = the same normal\n"
      "x the visibility of its surfaces that face the light; area = an area-weighted mean normal\n"
      "x that visibility; groups = the voxelizer's faces (contracts/voxel_volumes.glsl): the\n"
      "writers in six groups by the signed axis their normal leans along, each lit as a plane\n"
      "with its mean normal and the visibility of its light-facing surfaces, weighted by its\n"
      "share of the writers; by area = the same groups weighted by their area instead. Then per\n"
      "band of the writers' agreement |mean|: the share of voxels and the five biases.\n");
  std::printf("%9s %9s %9s %9s %9s %9s %9s %9s |\n", "edge m", "voxels", "exact", "all", "facing",
              "area", "groups", "by area");
  for (int k = 0; k < sizes; ++k) {
    const double edge = finest * std::ldexp(1.0, k);
    std::unordered_map<uint64_t, VoxelSums> voxels;
    for (const SurfacePoint& q : points) {
      VoxelSums& v = voxels[voxel_key(q.position, edge)];
      const double area = q.area;
      v.area += area;
      v.lit += area * std::max(0.0f, glm::dot(q.normal, l)) * q.visible;
      v.visible += area * q.visible;
      v.area_normal_sum += area * glm::dvec3(q.normal);
      const int g = face_group(q.normal);
      v.group_area[size_t(g)] += area;
      if (glm::dot(q.normal, l) > 0.0f) {
        v.facing_area += area;
        v.facing_visible += area * q.visible;
        v.group_facing_area[size_t(g)] += area;
        v.group_facing_visible[size_t(g)] += area * q.visible;
      }
      if (v.triangles.insert(q.triangle).second) {
        v.writer_normal_sum += glm::dvec3(q.normal);
        v.group_normal_sum[size_t(g)] += glm::dvec3(q.normal);
        v.group_writers[size_t(g)] += 1.0;
      }
    }
    // Bands of the writers' agreement (0.8 and 0.95: where the seventh round's facing test
    // began and was complete).
    const double bands[] = {0.0, 0.5, 0.8, 0.95, 1.01};
    Totals all, band[4];
    for (const auto& [key, v] : voxels) {
      const glm::dvec3 mean = v.writer_normal_sum / double(v.triangles.size());
      const double agreement = glm::length(mean);
      const double exact = v.lit / v.area;
      const double visible = v.visible / v.area;
      const double facing_visible = v.facing_area > 0.0 ? v.facing_visible / v.facing_area : 0.0;
      const double model = injected_cosine(mean, l) * visible;
      const double facing_model = injected_cosine(mean, l) * facing_visible;
      const double area_model = injected_cosine(v.area_normal_sum / v.area, l) * facing_visible;
      double group_model = 0.0, group_area_model = 0.0;
      for (size_t g = 0; g < 6; ++g) {
        if (v.group_writers[g] == 0.0) continue;
        const double group_visible =
            v.group_facing_area[g] > 0.0 ? v.group_facing_visible[g] / v.group_facing_area[g] : 0.0;
        const glm::dvec3 n = glm::normalize(v.group_normal_sum[g]);
        const double lit = std::max(0.0, glm::dot(n, glm::dvec3(l))) * group_visible;
        group_model += v.group_writers[g] / double(v.triangles.size()) * lit;
        group_area_model += v.group_area[g] / v.area * lit;
      }
      for (Totals* t :
           {&all, &band[std::upper_bound(bands + 1, bands + 4, agreement) - bands - 1]}) {
        ++t->voxels;
        t->exact += exact;
        t->model += model;
        t->facing_model += facing_model;
        t->area_model += area_model;
        t->group_model += group_model;
        t->group_area_model += group_area_model;
      }
    }
    auto bias = [](double model, double exact) {
      return exact > 0.0 ? 100.0 * (model / exact - 1.0) : 0.0;
    };
    std::printf("%9.3f %9zu %9.4f %+8.1f%% %+8.1f%% %+8.1f%% %+8.1f%% %+8.1f%% |", edge, all.voxels,
                all.exact / double(all.voxels), bias(all.model, all.exact),
                bias(all.facing_model, all.exact), bias(all.area_model, all.exact),
                bias(all.group_model, all.exact), bias(all.group_area_model, all.exact));
    for (int b = 0; b < 4; ++b) {
      std::printf(" [%.2f,%.2f) %4.1f%% %+6.1f%% %+6.1f%% %+6.1f%% %+6.1f%% %+6.1f%%", bands[b],
                  std::min(bands[b + 1], 1.0), 100.0 * double(band[b].voxels) / double(all.voxels),
                  bias(band[b].model, band[b].exact), bias(band[b].facing_model, band[b].exact),
                  bias(band[b].area_model, band[b].exact), bias(band[b].group_model, band[b].exact),
                  bias(band[b].group_area_model, band[b].exact));
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace voxgi::cli
