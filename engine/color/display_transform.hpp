#pragma once
// Scene-linear → display code values through an OpenColorIO config, evaluated exactly on the
// CPU or baked into a shaper + 3D LUT for shaders (shaders/lib/display_lut.glsl).

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxgi::color {

// Names the config path and, for a bad display or view, lists the valid ones.
class ColorError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class DisplayTransform {
 public:
  // The LUT's input shaper, per channel, for x = max(linear, 0):
  //   lo = 2^shaper_min_log2, d = 1 / (size - 1)
  //   t = x < lo ? d * x / lo                                                   (linear, black
  //   stays 0)
  //             : d + (1 - d) * (log2(x) - shaper_min_log2) / (shaper_max_log2 - shaper_min_log2)
  //   t = min(t, 1)
  // so texel 0 holds x = 0, texel 1 holds x = lo, and the other texels are spaced evenly in
  // log2 up to 2^shaper_max_log2. The default range -14..+7 with 65 texels is 1/3 stop per
  // texel and puts x = 1 exactly on a texel, so the clamp of the Standard view has no
  // interpolation error.
  struct Lut {
    uint32_t size = 0;
    std::vector<float> rgba;  // size³ RGBA32F, r fastest, then g, then b
    float shaper_min_log2 = -14.0f;
    float shaper_max_log2 = 7.0f;
  };

  explicit DisplayTransform(const std::filesystem::path& config = default_config_path());
  ~DisplayTransform();
  DisplayTransform(DisplayTransform&&) noexcept;
  DisplayTransform& operator=(DisplayTransform&&) noexcept;

  // $VOXGI_OCIO_CONFIG when set, else the config shipped in third_party_config/ocio.
  static std::filesystem::path default_config_path();
  const std::filesystem::path& config_path() const;

  std::vector<std::string> displays() const;
  std::vector<std::string> views(const std::string& display) const;

  Lut bake(const std::string& display, const std::string& view, uint32_t size = 65) const;
  // The OCIO CPU processor: the ground truth the LUT approximates.
  glm::vec3 apply_cpu(const std::string& display, const std::string& view, glm::vec3 linear) const;
  // Exactly the shader's math: shaper, then trilinear filtering between texel centres.
  static glm::vec3 apply_lut(const Lut& lut, glm::vec3 linear);
  // The shaper alone (linear value → LUT coordinate in [0, 1]).
  static float shaper(const Lut& lut, float linear);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi::color
