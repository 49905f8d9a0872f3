// The LPV family's spherical harmonics and propagation constants on the device
// (shaders/lpv/sh.glsl through tests/lpv/shaders/sh_probe.comp), checked against closed forms
// and an independent quadrature, and the reflective shadow maps' texel solid angles
// (passes/lpv/rsm_views.cpp).

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "passes/lpv/rsm_views.hpp"
#include "tests/gpu/buffer_probe.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

// Solid angle and vector solid angle (the integral of w) of the unit square [-0.5, 0.5]^2 on
// the plane at distance h along d, or of a side face, seen from the origin, by the midpoint
// rule on n x n points: an independent check of the closed forms in sh.glsl.
struct Region {
  double solid_angle = 0.0;
  glm::dvec3 vector{0.0};
};
Region face_region(bool far, int n) {
  Region r;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n - 0.5, v = (j + 0.5) / n - 0.5;
      // d = +z; the far face at z = 1.5, the side face at x = 0.5 spanning z in [0.5, 1.5].
      const glm::dvec3 p = far ? glm::dvec3(u, v, 1.5) : glm::dvec3(0.5, u, v + 1.0);
      const double cos_area = far ? 1.5 : 0.5;  // the face's distance along its normal
      const double r2 = glm::dot(p, p);
      const double d_omega = cos_area / (r2 * std::sqrt(r2)) / (double(n) * n);
      r.solid_angle += d_omega;
      r.vector += glm::normalize(p) * d_omega;
    }
  }
  return r;
}

class LpvShTest : public GpuTest {
 protected:
  std::vector<glm::vec4> run(const std::vector<glm::vec4>& directions) {
    gpu::ShaderCompiler compiler({fs::path(VOXGI_SOURCE_DIR) / "tests" / "lpv" / "shaders",
                                  fs::path(VOXGI_SOURCE_DIR) / "shaders"},
                                 "");
    const auto count = static_cast<uint32_t>(directions.size());
    gpu::Buffer input(context(), count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      gpu::MemoryUsage::GpuOnly, "test.directions");
    gpu::Buffer output(context(), count * 5 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       gpu::MemoryUsage::GpuOnly, "test.sh_results");
    input.upload_vector(directions);
    run_buffer_probe(compiler, "sh_probe.comp", input, output, count);
    return output.download_vector<glm::vec4>(count * 5);
  }
};

const std::vector<glm::vec4> kDirections = {
    {0, 0, 1, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, -1, 0}, {0.48f, -0.6f, 0.64f, 0}};

// Seed 002's sheet: the clamped cosine along z is (0.886227, 0, 1.023327, 0) in the order
// (Y00, Y1-1, Y10, Y11); its integral is pi; a uniform radiance L gives irradiance pi L.
TEST_F(LpvShTest, ClampedCosineAndUniformRadianceHaveTheirClosedForms) {
  const std::vector<glm::vec4> r = run(kDirections);
  const glm::vec4 along_z = r[0];
  EXPECT_NEAR(along_z.x, 0.886227f, 1e-5f);
  EXPECT_NEAR(along_z.y, 0.0f, 1e-6f);
  EXPECT_NEAR(along_z.z, 1.023327f, 1e-5f);
  EXPECT_NEAR(along_z.w, 0.0f, 1e-6f);
  for (size_t i = 0; i < kDirections.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(r[5 * i + 2].z, kPi, 1e-5) << "uniform radiance 1: irradiance pi";
    EXPECT_NEAR(r[5 * i + 2].w, kPi, 1e-5) << "the clamped cosine integrates to pi";
    const glm::vec3 n = glm::normalize(glm::vec3(kDirections[i]));
    // The band-1 coefficients are (y, z, x) of the axis, with no sign flip.
    EXPECT_NEAR(r[5 * i].y, 1.023327f * n.y, 1e-5f);
    EXPECT_NEAR(r[5 * i].z, 1.023327f * n.z, 1e-5f);
    EXPECT_NEAR(r[5 * i].w, 1.023327f * n.x, 1e-5f);
  }
}

// The sign check of the sheet: a projected direction evaluates to (1 + 3) / (4 pi) at that
// direction, (1 - 3) / (4 pi) opposite and less anywhere else, so x and y are not mirrored.
TEST_F(LpvShTest, AProjectedDirectionIsLargestWhereItPoints) {
  const std::vector<glm::vec4> r = run(kDirections);
  for (size_t i = 0; i < kDirections.size(); ++i) {
    SCOPED_TRACE(i);
    const float at = r[5 * i + 2].x, opposite = r[5 * i + 2].y;
    EXPECT_NEAR(at, (1.0 + 3.0) / (4.0 * kPi), 1e-5);
    EXPECT_NEAR(opposite, (1.0 - 3.0) / (4.0 * kPi), 1e-5);
    // Against every other input direction.
    for (size_t j = 0; j < kDirections.size(); ++j) {
      if (j == i) continue;
      const glm::vec3 m = glm::normalize(glm::vec3(kDirections[j]));
      const glm::vec4 b = r[5 * i + 1];
      const float value = b.x * 0.282095f + 0.488603f * (b.y * m.y + b.z * m.z + b.w * m.x);
      EXPECT_LT(value, at - 1e-4f);
    }
  }
}

// The propagation's face constants against a quadrature of the faces, and the 6 x 5 faces
// around a cell covering the sphere once: solid angles summing to 4 pi, so that a Lambertian
// lobe of flux 1 sends exactly 1 (seed 002's sheet: 0.4007 and 0.4234 sr).
TEST_F(LpvShTest, FaceSolidAnglesAreExactAndPartitionTheSphere) {
  const std::vector<glm::vec4> r = run(kDirections);
  const glm::vec4 c = r[3];
  const float side_d = r[4].x;
  const Region far = face_region(true, 1500);
  const Region side = face_region(false, 1500);
  EXPECT_NEAR(c.x, far.solid_angle, 1e-6);
  EXPECT_NEAR(c.y, side.solid_angle, 1e-6);
  EXPECT_NEAR(c.z, far.vector.z, 1e-6);
  EXPECT_NEAR(c.w, side.vector.x, 1e-6);
  EXPECT_NEAR(side_d, side.vector.z, 1e-6);
  EXPECT_NEAR(c.x, 0.4007, 1e-4);
  EXPECT_NEAR(c.y, 0.4234, 1e-4);
  EXPECT_NEAR(6.0 * (c.x + 4.0 * c.y), 4.0 * kPi, 1e-5);
  for (size_t i = 0; i < kDirections.size(); ++i) {
    EXPECT_NEAR(r[5 * i + 4].y, 1.0, 1e-5) << "a lobe of flux 1 sends " << r[5 * i + 4].y;
  }
}

// Reflective shadow maps: the texels of six 90-degree faces cover the sphere (4 pi) at any
// resolution, and a spot face's texels its pyramid; the texels of one face are symmetric.
TEST(LpvRsmTest, TexelSolidAnglesCoverTheSphere) {
  for (uint32_t n : {1u, 7u, 64u, 256u}) {
    double face = 0.0;
    for (uint32_t y = 0; y < n; ++y) {
      for (uint32_t x = 0; x < n; ++x) face += passes::lpv::rsm_texel_solid_angle(x, y, n, 1.0);
    }
    EXPECT_NEAR(6.0 * face, 4.0 * kPi, 1e-9) << n << "^2 texels";
    EXPECT_NEAR(passes::lpv::rsm_texel_solid_angle(0, 0, n, 1.0),
                passes::lpv::rsm_texel_solid_angle(n - 1, n - 1, n, 1.0), 1e-12);
  }
  // A pyramid of half-angle a: 4 asin(sin^2 a).
  const double a = 0.5;
  double pyramid = 0.0;
  for (uint32_t y = 0; y < 32; ++y) {
    for (uint32_t x = 0; x < 32; ++x) {
      pyramid += passes::lpv::rsm_texel_solid_angle(x, y, 32, std::tan(a));
    }
  }
  EXPECT_NEAR(pyramid, 4.0 * std::asin(std::sin(a) * std::sin(a)), 1e-9);
}

}  // namespace
}  // namespace voxgi::test
