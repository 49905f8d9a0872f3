// The path tracer's indirect light limited by max_depth against the closed forms and the
// radiosity solution of tests/common/gi_energy, which the voxel GI energy tests use as their
// references: two independent answers to the same scenes, each checking the other.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/common/gi_energy.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class AnalyticIndirectTest : public GpuTest {};

// One indirect bounce at the receiver: within 5 standard errors of the path-traced mean plus
// 0.2% (the receiver is 15 mm wide, the reference is its centre's value).
TEST_F(AnalyticIndirectTest, ReceiverOverALitSquareMatchesThePathTracer) {
  for (SquareLight light : {SquareLight::Directional, SquareLight::Point}) {
    for (double height : kReceiverHeights) {
      const LitSquare square{light, height};
      const PathTracedMean traced = path_traced_mean_indirect(lit_square_scene(square), 16, 1, 512);
      const double expected = lit_square_one_bounce_irradiance(square) / std::numbers::pi;
      std::printf("%s: path traced %.5f (standard error %.5f), analytic %.5f\n",
                  square.label().c_str(), traced.luminance, traced.standard_error, expected);
      EXPECT_NEAR(traced.luminance, expected, 5.0 * traced.standard_error + 2e-3 * expected)
          << square.label();
    }
  }
}

// path_tracer.first_bounce_distance D keeps the light of the square's part within D of the
// receiver: a disc of radius sqrt(D^2 - h^2) centred under the receiving point (inside the
// square here, so no placement of the point on the 15 mm receiver changes it), whose form
// factor from a parallel differential area is r^2 / (r^2 + h^2); less the receiver's shadow, as
// in the closed form above. Below the height, nothing. The same bar.
TEST_F(AnalyticIndirectTest, FirstBounceDistanceKeepsTheSquareWithinIt) {
  const LitSquare square{SquareLight::Directional, 0.5};
  const double h = square.height;
  const double hole = 0.5 * square.shadow_side();
  const double shadow = parallel_rectangle_form_factor(h, -hole, hole, -hole, hole);
  for (double radius : {0.15, 0.3}) {
    const double distance = std::sqrt(radius * radius + h * h);
    const PathTracedMean traced = path_traced_mean_indirect(
        lit_square_scene(square), 16, 1, 512,
        {{"path_tracer.first_bounce_distance", std::to_string(distance)}});
    const double disc = radius * radius / (radius * radius + h * h);
    const double expected =
        LitSquare::kAlbedo * LitSquare::kIrradiance * (disc - shadow) / std::numbers::pi;
    std::printf(
        "%s, first bounce within %.4f: path traced %.5f (standard error %.5f), "
        "analytic %.5f\n",
        square.label().c_str(), distance, traced.luminance, traced.standard_error, expected);
    EXPECT_NEAR(traced.luminance, expected, 5.0 * traced.standard_error + 2e-3 * expected)
        << distance;
  }
  const PathTracedMean none = path_traced_mean_indirect(
      lit_square_scene(square), 16, 1, 64, {{"path_tracer.first_bounce_distance", "0.45"}});
  EXPECT_EQ(none.luminance, 0.0) << "the square lies 0.5 under the receiver";
}

// path_tracer.first_bounce_sin2_min / _max keep the first reflections whose direction has
// sin^2 theta in a band: seen from the receiver, a disc (or a ring) of the square centred under
// it, whose form factor is exactly the band's width (a cosine-weighted cone of half angle theta
// holds sin^2 theta of the hemisphere); the receiver's shadow lies in [0, 5e-4). Both bands
// stay inside the square (sin^2 theta = 0.25 reaches 0.29 m out at h = 0.5 m). The same bar.
TEST_F(AnalyticIndirectTest, FirstBounceBandKeepsItsRingOfTheSquare) {
  const LitSquare square{SquareLight::Directional, 0.5};
  const double h = square.height;
  const double hole = 0.5 * square.shadow_side();
  const double shadow = parallel_rectangle_form_factor(h, -hole, hole, -hole, hole);
  struct Band {
    double min, max, form_factor;
  };
  for (const Band& band : {Band{0.0, 0.25, 0.25 - shadow}, Band{0.1, 0.25, 0.15}}) {
    const PathTracedMean traced = path_traced_mean_indirect(
        lit_square_scene(square), 16, 1, 512,
        {{"path_tracer.first_bounce_sin2_min", std::to_string(band.min)},
         {"path_tracer.first_bounce_sin2_max", std::to_string(band.max)}});
    const double expected =
        LitSquare::kAlbedo * LitSquare::kIrradiance * band.form_factor / std::numbers::pi;
    std::printf(
        "%s, first bounce sin^2 in [%.2f, %.2f): path traced %.5f (standard error %.5f), "
        "analytic %.5f\n",
        square.label().c_str(), band.min, band.max, traced.luminance, traced.standard_error,
        expected);
    EXPECT_NEAR(traced.luminance, expected, 5.0 * traced.standard_error + 2e-3 * expected)
        << band.min << " " << band.max;
  }
}

// The receiver on the floor before the lit wall, near it and far from it, and before the wall
// leaning back: the same bar.
TEST_F(AnalyticIndirectTest, ReceiverBeforeALitWallMatchesThePathTracer) {
  for (const LitWall& wall : kLitWalls) {
    const PathTracedMean traced = path_traced_mean_indirect(lit_wall_scene(wall), 16, 1, 512);
    const double expected = lit_wall_one_bounce_irradiance(wall) / std::numbers::pi;
    std::printf("%s: path traced %.5f (standard error %.5f), analytic %.5f\n", wall.label().c_str(),
                traced.luminance, traced.standard_error, expected);
    EXPECT_NEAR(traced.luminance, expected, 5.0 * traced.standard_error + 2e-3 * expected)
        << wall.label();
  }
}

// The box's 32 x 32 view after 1 to 3 indirect bounces: within 5 standard errors plus 1% (the
// radiosity's piecewise-constant patches; 12 and 24 patches per edge agree to 0.5%).
TEST_F(AnalyticIndirectTest, ClosedBoxMatchesThePathTracerPerBounce) {
  const BoxRadiosity radiosity(12, 3);
  const scene::Scene box = lit_box_scene();
  for (int bounces = 1; bounces <= 3; ++bounces) {
    const PathTracedMean traced = path_traced_mean_indirect(box, 32, bounces, 128);
    const double expected = radiosity.mean_indirect_radiance(box.cameras.front(), 32, bounces);
    std::printf(
        "closed box, %d indirect bounces: path traced %.5f (standard error %.5f), "
        "radiosity %.5f\n",
        bounces, traced.luminance, traced.standard_error, expected);
    EXPECT_NEAR(traced.luminance, expected, 5.0 * traced.standard_error + 1e-2 * expected)
        << bounces << " bounces";
  }
}

}  // namespace
}  // namespace voxgi::test
