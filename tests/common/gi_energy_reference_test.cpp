// The references of tests/common/gi_energy against each other, on the CPU: the corner form
// factor against Lambert's contour integral, the numerical one-bounce integral against the
// closed form, and the box radiosity's closure, energy per bounce and convergence.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tests/common/gi_energy.hpp"

namespace voxgi::test {
namespace {

TEST(GiEnergyReference, CornerFormFactorAgreesWithTheContourIntegral) {
  const double cases[][3] = {{1.0, 1.0, 1.0}, {0.5, 2.0, 0.3}, {3.0, 0.2, 1.7}, {0.01, 0.02, 1.0}};
  for (const auto& [a, b, h] : cases) {
    const glm::dvec3 rectangle[] = {{0, 0, 0}, {a, 0, 0}, {a, 0, b}, {0, 0, b}};
    const double contour =
        polygon_form_factor(glm::dvec3(0.0, h, 0.0), glm::dvec3(0.0, -1.0, 0.0), rectangle);
    EXPECT_NEAR(corner_parallel_form_factor(a, b, h), contour, 1e-12 * contour + 1e-15)
        << a << " x " << b << " at " << h;
  }
  // Signed extents: a rectangle not under the receiver.
  const glm::dvec3 offset[] = {{0.2, 0, -0.4}, {0.9, 0, -0.4}, {0.9, 0, 0.3}, {0.2, 0, 0.3}};
  EXPECT_NEAR(parallel_rectangle_form_factor(0.6, 0.2, 0.9, -0.4, 0.3),
              polygon_form_factor(glm::dvec3(0.0, 0.6, 0.0), glm::dvec3(0.0, -1.0, 0.0), offset),
              1e-12);
}

TEST(GiEnergyReference, CentredSquareFormFactorHasTheClosedFormAndLimits) {
  for (double x : {0.1, 0.5, 1.0, 2.0}) {
    // Side a = 2 x h centred under the receiver, h = 1.
    const double s = x / std::sqrt(1.0 + x * x);
    const double closed = 4.0 / std::numbers::pi * s * std::atan(s);
    EXPECT_NEAR(parallel_rectangle_form_factor(1.0, -x, x, -x, x), closed, 1e-12);
  }
  // An unbounded plane fills the hemisphere; a small patch is A cos^2 / (pi h^2) = A / pi.
  EXPECT_NEAR(parallel_rectangle_form_factor(1.0, -1e6, 1e6, -1e6, 1e6), 1.0, 1e-5);
  EXPECT_NEAR(parallel_rectangle_form_factor(1.0, -1e-3, 1e-3, -1e-3, 1e-3),
              4e-6 / std::numbers::pi, 1e-11);
}

TEST(GiEnergyReference, NumericalOneBounceIntegralMatchesTheClosedFormForUniformLight) {
  // Directional light: the integral is rho E (F_square - F_hole) exactly.
  for (double h : kReceiverHeights) {
    const double hole = 0.05;
    const double numeric = one_bounce_irradiance_over_square(h, 1.0, 0.8, hole, 2000,
                                                             [](double, double) { return 3.0; });
    const double closed =
        0.8 * 3.0 *
        (parallel_rectangle_form_factor(h, -0.5, 0.5, -0.5, 0.5) -
         parallel_rectangle_form_factor(h, -0.5 * hole, 0.5 * hole, -0.5 * hole, 0.5 * hole));
    EXPECT_NEAR(numeric, closed, 2e-5 * closed) << "h = " << h;
  }
  // The point-light case falls between the irradiance at the square's centre and at its corner.
  const LitSquare square{SquareLight::Point, 0.5};
  const double H = square.light_height();
  const double corner = LitSquare::kIntensity * H / std::pow(0.5 + H * H, 1.5);
  const double centre = LitSquare::kIntensity / (H * H);
  const double f = parallel_rectangle_form_factor(0.5, -0.5, 0.5, -0.5, 0.5);
  const double e = lit_square_one_bounce_irradiance(square);
  EXPECT_GT(e, LitSquare::kAlbedo * corner * f * 0.99);
  EXPECT_LT(e, LitSquare::kAlbedo * centre * f);
}

TEST(GiEnergyReference, BoxRadiosityIsClosedAndLosesTheAlbedoPerBounce) {
  const BoxRadiosity radiosity(12);
  double worst_sum = 0.0;
  for (int i = 0; i < radiosity.patch_count(); ++i) {
    worst_sum = std::max(worst_sum, std::abs(radiosity.form_factor_sum(i) - 1.0));
  }
  EXPECT_LT(worst_sum, 1e-9) << "the other five walls fill every patch's hemisphere";
  // Direct light: the point light's whole flux 4 pi I lands on the walls, rho of it leaves.
  EXPECT_NEAR(radiosity.power(0), LitBox::kAlbedo * 4.0 * std::numbers::pi * LitBox::kIntensity,
              1e-3 * radiosity.power(0));
  // In a closed box each bounce sends on rho of the power it received (reciprocity); point
  // collocation keeps that to a fraction of a percent.
  for (int k = 0; k < 4; ++k) {
    const double gain = radiosity.power(k + 1) / radiosity.power(k);
    std::printf("box radiosity: power of bounce %d / bounce %d = %.5f (albedo %.3f)\n", k + 1, k,
                gain, LitBox::kAlbedo);
    EXPECT_NEAR(gain, LitBox::kAlbedo, 0.005) << "bounce " << k + 1;
  }
}

TEST(GiEnergyReference, BoxRadiosityConvergesWithThePatchGrid) {
  const BoxRadiosity coarse(12);
  const BoxRadiosity fine(24);
  // Points on three walls, one near an edge.
  const glm::dvec3 lo = LitBox::interior_min();
  const glm::dvec3 points[][2] = {{lo + glm::dvec3(0.5, 0.5, 1.0), {0, 0, -1}},
                                  {lo + glm::dvec3(0.3, 0.0, 0.7), {0, 1, 0}},
                                  {lo + glm::dvec3(0.0, 0.9, 0.04), {1, 0, 0}}};
  for (int bounces = 1; bounces <= 4; ++bounces) {
    for (const auto& [p, n] : points) {
      const double a = coarse.indirect_radiance(p, n, bounces);
      const double b = fine.indirect_radiance(p, n, bounces);
      EXPECT_NEAR(a, b, 0.005 * b) << bounces << " bounces at " << p.x << " " << p.y << " " << p.z;
    }
  }
}

}  // namespace
}  // namespace voxgi::test
