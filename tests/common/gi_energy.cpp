#include "tests/common/gi_energy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "engine/image/metrics.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/hard_case_scenes.hpp"
#include "tests/reference/image_statistics.hpp"

namespace voxgi::test {

using std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Form factors

double corner_parallel_form_factor(double a, double b, double h) {
  const double A = a / h;
  const double B = b / h;
  const double sa = std::sqrt(1.0 + A * A);
  const double sb = std::sqrt(1.0 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * pi);
}

double parallel_rectangle_form_factor(double h, double x0, double x1, double z0, double z1) {
  // The rectangle as a signed sum of four rectangles with a corner under the receiver.
  return corner_parallel_form_factor(x1, z1, h) - corner_parallel_form_factor(x0, z1, h) -
         corner_parallel_form_factor(x1, z0, h) + corner_parallel_form_factor(x0, z0, h);
}

double polygon_form_factor(const glm::dvec3& p, const glm::dvec3& n,
                           std::span<const glm::dvec3> polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3 r0 = polygon[i] - p;
    const glm::dvec3 r1 = polygon[(i + 1) % polygon.size()] - p;
    const glm::dvec3 c = glm::cross(r0, r1);
    const double length = glm::length(c);
    // p on the edge's line: the edge subtends no angle (or p is on the edge itself, where the
    // form factor is not defined).
    if (length < 1e-14) continue;
    sum += std::atan2(length, glm::dot(r0, r1)) * glm::dot(n, c) / length;
  }
  return std::abs(sum) / (2.0 * pi);
}

// ---------------------------------------------------------------------------------------------
// Receiver facing a lit square

double LitSquare::shadow_side() const {
  if (light == SquareLight::Directional) return kReceiverSide;
  // Central projection from the light at H onto the square: scale H / (H - h).
  return kReceiverSide * light_height() / kLightAboveReceiver;
}

std::string LitSquare::label() const {
  char text[144];
  char units[48] = "";
  if (units_per_metre != 1.0) {
    std::snprintf(units, sizeof units, ", modelled at %g units per metre", units_per_metre);
  }
  char where[64] = "";
  if (under && beside != 0.0) {
    std::snprintf(where, sizeof where, " under the square's level, %.2f m aside", beside);
  } else if (under) {
    std::snprintf(where, sizeof where, " under the square");
  }
  std::snprintf(text, sizeof text, "%s light, h = %.2f m%s%s",
                light == SquareLight::Directional ? "directional" : "point", height, where, units);
  return text;
}

scene::Scene lit_square_scene(const LitSquare& setup) {
  scene::SceneBuilder b("lit_square");
  const float u = static_cast<float>(setup.units_per_metre);
  const float a = static_cast<float>(LitSquare::kSide) * u;
  const float r = static_cast<float>(LitSquare::kReceiverSide) * u;
  const float h = static_cast<float>(setup.height) * u;
  const int square = b.add_material(matte(glm::vec3(static_cast<float>(LitSquare::kAlbedo))));
  const int receiver = b.add_material(matte(glm::vec3(1.0f)));
  // Facing +y.
  b.add_quad("square", {-0.5f * a, 0.0f, -0.5f * a}, {0, 0, a}, {a, 0, 0}, square);
  const float x = setup.under ? static_cast<float>(setup.beside) * u : 0.0f;
  if (setup.under) {
    // Facing +y, towards the square's underside.
    b.add_quad("receiver", {x - 0.5f * r, -h, -0.5f * r}, {0, 0, r}, {r, 0, 0}, receiver);
  } else {
    // Facing -y, towards the square.
    b.add_quad("receiver", {-0.5f * r, h, -0.5f * r}, {r, 0, 0}, {0, 0, r}, receiver);
  }
  scene::Light light;
  if (setup.light == SquareLight::Directional) {
    light.type = scene::LightType::Directional;
    light.intensity = static_cast<float>(LitSquare::kIrradiance);
  } else {
    light.type = scene::LightType::Point;
    light.intensity = static_cast<float>(LitSquare::kIntensity) * u * u;  // the same irradiance
  }
  b.add_light(light, {0.0f, static_cast<float>(setup.light_height()) * u, 0.0f},
              {0.0f, -1.0f, 0.0f});
  // 4 cm from the receiver (at most half its distance to the square) on its facing side,
  // looking at it; the view's half-width there is 6 mm, inside the receiver's 7.5 mm.
  const float distance = std::min(0.04f * u, 0.5f * h);
  const float y = setup.under ? -h : h;
  const float side = setup.under ? 1.0f : -1.0f;
  b.add_camera("at_receiver", {x, y + side * distance, 0.0f}, {x, y, 0.0f},
               2.0f * std::atan(0.006f * u / distance), {0.0f, 0.0f, 1.0f});
  return b.finish();
}

double lit_square_one_bounce_irradiance(const LitSquare& setup) {
  const double h = setup.height;
  const double half = 0.5 * LitSquare::kSide;
  const double hole = 0.5 * setup.shadow_side();
  if (setup.light == SquareLight::Directional) {
    const double f = parallel_rectangle_form_factor(h, -half, half, -half, half) -
                     parallel_rectangle_form_factor(h, -hole, hole, -hole, hole);
    return LitSquare::kAlbedo * LitSquare::kIrradiance * f;
  }
  // A 2000^2 grid of 0.5 mm cells: the integrand varies on the scale of h >= 0.25 m.
  const double H = setup.light_height();
  return one_bounce_irradiance_over_square(
      h, LitSquare::kSide, LitSquare::kAlbedo, setup.shadow_side(), 2000, [H](double x, double z) {
        const double d2 = x * x + z * z + H * H;
        return LitSquare::kIntensity * H / (d2 * std::sqrt(d2));
      });
}

// ---------------------------------------------------------------------------------------------
// Receiver on a floor before a lit wall

std::array<glm::dvec3, 4> LitWall::corners() const {
  const double half = 0.5 * kWidth;
  const glm::dvec3 up = kHeight * glm::dvec3(0.0, std::cos(lean), -std::sin(lean));
  return {glm::dvec3(-half, 0.0, 0.0), glm::dvec3(half, 0.0, 0.0), glm::dvec3(half, 0.0, 0.0) + up,
          glm::dvec3(-half, 0.0, 0.0) + up};
}

glm::dvec3 LitWall::normal() const {
  return {0.0, std::sin(lean), std::cos(lean)};
}

std::string LitWall::label() const {
  char text[96];
  std::snprintf(text, sizeof text, "receiver %.2f m before the wall, leaning %.0f degrees",
                distance, lean * 180.0 / pi);
  return text;
}

scene::Scene lit_wall_scene(const LitWall& setup) {
  scene::SceneBuilder b("lit_wall");
  const float w = static_cast<float>(LitWall::kWidth);
  const float depth = static_cast<float>(LitWall::kDepth);
  const float d = static_cast<float>(setup.distance);
  const int wall = b.add_material(matte(glm::vec3(static_cast<float>(LitWall::kAlbedo))));
  const int floor = b.add_material(matte(glm::vec3(1.0f)));
  // Facing +z (tilted up by its lean), standing on the floor.
  const std::array<glm::dvec3, 4> c = setup.corners();
  b.add_quad("wall", glm::vec3(c[0]), glm::vec3(c[1] - c[0]), glm::vec3(c[3] - c[0]), wall);
  // Facing +y, from behind the wall's top to kDepth in front of it.
  const float behind = 0.1f + static_cast<float>(-c[3].z);
  b.add_quad("floor", {-0.5f * w, 0.0f, -behind}, {0, 0, depth + behind}, {w, 0, 0}, floor);
  scene::Light light;
  light.type = scene::LightType::Directional;
  light.intensity = static_cast<float>(LitWall::kIrradiance);
  b.add_light(light, {0.0f, 2.0f, 2.0f}, glm::vec3(LitWall::light_direction()));
  // 4 cm above the receiver, looking down at it; the view's half-width there is 6 mm.
  const float above = 0.04f;
  b.add_camera("at_receiver", {0.0f, above, d}, {0.0f, 0.0f, d}, 2.0f * std::atan(0.006f / above),
               {0.0f, 0.0f, -1.0f});
  return b.finish();
}

double lit_wall_one_bounce_irradiance(const LitWall& setup) {
  const std::array<glm::dvec3, 4> wall = setup.corners();
  const double f = polygon_form_factor({0.0, 0.0, setup.distance}, {0.0, 1.0, 0.0}, wall);
  // The light comes from -light_direction().
  const double cosine = glm::dot(-LitWall::light_direction(), setup.normal());
  return LitWall::kAlbedo * LitWall::kIrradiance * cosine * f;
}

// ---------------------------------------------------------------------------------------------
// Camera rays

CameraPixelRays::CameraPixelRays(const scene::Camera& camera, uint32_t size)
    : inverse_view_proj_(glm::inverse(
          glm::dmat4(scene::projection_matrix(camera, 1.0f) * scene::view_matrix(camera)))),
      size_(size) {}

PixelRay CameraPixelRays::operator()(uint32_t x, uint32_t y) const {
  const double nx = (x + 0.5) / size_ * 2.0 - 1.0;
  const double ny = (y + 0.5) / size_ * 2.0 - 1.0;
  const glm::dvec4 near_point = inverse_view_proj_ * glm::dvec4(nx, ny, 0.0, 1.0);
  const glm::dvec4 far_point = inverse_view_proj_ * glm::dvec4(nx, ny, 1.0, 1.0);
  const glm::dvec3 origin = glm::dvec3(near_point) / near_point.w;
  return {origin, glm::dvec3(far_point) / far_point.w - origin};
}

// ---------------------------------------------------------------------------------------------
// Closed box

glm::dvec3 LitBox::light_position() {
  return 0.5 * (interior_min() + interior_max()) + glm::dvec3(0.1, 0.15, 0.05);
}

scene::Scene lit_box_scene() {
  scene::SceneBuilder b("lit_box");
  const int wall = b.add_material(matte(glm::vec3(static_cast<float>(LitBox::kAlbedo))));
  add_closed_box(b, glm::vec3(LitBox::interior_min()), glm::vec3(LitBox::interior_max()),
                 static_cast<float>(LitBox::kWall), wall);
  b.add_light(point_light(static_cast<float>(LitBox::kIntensity)),
              glm::vec3(LitBox::light_position()));
  b.add_camera("inside", {0.0f, 0.0f, -0.45f}, {0.0f, 0.0f, 1.0f},
               0.5f * std::numbers::pi_v<float>);
  return b.finish();
}

BoxRadiosity::BoxRadiosity(int patches_per_edge, int max_bounce) {
  const glm::dvec3 lo = LitBox::interior_min();
  const glm::dvec3 hi = LitBox::interior_max();
  const int n = patches_per_edge;
  const double step = LitBox::kSide / n;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          Patch patch;
          patch.wall = axis * 2 + side;
          patch.normal = glm::dvec3(0.0);
          patch.normal[axis] = side == 0 ? 1.0 : -1.0;  // inward
          glm::dvec3 corner = lo;
          corner[axis] = side == 0 ? lo[axis] : hi[axis];
          corner[u] += i * step;
          corner[v] += j * step;
          glm::dvec3 du(0.0), dv(0.0);
          du[u] = step;
          dv[v] = step;
          patch.corners = {corner, corner + du, corner + du + dv, corner + dv};
          patch.centre = corner + 0.5 * (du + dv);
          patch.area = step * step;
          patches_.push_back(std::move(patch));
        }
      }
    }
  }
  const size_t count = patches_.size();

  // Bounce 0: the direct light averaged over 4 x 4 points of each patch (the light is at
  // least 0.35 m from every wall, so this is the patch mean to well below 0.1%).
  const glm::dvec3 light = LitBox::light_position();
  std::vector<double> direct(count, 0.0);
  for (size_t j = 0; j < count; ++j) {
    const Patch& patch = patches_[j];
    const glm::dvec3 du = patch.corners[1] - patch.corners[0];
    const glm::dvec3 dv = patch.corners[3] - patch.corners[0];
    double sum = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 4; ++c) {
        const glm::dvec3 q = patch.corners[0] + (a + 0.5) / 4.0 * du + (c + 0.5) / 4.0 * dv;
        const glm::dvec3 to_light = light - q;
        const double d2 = glm::dot(to_light, to_light);
        sum += LitBox::kIntensity * std::max(glm::dot(patch.normal, to_light), 0.0) /
               (d2 * std::sqrt(d2));
      }
    }
    direct[j] = LitBox::kAlbedo / pi * sum / 16.0;
  }
  radiance_.push_back(std::move(direct));

  std::vector<std::vector<double>> form_factors(count, std::vector<double>(count, 0.0));
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = 0; j < count; ++j) {
      if (patches_[i].wall == patches_[j].wall) continue;  // coplanar: sees nothing of it
      form_factors[i][j] =
          polygon_form_factor(patches_[i].centre, patches_[i].normal, patches_[j].corners);
    }
  }
  for (int k = 0; k < max_bounce; ++k) {
    const std::vector<double>& previous = radiance_.back();
    std::vector<double> next(count, 0.0);
    for (size_t i = 0; i < count; ++i) {
      double gathered = 0.0;
      for (size_t j = 0; j < count; ++j) gathered += form_factors[i][j] * previous[j];
      next[i] = LitBox::kAlbedo * gathered;
    }
    radiance_.push_back(std::move(next));
  }
}

double BoxRadiosity::form_factor_sum(int patch) const {
  const Patch& from = patches_[static_cast<size_t>(patch)];
  double sum = 0.0;
  for (const Patch& to : patches_) {
    if (to.wall != from.wall) sum += polygon_form_factor(from.centre, from.normal, to.corners);
  }
  return sum;
}

double BoxRadiosity::power(int bounce) const {
  double sum = 0.0;
  for (size_t j = 0; j < patches_.size(); ++j) {
    sum += pi * patches_[j].area * radiance_[static_cast<size_t>(bounce)][j];
  }
  return sum;
}

double BoxRadiosity::indirect_radiance(const glm::dvec3& p, const glm::dvec3& n,
                                       int indirect_bounces) const {
  double gathered = 0.0;
  for (size_t j = 0; j < patches_.size(); ++j) {
    const Patch& patch = patches_[j];
    if (glm::dot(patch.normal, n) > 0.5) continue;  // the wall p lies on
    double radiance = 0.0;
    for (int k = 0; k < indirect_bounces; ++k) radiance += radiance_[static_cast<size_t>(k)][j];
    gathered += polygon_form_factor(p, n, patch.corners) * radiance;
  }
  return LitBox::kAlbedo * gathered;
}

double BoxRadiosity::mean_indirect_radiance(const scene::Camera& camera, uint32_t size,
                                            int indirect_bounces) const {
  const CameraPixelRays rays(camera, size);
  const glm::dvec3 lo = LitBox::interior_min();
  const glm::dvec3 hi = LitBox::interior_max();
  double sum = 0.0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const auto [origin, dir] = rays(x, y);
      // The camera is inside the room: the ray leaves it through the wall it sees.
      double t = std::numeric_limits<double>::max();
      int axis = 0;
      for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-12) continue;
        const double ta = ((dir[a] > 0.0 ? hi[a] : lo[a]) - origin[a]) / dir[a];
        if (ta < t) {
          t = ta;
          axis = a;
        }
      }
      glm::dvec3 normal(0.0);
      normal[axis] = dir[axis] > 0.0 ? -1.0 : 1.0;
      // A micrometre into the room and away from the wall's edges: on an edge, the neighbouring
      // wall's patches would have the point on their border, where the contour integral is
      // undefined.
      const glm::dvec3 p = glm::clamp(origin + t * dir, lo + 1e-6, hi - 1e-6);
      sum += indirect_radiance(p, normal, indirect_bounces);
    }
  }
  return sum / (static_cast<double>(size) * size);
}

// ---------------------------------------------------------------------------------------------
// Placement on the voxel grid

scene::Scene moved_on_the_voxel_grid(scene::Scene scene, uint32_t voxel_resolution, double voxels) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  const glm::vec3 size = hi - lo;
  const double extent = std::max({size.x, size.y, size.z});
  // The automatic voxel edge of one dense level (common.voxelize).
  const double voxel = extent / (static_cast<double>(voxel_resolution) - 4.0);
  for (scene::Node& node : scene.nodes) {
    if (node.parent < 0) node.translation += glm::vec3(static_cast<float>(voxels * voxel));
  }
  scene.update_transforms();
  return scene;
}

// ---------------------------------------------------------------------------------------------
// Scenes for the energy bounds

scene::Scene cornell_lit_by_its_point_light() {
  scene::Scene cornell = scene::make_builtin_scene("cornell");
  for (scene::Material& material : cornell.materials) material.emissive = glm::vec3(0.0f);
  return cornell;
}

// ---------------------------------------------------------------------------------------------
// Rendering

VoxelGiSetup vct_gi_setup(uint32_t voxel_resolution, int diffuse_cones) {
  VoxelGiSetup gi;
  gi.graph = "graphs/vct.json";
  gi.voxel_resolution = voxel_resolution;
  gi.indirect_bounces = 1;
  gi.label = "vct " + std::to_string(voxel_resolution) + "^3";
  if (diffuse_cones > 0) {
    gi.overrides["cone_trace.diffuse_cones"] = std::to_string(diffuse_cones);
    gi.label += ", " + std::to_string(diffuse_cones) + " cones";
  }
  return gi;
}

VoxelGiSetup vct_front_light_gi_setup(uint32_t voxel_resolution, int diffuse_cones) {
  VoxelGiSetup gi = vct_gi_setup(voxel_resolution, diffuse_cones);
  gi.graph = "graphs/vct_front_light.json";
  gi.label = "front light " + gi.label;
  return gi;
}

VoxelGiSetup lpv_gi_setup(uint32_t voxel_resolution, int iterations) {
  VoxelGiSetup gi;
  gi.graph = "graphs/lpv.json";
  gi.voxel_resolution = voxel_resolution;
  gi.indirect_bounces = 1;
  gi.label = "lpv " + std::to_string(voxel_resolution) + "^3";
  if (iterations > 0) {
    gi.overrides["lpv.iterations"] = std::to_string(iterations);
    gi.label += ", " + std::to_string(iterations) + " iterations";
  }
  return gi;
}

VoxelGiSetup dvs_gi_setup(uint32_t voxel_resolution, int bounces, int diffuse_cones) {
  VoxelGiSetup gi;
  gi.graph = "graphs/dvs.json";
  gi.voxel_resolution = voxel_resolution;
  gi.overrides["dvs.bounces"] = std::to_string(bounces);
  gi.indirect_bounces = bounces + 1;
  gi.label = "dvs " + std::to_string(voxel_resolution) + "^3, " + std::to_string(bounces) +
             " voxel bounces";
  if (diffuse_cones > 0) {
    gi.overrides["dvs.cones"] = std::to_string(diffuse_cones);
    gi.label += ", " + std::to_string(diffuse_cones) + " cones";
  }
  return gi;
}

VoxelGiSetup dvs_front_light_gi_setup(uint32_t voxel_resolution, int bounces, int diffuse_cones) {
  VoxelGiSetup gi = dvs_gi_setup(voxel_resolution, bounces, diffuse_cones);
  gi.graph = "graphs/dvs_front_light.json";
  gi.label = "front light " + gi.label;
  return gi;
}

std::string voxel_resolution_name(uint32_t voxel_resolution) {
  std::string name = "R";
  name += std::to_string(voxel_resolution);
  return name;
}

RenderSetup voxel_gi_render_setup(const VoxelGiSetup& gi, const scene::Scene& scene,
                                  uint32_t size) {
  RenderSetup setup;
  setup.graph = gi.graph;
  setup.scene_data = scene;
  setup.width = size;
  setup.height = size;
  setup.overrides = gi.overrides;
  setup.overrides["voxel.resolution"] = std::to_string(gi.voxel_resolution);
  setup.overrides["voxel.levels"] = std::to_string(gi.voxel_levels);
  return setup;
}

double mean_luminance(const RenderedImage& image) {
  double sum = 0.0;
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  for (size_t i = 0; i < pixels; ++i) sum += image::luminance(&image.rgba[i * 4]);
  return pixels > 0 ? sum / static_cast<double>(pixels) : 0.0;
}

double render_mean_indirect(const VoxelGiSetup& gi, const scene::Scene& scene, uint32_t size) {
  RenderHarness harness(voxel_gi_render_setup(gi, scene, size));
  harness.render();
  const RenderedImage indirect = harness.output("indirect");
  expect_finite_non_negative(indirect, gi.label + " indirect");
  return mean_luminance(indirect);
}

namespace {

// graphs/reference.json as the comparisons need it: Lambertian, `indirect_bounces` + 1 deep,
// pixel centres, `per_frame` samples per pixel and frame.
RenderSetup path_traced_setup(const scene::Scene& scene, uint32_t size, int indirect_bounces,
                              int per_frame) {
  RenderSetup setup;
  setup.graph = "graphs/reference.json";
  setup.scene_data = scene;
  setup.width = size;
  setup.height = size;
  setup.overrides = {{"path_tracer.lambert", "true"},
                     {"path_tracer.max_depth", std::to_string(indirect_bounces + 1)},
                     {"path_tracer.pixel_jitter", "false"},
                     {"path_tracer.samples_per_frame", std::to_string(per_frame)}};
  return setup;
}

}  // namespace

PathTracedMean path_traced_mean_indirect(const scene::Scene& scene, uint32_t size,
                                         int indirect_bounces, int samples_per_pixel,
                                         const std::map<std::string, std::string>& overrides) {
  const int per_frame = std::min(samples_per_pixel, 32);
  RenderSetup setup = path_traced_setup(scene, size, indirect_bounces, per_frame);
  for (const auto& [key, value] : overrides) setup.overrides[key] = value;
  RenderHarness harness(setup);
  harness.render((samples_per_pixel + per_frame - 1) / per_frame);
  const RenderedImage indirect = harness.output("indirect");
  expect_finite_non_negative(indirect, "path-traced indirect");
  return {mean_luminance(indirect), mean_luminance_standard_error(harness.output("variance"))};
}

double IndirectComparison::mean_ratio() const {
  double sum = 0.0;
  for (double value : rendered) sum += value;
  return rendered.empty() || expected <= 0.0 ? 0.0 : sum / rendered.size() / expected;
}

std::string IndirectComparison::ratios() const {
  std::string text;
  for (double value : rendered) {
    char ratio[16];
    std::snprintf(ratio, sizeof ratio, " %.3f", expected > 0.0 ? value / expected : 0.0);
    text += ratio;
  }
  return text;
}

namespace {

// Mean indirect luminance of `scene` at every placement of kVoxelPlacements.
std::vector<double> render_at_every_placement(const VoxelGiSetup& gi, const scene::Scene& scene,
                                              uint32_t size) {
  std::vector<double> means;
  for (double placement : kVoxelPlacements) {
    const scene::Scene moved = moved_on_the_voxel_grid(scene, gi.voxel_resolution, placement);
    means.push_back(render_mean_indirect(gi, moved, size));
  }
  return means;
}

}  // namespace

IndirectComparison compare_lit_square(const VoxelGiSetup& gi, const LitSquare& square) {
  // Receiver albedo 1: outgoing radiance E / pi.
  return {render_at_every_placement(gi, lit_square_scene(square), 16),
          lit_square_one_bounce_irradiance(square) / pi};
}

IndirectComparison compare_lit_wall(const VoxelGiSetup& gi, const LitWall& wall) {
  // Receiver albedo 1: outgoing radiance E / pi.
  return {render_at_every_placement(gi, lit_wall_scene(wall), 16),
          lit_wall_one_bounce_irradiance(wall) / pi};
}

IndirectComparison compare_lit_box(const VoxelGiSetup& gi, const BoxRadiosity& radiosity) {
  const uint32_t size = 32;
  const scene::Scene box = lit_box_scene();
  // The unmoved camera: moving the whole scene changes no pixel's view of the box.
  return {render_at_every_placement(gi, box, size),
          radiosity.mean_indirect_radiance(box.cameras.front(), size, gi.indirect_bounces)};
}

// ---------------------------------------------------------------------------------------------
// Shared expectations

namespace {

// The receiver of `dark` (under the square) against the closed form for one as far above it:
// below `fraction` of it.
void expect_dark_under_the_square(const VoxelGiSetup& gi, const LitSquare& dark, double fraction,
                                  const char* tag) {
  const LitSquare above{dark.light, dark.height};
  const IndirectComparison c = {render_at_every_placement(gi, lit_square_scene(dark), 16),
                                lit_square_one_bounce_irradiance(above) / pi};
  std::printf("[%s] %s, %s: %.5f of the lit side's %.5f, ratio %.4f (per placement%s)\n", tag,
              gi.label.c_str(), dark.label().c_str(), c.mean_ratio() * c.expected, c.expected,
              c.mean_ratio(), c.ratios().c_str());
  EXPECT_LT(c.mean_ratio(), fraction) << gi.label << ", " << dark.label();
}

}  // namespace

void expect_unlit_underside_sends_nothing(const VoxelGiSetup& gi, SquareLight light) {
  for (const auto& [height, fraction] : kUndersideCases) {
    expect_dark_under_the_square(gi, LitSquare{light, height, true}, fraction, "unlit underside");
  }
}

void expect_unlit_underside_sends_nothing_sideways(const VoxelGiSetup& gi) {
  for (const auto& [height, beside, fraction] : kBesideCases) {
    LitSquare aside{SquareLight::Directional, height, true};
    aside.beside = beside;
    expect_dark_under_the_square(gi, aside, fraction, "unlit underside, aside");
  }
}

namespace {

// Sums of the luminance of the image's lit and dark halves, the lit one being where `linear`
// (direct light included) is larger; an eighth of the width on each side of the middle is
// left out.
struct Halves {
  double lit = 0.0;
  double dark = 0.0;
};
Halves image_halves(const RenderedImage& image, const RenderedImage& linear) {
  const uint32_t w = image.width;
  double left = 0.0, right = 0.0, left_direct = 0.0, right_direct = 0.0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t c = 0; c < w / 2 - w / 8; ++c) {
      const size_t row = static_cast<size_t>(y) * w;
      left += image::luminance(&image.rgba[(row + c) * 4]);
      right += image::luminance(&image.rgba[(row + w - 1 - c) * 4]);
      left_direct += image::luminance(&linear.rgba[(row + c) * 4]);
      right_direct += image::luminance(&linear.rgba[(row + w - 1 - c) * 4]);
    }
  }
  return left_direct > right_direct ? Halves{left, right} : Halves{right, left};
}

}  // namespace

void expect_thin_wall_in_one_voxel_sends_nothing_through(const VoxelGiSetup& gi) {
  const double fraction = kThinWallLeak;
  // The floor spans 2 m, so one dense level's voxel is 2 / (R - 4) (moved_on_the_voxel_grid)
  // and x = 0 lies on a voxel face: the wall's faces straddle the middle of the voxel
  // [0, voxel).
  const float voxel = 2.0f / (static_cast<float>(gi.voxel_resolution) - 4.0f);
  const float x = 0.5f * voxel;
  scene::SceneBuilder b("thin_wall_in_one_voxel");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
  b.add_quad("wall_minus_x", {x - 0.0005f, 0, -1}, {0, 0, 2}, {0, 1, 0}, white);
  b.add_quad("wall_plus_x", {x + 0.0005f, 0, -1}, {0, 1, 0}, {0, 0, 2}, white);
  b.add_light(point_light(5.0f), {-0.5f, 0.6f, 0});
  b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  const scene::Scene scene = b.finish();
  const uint32_t size = 32;
  RenderHarness harness(voxel_gi_render_setup(gi, scene, size));
  harness.render();
  const RenderedImage indirect = harness.output("indirect");
  expect_finite_non_negative(indirect, gi.label + " indirect");
  const Halves rendered = image_halves(indirect, harness.output("linear"));

  RenderHarness reference(path_traced_setup(scene, size, gi.indirect_bounces, 32));
  reference.render(2);
  const Halves traced = image_halves(reference.output("indirect"), reference.output("linear"));
  std::printf(
      "[thin wall in one voxel] %s: lit half %.3f (path traced %.3f, ratio %.4f), dark half "
      "%.3f (path traced %.3f), dark / lit %.4f\n",
      gi.label.c_str(), rendered.lit, traced.lit, rendered.lit / traced.lit, rendered.dark,
      traced.dark, rendered.dark / rendered.lit);
  EXPECT_NEAR(rendered.lit / traced.lit, 1.0, kThinWallLitTolerance) << gi.label;
  EXPECT_LT(rendered.dark, fraction * rendered.lit) << gi.label;
}

namespace {

// Prints one closed-form case's ratios under `tag` and expects their mean within `tolerance`.
void expect_mean_ratio_near_one(const char* tag, const VoxelGiSetup& gi,
                                const std::string& case_label, const IndirectComparison& c,
                                double tolerance) {
  std::printf("[%s] %s, %s: analytic %.5f, mean ratio %.4f (per placement%s)\n", tag,
              gi.label.c_str(), case_label.c_str(), c.expected, c.mean_ratio(), c.ratios().c_str());
  EXPECT_NEAR(c.mean_ratio(), 1.0, tolerance) << gi.label << ", " << case_label;
}

}  // namespace

void expect_lit_square_matches_closed_form(const VoxelGiSetup& gi, SquareLight light,
                                           double tolerance, double units_per_metre) {
  ASSERT_EQ(gi.indirect_bounces, 1) << "the closed form is for one bounce";
  for (double height : kReceiverHeights) {
    const LitSquare square{light, height, false, units_per_metre};
    expect_mean_ratio_near_one("lit square", gi, square.label(), compare_lit_square(gi, square),
                               tolerance);
  }
}

void expect_receiver_before_a_lit_wall_matches_closed_form(const VoxelGiSetup& gi,
                                                           double tolerance) {
  ASSERT_EQ(gi.indirect_bounces, 1) << "the closed form is for one bounce";
  for (const LitWall& wall : kLitWalls) {
    expect_mean_ratio_near_one("lit wall", gi, wall.label(), compare_lit_wall(gi, wall), tolerance);
  }
}

void expect_lit_box_matches_radiosity(const VoxelGiSetup& gi, const BoxRadiosity& radiosity,
                                      double tolerance) {
  const IndirectComparison c = compare_lit_box(gi, radiosity);
  std::printf(
      "[lit box] %s (%d indirect bounces): radiosity %.5f, mean ratio %.4f (per "
      "placement%s)\n",
      gi.label.c_str(), gi.indirect_bounces, c.expected, c.mean_ratio(), c.ratios().c_str());
  EXPECT_NEAR(c.mean_ratio(), 1.0, tolerance) << gi.label;
}

std::vector<EnergyBoundScene> energy_bound_scenes() {
  // Cornell box: measured 0.94 to 0.97 for vct (32^3 and 64^3, 4 to 16 cones, refine 0 to 3).
  // Thin wall: measured 1.15 to 1.25 for vct with the default refine 2 (1.34 with refine 1,
  // 1.48 with refine 0: a sample's texel behind the lit face no longer dilutes its light,
  // docs/error-budget.md, twenty-seventh round; 1.41 to 1.51 in the tenth round, 1.46 to 1.83
  // before voxels sent each side the share of their surfaces facing it).
  // The two faces of the 1 mm wall straddle a voxel face and fall in different voxels, so the
  // light shares leave it where it was; the excess left has another cause, not yet found
  // (docs/error-budget.md, "What is left").
  // The voxel bounces of dvs on the Cornell box add 0.89 to 1.01 of what the path tracer's next
  // bounce adds (0.49 to 0.80 while they sampled the volumes with anisotropic filtering,
  // docs/error-budget.md, thirteenth round). On the thin wall they add 1.6 to 3.5 times what
  // the path tracer's second and third bounces add, the same excess fed back, and those are
  // within their noise of zero.
  return {{"cornell_point_light", cornell_lit_by_its_point_light, 0.20, 0.20},
          {"thin_wall", [] { return thin_wall(); }, 1.0, 2.5}};
}

void expect_within_energy_bound(const std::string& label, double rendered,
                                const PathTracedMean& reference, double tolerance) {
  const double ratio = rendered / reference.luminance;
  std::printf(
      "[energy bound] %s: mean indirect %.5f, path traced %.5f (standard error %.2f%%), "
      "ratio %.4f\n",
      label.c_str(), rendered, reference.luminance,
      100.0 * reference.standard_error / reference.luminance, ratio);
  EXPECT_LE(rendered, (1.0 + tolerance) * reference.luminance) << label;
}

}  // namespace voxgi::test
