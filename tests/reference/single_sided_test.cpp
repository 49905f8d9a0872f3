// path_tracer.single_sided: glTF's single-sided materials as the rasterised passes treat them.
// Camera rays pass through a back face (the G-buffer culls it); any later ray that meets one
// stops with no light; emitters seen from behind send nothing. Fronts, double-sided materials
// and the default (both faces shaded) are untouched.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/scene_builder.hpp"
#include "tests/common/gi_energy.hpp"
#include "tests/common/hard_case_scenes.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class SingleSidedTest : public GpuTest {};

enum class SquareSource { LitByPointLight, Emitting };

// A 1 m square at y = 0 and a 0.2 m receiver 0.5 m above it, facing down at it (double-sided),
// seen by a camera 4 cm under the receiver. The square is single-sided, its front up (towards
// the receiver) or turned over; it reflects a point light above the receiver or emits itself.
scene::Scene square_under_receiver(SquareSource source, bool turned_over) {
  scene::SceneBuilder b("square_under_receiver");
  scene::Material square = source == SquareSource::Emitting
                               ? matte(glm::vec3(0.8f), glm::vec3(2.0f))
                               : matte(glm::vec3(0.8f));
  square.double_sided = false;
  const int square_material = b.add_material(square);
  scene::Material receiver = matte(glm::vec3(1.0f));
  receiver.double_sided = true;
  const int receiver_material = b.add_material(receiver);
  if (turned_over) {
    b.add_quad("square", {-0.5f, 0.0f, -0.5f}, {1, 0, 0}, {0, 0, 1}, square_material);
  } else {
    b.add_quad("square", {-0.5f, 0.0f, -0.5f}, {0, 0, 1}, {1, 0, 0}, square_material);
  }
  b.add_quad("receiver", {-0.1f, 0.5f, -0.1f}, {0.2f, 0, 0}, {0, 0, 0.2f}, receiver_material);
  if (source == SquareSource::LitByPointLight) {
    scene::Light light;
    light.type = scene::LightType::Point;
    light.intensity = 2.0f;
    b.add_light(light, {0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
  }
  b.add_camera("at_receiver", {0.0f, 0.46f, 0.0f}, {0.0f, 0.5f, 0.0f}, 2.0f * std::atan(2.0f),
               {0.0f, 0.0f, 1.0f});
  return b.finish();
}

RenderedImage render_output(const scene::Scene& scene, const std::string& output,
                            std::map<std::string, std::string> overrides, int frames) {
  RenderSetup setup;
  setup.graph = "graphs/reference.json";
  setup.scene_data = scene;
  setup.width = setup.height = 16;
  overrides["path_tracer.pixel_jitter"] = "false";
  overrides["path_tracer.lambert"] = "true";
  setup.overrides = overrides;
  RenderHarness harness(setup);
  harness.render(frames);
  return harness.output(output);
}

// One reflection off the square, counted as the deferred split counts it (an emitter's light at
// the receiver is indirect).
RenderedImage receiver_indirect(SquareSource source, bool turned_over, bool single_sided) {
  return render_output(square_under_receiver(source, turned_over), "indirect",
                       {{"path_tracer.max_depth", "2"},
                        {"path_tracer.deferred_layers", "true"},
                        {"path_tracer.samples_per_frame", "16"},
                        {"path_tracer.single_sided", single_sided ? "true" : "false"}},
                       4);
}

// The back of a single-sided square facing the receiver reflects and emits nothing; its front
// gives what both faces give by default. By light sampling and by BSDF-sampled hits alike (the
// emitting square is reached by both, weighted by MIS).
TEST_F(SingleSidedTest, ABackFaceSendsNoLightAndAFrontLosesNone) {
  for (SquareSource source : {SquareSource::LitByPointLight, SquareSource::Emitting}) {
    const char* label = source == SquareSource::Emitting ? "emitting square" : "lit square";
    const RenderedImage front_default = receiver_indirect(source, false, false);
    const RenderedImage front = receiver_indirect(source, false, true);
    const RenderedImage back_default = receiver_indirect(source, true, false);
    const RenderedImage back = receiver_indirect(source, true, true);
    const double expected = mean_luminance(front_default);
    std::printf(
        "%s: receiver's indirect %.5f; front single-sided %.5f, back %.5f, back "
        "single-sided %.5f\n",
        label, expected, mean_luminance(front), mean_luminance(back_default), mean_luminance(back));
    ASSERT_GT(expected, 0.0) << label;
    // No path meets a back face: the same paths, bit for bit.
    EXPECT_EQ(front.rgba, front_default.rgba) << label;
    // Both faces shaded by default: turned over, the square sends the same light (its
    // vertices' order moves the points that light sampling picks: a sampling difference).
    EXPECT_NEAR(mean_luminance(back_default), expected, 1e-2 * expected) << label;
    for (size_t i = 0; i < back.rgba.size(); i += 4) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back.rgba[i + c], 0.0f) << label << ", pixel " << i / 4;
    }
  }
}

// The quad faces away from the camera, placed plainly or by a mirroring transform; or a pair of
// coincident quads, one facing each way, as meshes exported with both sides often have.
enum class NearQuad { None, Plain, Mirrored, CoincidentPair };

// A camera looking at the back of a single-sided quad sees through it, as the G-buffer culls it:
// the wall behind reads as it does with the quad taken away. Also when a mirroring transform
// places the quad, which reverses its winding in world space but not its front (glTF). By
// default the quad's back is shaded: dark here, since the light lies on its front side. Of a
// coincident pair the camera sees the quad facing it, as the G-buffer does, not the wall.
TEST_F(SingleSidedTest, CameraRaysPassThroughBackFaces) {
  auto scene_with = [](NearQuad near_quad) {
    scene::SceneBuilder b("back_face_before_a_wall");
    scene::Material both_faces = matte(glm::vec3(0.8f));
    both_faces.double_sided = true;
    const int wall = b.add_material(both_faces);
    scene::Material single = matte(glm::vec3(0.8f));
    single.double_sided = false;
    const int near = b.add_material(single);
    // The wall at z = 0 faces +z (the camera); the quad at z = 1 faces -z (away from it).
    b.add_quad("wall", {-1.0f, -1.0f, 0.0f}, {2, 0, 0}, {0, 2, 0}, wall);
    if (near_quad == NearQuad::Plain) {
      b.add_quad("quad", {-0.3f, -0.3f, 1.0f}, {0, 0.6f, 0}, {0.6f, 0, 0}, near);
    } else if (near_quad == NearQuad::CoincidentPair) {
      // The same four vertices, each triangle once in each winding (both orders, so that
      // neither face is the one a traversal happens to meet first everywhere).
      std::vector<scene::Vertex> vertices(4);
      const glm::vec2 corners[4] = {{-0.3f, -0.3f}, {0.3f, -0.3f}, {0.3f, 0.3f}, {-0.3f, 0.3f}};
      for (int k = 0; k < 4; ++k) {
        vertices[k].position = glm::vec3(corners[k], 1.0f);
        vertices[k].normal = glm::vec3(0.0f);  // left to the builder: culling goes by winding
      }
      b.add_mesh("coincident_pair", vertices, {0, 1, 2, 0, 2, 1, 0, 3, 2, 0, 2, 3}, near);
    } else if (near_quad == NearQuad::Mirrored) {
      // Counter-clockwise about -z before the mirror x -> -x, clockwise after it.
      std::vector<scene::Vertex> vertices(4);
      const glm::vec2 corners[4] = {{-0.3f, -0.3f}, {-0.3f, 0.3f}, {0.3f, 0.3f}, {0.3f, -0.3f}};
      for (int k = 0; k < 4; ++k) {
        vertices[k].position = glm::vec3(corners[k], 1.0f);
        vertices[k].normal = glm::vec3(0.0f, 0.0f, -1.0f);
      }
      b.add_mesh("mirrored_quad", vertices, {0, 1, 2, 0, 2, 3}, near,
                 glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)));
    }
    scene::Light light;
    light.type = scene::LightType::Point;
    light.intensity = 1.0f;
    b.add_light(light, {0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, -1.0f});
    b.add_camera("front", {0.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 0.9f);
    return b.finish();
  };
  const std::map<std::string, std::string> direct_only = {{"path_tracer.max_depth", "1"}};
  auto with_single_sided = direct_only;
  with_single_sided["path_tracer.single_sided"] = "true";
  const RenderedImage open = render_output(scene_with(NearQuad::None), "direct", direct_only, 1);
  for (NearQuad quad : {NearQuad::Plain, NearQuad::Mirrored, NearQuad::CoincidentPair}) {
    const char* label = quad == NearQuad::Mirrored         ? "mirrored quad"
                        : quad == NearQuad::CoincidentPair ? "coincident pair"
                                                           : "quad";
    const RenderedImage through = render_output(scene_with(quad), "direct", with_single_sided, 1);
    const RenderedImage shaded = render_output(scene_with(quad), "direct", direct_only, 1);
    // The pair's quad facing the camera is unlit, as the back that the default shades.
    const RenderedImage& expected = quad == NearQuad::CoincidentPair ? shaded : open;
    size_t covered = 0;
    for (size_t i = 0; i < open.rgba.size(); i += 4) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(through.rgba[i + c], expected.rgba[i + c], 1e-4f * expected.rgba[i + c] + 1e-7f)
            << label << ", pixel " << i / 4;
      }
      if (shaded.rgba[i + 1] == 0.0f && open.rgba[i + 1] > 0.0f) ++covered;
    }
    std::printf("%s: its back covers %zu of %zu pixels when shaded\n", label, covered,
                open.rgba.size() / 4);
    EXPECT_GT(covered, open.rgba.size() / 4 / 20) << label << ": the default shades its back";
  }
}

}  // namespace
}  // namespace voxgi::test
