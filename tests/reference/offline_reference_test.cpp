// The reference path tracer against the independent offline references of
// ../shared/references (Cycles, 2048 spp): full, direct and indirect layers within the
// agreement the references' README lists, widened by this render's own noise as measured by
// the tracer's variance output (so a few hundred samples suffice in CI).
//
// The CI test renders at half the references' resolution and compares with the references
// box-downsampled 2 × 2 (with a 1-pixel box filter both are the same image). The DISABLED_
// tests render at full resolution until convergence and print the time it took; run them with
// --gtest_also_run_disabled_tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "engine/image/image.hpp"
#include "engine/image/metrics.hpp"
#include "engine/scene/gltf_loader.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/reference/image_statistics.hpp"

namespace voxgi::test {
namespace {

struct OfflineReference {
  const char* name;   // NAME of NAME-passes.exr
  const char* scene;  // under shared/scenes
  const char* camera;
  uint32_t width, height;  // of the reference
  bool lambert;
  double rel_mse;    // agreement of a correct glTF path tracer (references/README.md)
  double luminance;  // relative mean-luminance agreement
};

const OfflineReference kCornell{"cornell-box-camera-256x256",
                                "cornell-box/cornell-box.gltf",
                                "camera",
                                256,
                                256,
                                false,
                                0.01,
                                0.03};
const OfflineReference kCornellLambert{"cornell-box-camera-256x256-lambert",
                                       "cornell-box/cornell-box.gltf",
                                       "camera",
                                       256,
                                       256,
                                       true,
                                       0.005,
                                       0.01};
const OfflineReference kSponzaAtrium{"sponza-dabrovic-atrium-256x192",
                                     "sponza-dabrovic/sponza-dabrovic.glb",
                                     "atrium",
                                     256,
                                     192,
                                     false,
                                     0.03,
                                     0.05};
const OfflineReference kSponzaGallery{"sponza-dabrovic-gallery-256x192",
                                      "sponza-dabrovic/sponza-dabrovic.glb",
                                      "gallery",
                                      256,
                                      192,
                                      false,
                                      0.03,
                                      0.05};
const OfflineReference kConference{
    "conference-room-256x192", "conference/conference.glb", "room", 256, 192, false, 0.03, 0.05};
const OfflineReference kSibenik{
    "sibenik-nave-256x192", "sibenik/sibenik.glb", "nave", 256, 192, false, 0.05, 1.0};

std::filesystem::path shared_dir() {
  return std::filesystem::path(VOXGI_SHARED_DIR);
}

struct LayerResult {
  image::ImageMetrics metrics;
  double noise_rel_mse = 0.0;
  double luminance_standard_error = 0.0;  // relative to the reference's mean luminance
};

class OfflineReferenceTest : public GpuTest {
 protected:
  // Renders `ref` at 1/downsample of its size with `spp` samples per pixel and compares the
  // three layers; fails on any disagreement beyond agreement + noise.
  void check(const OfflineReference& ref, uint32_t downsample, uint32_t spp,
             uint32_t samples_per_frame) {
    // Measurements may ask for other sample counts (e.g. VOXGI_REFERENCE_SPP=16).
    if (const char* env = std::getenv("VOXGI_REFERENCE_SPP")) {
      spp = static_cast<uint32_t>(std::max(1, std::atoi(env)));
      samples_per_frame = std::min(samples_per_frame, spp);
      spp = spp / samples_per_frame * samples_per_frame;
    }
    const std::filesystem::path scene_path = shared_dir() / "scenes" / ref.scene;
    const std::filesystem::path passes =
        shared_dir() / "references" / (std::string(ref.name) + "-passes.exr");
    if (!std::filesystem::exists(scene_path) || !std::filesystem::exists(passes)) {
      GTEST_SKIP() << "shared scenes or references not found (" << scene_path << ", " << passes
                   << "): VOXGI_SHARED_DIR must hold scenes/ and references/";
    }
    scene::Scene scene = scene::load_gltf(scene_path);
    for (scene::Camera& camera : scene.cameras) camera.aspect = 0.0f;  // as the references
    RenderSetup setup;
    setup.scene_data = std::move(scene);
    setup.camera = ref.camera;
    setup.graph = "graphs/reference.json";
    setup.width = ref.width / downsample;
    setup.height = ref.height / downsample;
    setup.overrides = {{"path_tracer.samples_per_frame", std::to_string(samples_per_frame)},
                       {"path_tracer.lambert", ref.lambert ? "true" : "false"}};
    RenderHarness harness(setup);
    const auto start = std::chrono::steady_clock::now();
    harness.render(static_cast<int>(spp / samples_per_frame));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const RenderedImage variance = harness.output("variance");
    const char* layers[3][2] = {
        {"linear", "Combined"}, {"direct", "Direct"}, {"indirect", "Indirect"}};
    std::cout << ref.name << " at " << setup.width << "x" << setup.height << ", "
              << variance.at(0, 0).w << " spp: " << seconds << " s on this device\n";
    for (const auto& layer : layers) {
      const RenderedImage rendered = harness.output(layer[0]);
      expect_finite_non_negative(rendered, std::string(ref.name) + " " + layer[0]);
      const image::ImageRGBA32F reference =
          box_downsample(image::read_exr(passes, layer[1]), downsample);
      const image::ImageMetrics m = image::compare_images(to_image(rendered), reference);
      const double noise = image::noise_rel_mse(reference, to_image(variance));
      const double lum_se =
          mean_luminance_standard_error(variance) / std::max(m.mean_luminance_reference, 1e-9);
      // Twice the expected noise contribution: relMSE of a noisy image scatters around its
      // expectation by far less than that at these pixel counts.
      const double rel_mse_limit = ref.rel_mse + 2.0 * noise;
      const double luminance_limit = ref.luminance + 4.0 * lum_se;
      std::cout << "  " << layer[0] << ": relMSE " << m.rel_mse << " (limit " << rel_mse_limit
                << ", noise part " << noise << "), mean luminance " << m.mean_luminance << " vs "
                << m.mean_luminance_reference << " (bias " << m.luminance_bias * 100.0
                << " %, limit " << luminance_limit * 100.0 << " %), SSIM " << m.ssim_luminance
                << "\n";
      EXPECT_EQ(m.non_finite_pixels, 0u);
      // Without the Lambert override the references use Cycles' Principled BSDF, which
      // reflects more than the glTF BRDF (Disney diffuse retro-reflection and no (1 - F) on the
      // diffuse lobe: for the Cornell walls +8% at normal incidence, +11% averaged over view
      // angles). That compounds over bounces (Cornell indirect +46%); the same tracer with that
      // model meets these references on every layer (docs/reference.md). So only the
      // single-reflection layer can be held to the README's agreement, widened by the 2% model
      // difference it states. Lambert references are held to their agreement on every layer.
      if (!ref.lambert && std::string(layer[0]) != "direct") continue;
      const double model = ref.lambert ? 0.0 : 0.02;
      EXPECT_LE(m.rel_mse, rel_mse_limit) << ref.name << " " << layer[0];
      EXPECT_LE(std::abs(m.luminance_bias), luminance_limit + model) << ref.name << " " << layer[0];
    }
  }
};

TEST_F(OfflineReferenceTest, CornellBoxLambert) {
  check(kCornellLambert, 4, 256, 64);
}
TEST_F(OfflineReferenceTest, CornellBox) {
  check(kCornell, 4, 256, 64);
}

// Full resolution until converged: minutes on lavapipe.
TEST_F(OfflineReferenceTest, DISABLED_CornellBoxFullResolution) {
  check(kCornell, 1, 1024, 32);
}
TEST_F(OfflineReferenceTest, DISABLED_CornellBoxLambertFullResolution) {
  check(kCornellLambert, 1, 1024, 32);
}
TEST_F(OfflineReferenceTest, DISABLED_SponzaAtriumFullResolution) {
  check(kSponzaAtrium, 1, 256, 8);
}
TEST_F(OfflineReferenceTest, DISABLED_SponzaGalleryFullResolution) {
  check(kSponzaGallery, 1, 256, 8);
}
TEST_F(OfflineReferenceTest, DISABLED_ConferenceRoomFullResolution) {
  check(kConference, 1, 256, 8);
}
TEST_F(OfflineReferenceTest, DISABLED_SibenikFullResolution) {
  check(kSibenik, 1, 256, 8);
}
// A quarter of the resolution at 64 spp: a few minutes on lavapipe.
TEST_F(OfflineReferenceTest, DISABLED_SponzaAtriumQuarterResolution) {
  check(kSponzaAtrium, 4, 64, 8);
}
TEST_F(OfflineReferenceTest, DISABLED_SponzaGalleryQuarterResolution) {
  check(kSponzaGallery, 4, 64, 8);
}
TEST_F(OfflineReferenceTest, DISABLED_ConferenceRoomQuarterResolution) {
  check(kConference, 4, 64, 8);
}

}  // namespace
}  // namespace voxgi::test
