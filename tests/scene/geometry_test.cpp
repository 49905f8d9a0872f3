#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/scene/geometry.hpp"

namespace voxgi::scene {
namespace {

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

void expect_orthonormal_frames(const Primitive& p) {
  for (const Vertex& v : p.vertices) {
    ASSERT_TRUE(finite(glm::vec4(v.normal, 0.0f)));
    ASSERT_TRUE(finite(v.tangent));
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0f, 1e-5f);
    EXPECT_EQ(std::abs(v.tangent.w), 1.0f);
  }
}

Primitive quad(glm::vec2 uv_scale) {
  Primitive p;
  const glm::vec3 positions[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int i = 0; i < 4; ++i) {
    Vertex v;
    v.position = positions[i];
    v.normal = {0, 0, 1};
    v.uv = glm::vec2(positions[i]) * uv_scale;
    p.vertices.push_back(v);
  }
  p.indices = {0, 1, 2, 0, 2, 3};
  return p;
}

TEST(Tangents, FollowTheUDirectionWithHandedness) {
  Primitive p = quad({1, 1});
  generate_tangents(p);
  expect_orthonormal_frames(p);
  for (const Vertex& v : p.vertices) {
    EXPECT_NEAR(v.tangent.x, 1.0f, 1e-5f);
    EXPECT_EQ(v.tangent.w, 1.0f);  // bitangent = cross(n, t) = +Y = direction of +v
  }
  Primitive mirrored = quad({1, -1});  // v runs down: left-handed UV frame
  generate_tangents(mirrored);
  expect_orthonormal_frames(mirrored);
  for (const Vertex& v : mirrored.vertices) EXPECT_EQ(v.tangent.w, -1.0f);
  Primitive flipped_u = quad({-1, 1});
  generate_tangents(flipped_u);
  for (const Vertex& v : flipped_u.vertices) {
    EXPECT_NEAR(v.tangent.x, -1.0f, 1e-5f);
    EXPECT_EQ(v.tangent.w, -1.0f);
  }
}

TEST(Tangents, DegenerateInputStaysFinite) {
  Primitive p;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Zero-area triangle, repeated vertices, collinear points, zero and NaN normals, equal UVs.
  const glm::vec3 positions[7] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 0, 0},
                                  {2, 0, 0}, {3, 0, 0}, {0, 1, 0}};
  for (int i = 0; i < 7; ++i) {
    Vertex v;
    v.position = positions[i];
    v.normal = i % 2 ? glm::vec3(0.0f) : glm::vec3(nan, 0, 0);
    v.uv = glm::vec2(0.5f);
    p.vertices.push_back(v);
  }
  p.indices = {0, 1, 2, 3, 4, 5, 0, 3, 6};
  repair_normals(p);
  generate_tangents(p);
  expect_orthonormal_frames(p);
  // The vertices of the one real triangle get its face normal (+Z).
  EXPECT_NEAR(p.vertices[6].normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(p.vertices[3].normal.z, 1.0f, 1e-6f);
}

TEST(Tangents, RepairKeepsValidOnesAndRegeneratesBroken) {
  Primitive p = quad({1, 1});
  for (Vertex& v : p.vertices) v.tangent = glm::vec4(0, 1, 0.1f, -3.0f);
  repair_tangents(p);
  expect_orthonormal_frames(p);
  for (const Vertex& v : p.vertices) {
    EXPECT_NEAR(v.tangent.y, 1.0f, 1e-5f);
    EXPECT_EQ(v.tangent.w, -1.0f);
  }
  p.vertices[2].tangent = glm::vec4(0, 0, 5, 1);  // parallel to the normal
  repair_tangents(p);
  expect_orthonormal_frames(p);
  EXPECT_NEAR(p.vertices[2].tangent.x, 1.0f, 1e-5f);  // regenerated from the UVs
}

TEST(Normals, FlatNormalsSplitVertices) {
  Primitive p;
  p.vertices.resize(4);
  p.vertices[0].position = {0, 0, 0};
  p.vertices[1].position = {1, 0, 0};
  p.vertices[2].position = {0, 1, 0};
  p.vertices[3].position = {0, 0, 1};
  p.indices = {0, 1, 2, 0, 3, 1, 0, 0, 0};
  make_flat_normals(p);
  ASSERT_EQ(p.vertices.size(), 9u);
  EXPECT_EQ(p.vertices[0].normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(p.vertices[3].normal, glm::vec3(0, 1, 0));
  EXPECT_EQ(p.vertices[6].normal, glm::vec3(0, 1, 0));  // degenerate: fallback
}

TEST(Geometry, FlipWindingSwapsTwoIndices) {
  EXPECT_EQ(flip_winding({0, 1, 2, 3, 4, 5}), (std::vector<uint32_t>{0, 2, 1, 3, 5, 4}));
}

TEST(Geometry, AnyPerpendicularIsUnitAndOrthogonal) {
  for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1),
                            glm::normalize(glm::vec3(1, 1, 1))}) {
    const glm::vec3 t = any_perpendicular(n);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace voxgi::scene
