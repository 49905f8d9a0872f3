// The CPU BVH: structure (every triangle in one leaf, nested bounds, bounded depth), ray
// queries equal to testing every triangle, refit, degenerate input, far offsets, empty scenes.

#include "engine/scene/bvh.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>
#include <set>
#include <utility>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"

namespace voxgi::scene {
namespace {

// `meshes` random triangle soups of `triangles` triangles each, placed by random transforms
// (rotation, non-uniform scale, some mirrored) inside a 10 m cube.
Scene random_scene(uint32_t seed, int meshes, int triangles) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  SceneBuilder b("random");
  Material m;
  m.base_color = glm::vec4(0.5f);
  const int material = b.add_material(m);
  for (int k = 0; k < meshes; ++k) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    for (int t = 0; t < triangles; ++t) {
      const glm::vec3 centre(unit(rng), unit(rng), unit(rng));
      const float size = 0.02f + 0.3f * (unit(rng) * 0.5f + 0.5f);
      for (int c = 0; c < 3; ++c) {
        Vertex v;
        v.position = centre + size * glm::vec3(unit(rng), unit(rng), unit(rng));
        indices.push_back(static_cast<uint32_t>(vertices.size()));
        vertices.push_back(v);
      }
    }
    glm::mat4 transform =
        glm::translate(glm::mat4(1.0f), 4.0f * glm::vec3(unit(rng), unit(rng), unit(rng)));
    transform = glm::rotate(transform, 3.0f * unit(rng),
                            glm::normalize(glm::vec3(unit(rng), unit(rng), 1.0f)));
    glm::vec3 scale(1.0f + 0.5f * unit(rng), 1.0f + 0.5f * unit(rng), 1.0f + 0.5f * unit(rng));
    if (k % 3 == 2) scale.x = -scale.x;  // mirrored instance
    transform = glm::scale(transform, scale);
    b.add_mesh("soup" + std::to_string(k), std::move(vertices), std::move(indices), material,
               transform);
  }
  return b.finish();
}

struct Ray {
  glm::dvec3 origin;
  glm::vec3 direction;
};

// Rays from random points of a cube around the scene towards random points inside it, plus
// axis-aligned ones (zero direction components).
std::vector<Ray> random_rays(uint32_t seed, int count, const glm::dvec3& centre, double extent) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 from = centre + extent * 1.5 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    const glm::dvec3 to = centre + extent * 0.5 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    glm::vec3 d(to - from);
    if (i % 10 == 0) d = glm::vec3(0.0f);
    if (i % 10 == 0) d[i % 3] = unit(rng) < 0.0 ? -1.0f : 1.0f;
    rays.push_back({from, d});
  }
  return rays;
}

void expect_same_hits(const Bvh& bvh, const std::vector<Ray>& rays, int* hits = nullptr) {
  int hit_count = 0;
  for (const Ray& ray : rays) {
    const auto fast = bvh.intersect(ray.origin, ray.direction, 0.0f, 1e30f);
    const auto slow = bvh.intersect_brute_force(ray.origin, ray.direction, 0.0f, 1e30f);
    ASSERT_EQ(fast.has_value(), slow.has_value());
    if (!fast) continue;
    ++hit_count;
    EXPECT_EQ(fast->t, slow->t);
    // Equal distances may come from different triangles (shared edges); otherwise the same.
    if (fast->triangle != slow->triangle) {
      EXPECT_EQ(fast->t, slow->t);
    }
  }
  if (hits) *hits = hit_count;
}

void expect_valid_structure(const Bvh& bvh) {
  const auto& nodes = bvh.nodes();
  const auto& tris = bvh.triangles();
  ASSERT_FALSE(nodes.empty());
  std::vector<int> seen(tris.size(), 0);
  std::vector<int> parents(nodes.size(), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const BvhNode& n = nodes[i];
    if (n.leaf()) {
      ASSERT_LE(size_t(n.first) + n.count, tris.size());
      for (uint32_t t = n.first; t < n.first + n.count; ++t) {
        ++seen[t];
        const BvhTriangle& tri = tris[t];
        for (const glm::vec3& v : {tri.v0, tri.v1, tri.v2}) {
          EXPECT_TRUE(glm::all(glm::lessThanEqual(n.bounds_min, v)) &&
                      glm::all(glm::lessThanEqual(v, n.bounds_max)))
              << "triangle " << t << " outside leaf " << i;
        }
      }
      continue;
    }
    ASSERT_GT(n.first, i) << "children come after their parent";
    ASSERT_LT(size_t(n.first) + 1, nodes.size());
    for (uint32_t c = n.first; c <= n.first + 1; ++c) {
      ++parents[c];
      EXPECT_TRUE(glm::all(glm::lessThanEqual(n.bounds_min, nodes[c].bounds_min)) &&
                  glm::all(glm::lessThanEqual(nodes[c].bounds_max, n.bounds_max)))
          << "child " << c << " not inside parent " << i;
    }
  }
  for (size_t t = 0; t < tris.size(); ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
  EXPECT_EQ(parents[0], 0);
  for (size_t i = 1; i < nodes.size(); ++i) EXPECT_EQ(parents[i], 1) << "node " << i;

  // Every (instance, triangle) of the scene appears once.
  std::set<std::pair<uint32_t, uint32_t>> ids;
  for (const BvhTriangle& t : tris) ids.insert({t.instance, t.index});
  EXPECT_EQ(ids.size(), tris.size());

  const BvhStats& s = bvh.stats();
  EXPECT_EQ(s.triangles, tris.size());
  EXPECT_EQ(s.nodes, nodes.size());
  EXPECT_EQ(s.leaves, (nodes.size() + 1) / 2);
  EXPECT_LE(s.max_depth, kBvhMaxDepth);
  EXPECT_GT(s.sah_cost, 0.0);
  EXPECT_GE(s.build_ms, 0.0);
}

size_t scene_triangles(const Scene& scene) {
  size_t n = 0;
  for (const Instance& i : scene.instances()) {
    n += scene.meshes[size_t(i.mesh)].primitives[size_t(i.primitive)].indices.size() / 3;
  }
  return n;
}

TEST(Bvh, RandomMeshesStructureAndRaysMatchBruteForce) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Scene scene = random_scene(seed, 6, 300);
    const Bvh bvh = Bvh::build(scene);
    EXPECT_EQ(bvh.triangles().size(), scene_triangles(scene));
    expect_valid_structure(bvh);
    int hits = 0;
    expect_same_hits(bvh, random_rays(seed + 100, 2000, glm::dvec3(0.0), 6.0), &hits);
    EXPECT_GT(hits, 200) << "the rays must actually exercise hits";
    // A good SAH tree costs far less than testing every triangle.
    EXPECT_LT(bvh.stats().sah_cost, 0.05 * double(bvh.triangles().size()));
  }
}

TEST(Bvh, BuiltinCornellMatchesBruteForce) {
  const Scene scene = make_builtin_scene("cornell");
  const Bvh bvh = Bvh::build(scene);
  expect_valid_structure(bvh);
  int hits = 0;
  expect_same_hits(bvh, random_rays(7, 3000, glm::dvec3(0.278, 0.27, 0.28), 0.3), &hits);
  EXPECT_GT(hits, 1000);
  // A ray from the camera straight ahead hits the back wall at z = 0.5592.
  const auto hit = bvh.intersect(glm::dvec3(0.05, 0.5, -0.8), glm::vec3(0, 0, 1), 0.0f, 100.0f);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.8 + 0.5592, 1e-5);
}

TEST(Bvh, RefitAfterMovingAnInstanceEqualsRebuild) {
  Scene scene = random_scene(11, 5, 200);
  Bvh refitted = Bvh::build(scene);
  // Move two nodes far (through each other) and rotate one.
  scene.nodes[0].translation += glm::vec3(3.0f, -1.0f, 0.5f);
  scene.nodes[3].translation -= glm::vec3(2.0f, 0.0f, 4.0f);
  scene.nodes[3].rotation = glm::angleAxis(0.7f, glm::vec3(0, 1, 0)) * scene.nodes[3].rotation;
  scene.update_transforms();
  refitted.refit(scene);
  const Bvh rebuilt = Bvh::build(scene);
  EXPECT_EQ(refitted.nodes().size(), Bvh::build(random_scene(11, 5, 200)).nodes().size())
      << "refit keeps the topology";
  expect_valid_structure(refitted);
  EXPECT_GE(refitted.stats().refit_ms, 0.0);
  for (const Ray& ray : random_rays(12, 2000, glm::dvec3(0.0), 7.0)) {
    const auto a = refitted.intersect(ray.origin, ray.direction, 0.0f, 1e30f);
    const auto b = rebuilt.intersect(ray.origin, ray.direction, 0.0f, 1e30f);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    EXPECT_NEAR(a->t, b->t, 1e-4f * std::max(1.0f, b->t));
    const BvhTriangle& ta = refitted.triangles()[a->triangle];
    const BvhTriangle& tb = rebuilt.triangles()[b->triangle];
    if (std::abs(a->t - b->t) > 1e-4f) {
      EXPECT_EQ(std::make_pair(ta.instance, ta.index), std::make_pair(tb.instance, tb.index));
    }
  }
}

TEST(Bvh, RefitRejectsADifferentScene) {
  Bvh bvh = Bvh::build(random_scene(5, 2, 10));
  EXPECT_THROW(bvh.refit(random_scene(5, 3, 10)), SceneError);
}

TEST(Bvh, DegenerateTrianglesNeverHitAndDoNotBreakTheTree) {
  SceneBuilder b("degenerate");
  const int material = b.add_material(Material{});
  std::vector<Vertex> vertices(12);
  const glm::vec3 p[12] = {{0, 0, 0},     {1, 0, 0},     {0, 1, 0},       // a real triangle
                           {2, 2, 2},     {2, 2, 2},     {2, 2, 2},       // one point
                           {0, 0, 1},     {1, 1, 1},     {2, 2, 1},       // collinear
                           {0.5, 0.2, 0}, {0.5, 0.2, 0}, {0.7, 0.1, 0}};  // repeated vertex
  for (int i = 0; i < 12; ++i) vertices[size_t(i)].position = p[i];
  std::vector<uint32_t> indices(12);
  for (uint32_t i = 0; i < 12; ++i) indices[i] = i;
  // Many copies of the point triangle: all centroids coincide, no SAH plane separates them.
  for (int k = 0; k < 50; ++k) indices.insert(indices.end(), {3, 4, 5});
  b.add_mesh("mixed", vertices, indices, material);
  const Scene scene = b.finish();
  const Bvh bvh = Bvh::build(scene);
  expect_valid_structure(bvh);
  EXPECT_EQ(bvh.triangles().size(), 54u);
  int hits = 0;
  expect_same_hits(bvh, random_rays(3, 2000, glm::dvec3(1.0), 2.0), &hits);
  for (const Ray& ray : random_rays(4, 2000, glm::dvec3(1.0), 2.0)) {
    const auto hit = bvh.intersect(ray.origin, ray.direction, 0.0f, 1e30f);
    if (!hit) continue;
    const BvhTriangle& t = bvh.triangles()[hit->triangle];
    EXPECT_GT(glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)), 0.0f)
        << "a degenerate triangle was hit";
  }
  // Straight down onto the real triangle.
  const auto hit = bvh.intersect(glm::dvec3(0.2, 0.2, 5.0), glm::vec3(0, 0, -1), 0.0f, 100.0f);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.0f, 1e-5f);
}

// Every instance of `scene` baked into world-space vertices under a node translated by
// `offset` (whole metres, exact in float), so the copy is the same geometry moved exactly.
Scene baked_copy(const Scene& scene, const glm::vec3& offset) {
  SceneBuilder b("baked");
  const int material = b.add_material(Material{});
  int k = 0;
  for (const Instance& instance : scene.instances()) {
    const Primitive& p = scene.meshes[size_t(instance.mesh)].primitives[size_t(instance.primitive)];
    std::vector<Vertex> vertices = p.vertices;
    for (Vertex& v : vertices) v.position = glm::vec3(instance.world * glm::vec4(v.position, 1.0f));
    std::string name = "m";
    name += std::to_string(k++);  // appended, not "m" + ...: avoids a GCC 12 -Wrestrict false alarm
    b.add_mesh(name, vertices, p.indices, material, glm::translate(glm::mat4(1.0f), offset));
  }
  return b.finish();
}

TEST(Bvh, SceneFarFromTheOriginKeepsPrecision) {
  // The Cornell box moved by 1e5 m: float world coordinates there are 8 mm apart, but the
  // BVH works relative to its origin (in double), so hits agree with the box at the origin.
  const glm::vec3 offset(1e5f, -1e5f, 1e5f);
  const Scene near_scene = baked_copy(make_builtin_scene("cornell"), glm::vec3(0.0f));
  const Scene far_scene = baked_copy(make_builtin_scene("cornell"), offset);
  const Bvh near_bvh = Bvh::build(near_scene);
  const Bvh far_bvh = Bvh::build(far_scene);
  expect_valid_structure(far_bvh);
  const auto rays = random_rays(21, 2000, glm::dvec3(0.278, 0.27, 0.28), 0.3);
  std::vector<Ray> shifted = rays;
  for (Ray& r : shifted) r.origin += glm::dvec3(offset);
  int compared = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto a = near_bvh.intersect(rays[i].origin, rays[i].direction, 0.0f, 1e30f);
    const auto b = far_bvh.intersect(shifted[i].origin, shifted[i].direction, 0.0f, 1e30f);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    ++compared;
    const double length = glm::length(rays[i].direction);
    EXPECT_NEAR(a->t * length, b->t * length, 1e-5);
  }
  EXPECT_GT(compared, 500);
  expect_same_hits(far_bvh, shifted);
}

TEST(Bvh, EmptySceneHasNoNodesAndNoHits) {
  const Scene scene = make_builtin_scene("empty");
  Bvh bvh = Bvh::build(scene);
  EXPECT_TRUE(bvh.empty());
  EXPECT_TRUE(bvh.nodes().empty());
  EXPECT_EQ(bvh.stats().triangles, 0u);
  EXPECT_EQ(bvh.stats().sah_cost, 0.0);
  EXPECT_FALSE(bvh.intersect(glm::dvec3(0.0), glm::vec3(0, 0, 1), 0.0f, 1e30f));
  bvh.refit(scene);
  EXPECT_TRUE(bvh.empty());
}

}  // namespace
}  // namespace voxgi::scene
