#include "engine/color/display_transform.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace OCIO = OCIO_NAMESPACE;

namespace voxgi::color {

struct DisplayTransform::Impl {
  std::filesystem::path path;
  OCIO::ConstConfigRcPtr config;

  [[noreturn]] void fail(const std::string& what) const {
    throw ColorError(path.string() + ": " + what);
  }

  OCIO::ConstCPUProcessorRcPtr processor(const std::string& display,
                                         const std::string& view) const {
    check(display, view);
    try {
      OCIO::DisplayViewTransformRcPtr transform = OCIO::DisplayViewTransform::Create();
      transform->setSrc(OCIO::ROLE_SCENE_LINEAR);
      transform->setDisplay(display.c_str());
      transform->setView(view.c_str());
      return config->getProcessor(transform)->getOptimizedCPUProcessor(
          OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    } catch (const OCIO::Exception& e) {
      fail("display \"" + display + "\", view \"" + view + "\": " + e.what());
    }
  }

  std::vector<std::string> displays() const {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumDisplays(); ++i) names.emplace_back(config->getDisplay(i));
    return names;
  }

  std::vector<std::string> views(const std::string& display) const {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumViews(display.c_str()); ++i) {
      names.emplace_back(config->getView(display.c_str(), i));
    }
    return names;
  }

  static std::string list(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
    return out;
  }

  void check(const std::string& display, const std::string& view) const {
    const auto all = displays();
    if (std::find(all.begin(), all.end(), display) == all.end()) {
      fail("display \"" + display + "\" not found; valid displays: " + list(all));
    }
    const auto valid = views(display);
    if (std::find(valid.begin(), valid.end(), view) == valid.end()) {
      fail("view \"" + view + "\" not found for display \"" + display +
           "\"; valid views: " + list(valid));
    }
  }
};

DisplayTransform::DisplayTransform(const std::filesystem::path& config) : impl_(new Impl) {
  impl_->path = config;
  std::error_code ec;
  if (!std::filesystem::exists(config, ec)) impl_->fail("OCIO config file does not exist");
  try {
    impl_->config = OCIO::Config::CreateFromFile(config.c_str());
    impl_->config->validate();
  } catch (const OCIO::Exception& e) {
    impl_->fail(std::string("cannot load the OCIO config: ") + e.what());
  }
  if (!impl_->config->getColorSpace(OCIO::ROLE_SCENE_LINEAR)) {
    impl_->fail("the config has no scene_linear role");
  }
}

DisplayTransform::~DisplayTransform() = default;
DisplayTransform::DisplayTransform(DisplayTransform&&) noexcept = default;
DisplayTransform& DisplayTransform::operator=(DisplayTransform&&) noexcept = default;

std::filesystem::path DisplayTransform::default_config_path() {
  if (const char* env = std::getenv("VOXGI_OCIO_CONFIG"); env && *env) return env;
  return VOXGI_OCIO_CONFIG_DEFAULT;
}

const std::filesystem::path& DisplayTransform::config_path() const {
  return impl_->path;
}

std::vector<std::string> DisplayTransform::displays() const {
  return impl_->displays();
}

std::vector<std::string> DisplayTransform::views(const std::string& display) const {
  const auto all = impl_->displays();
  if (std::find(all.begin(), all.end(), display) == all.end()) {
    impl_->fail("display \"" + display + "\" not found; valid displays: " + Impl::list(all));
  }
  return impl_->views(display);
}

namespace {

// Inverse of the shaper at texel i of n.
float texel_value(uint32_t i, uint32_t n, float min_log2, float max_log2) {
  if (i == 0) return 0.0f;
  const float u = float(i - 1) / float(n - 2);  // texel 1 → min_log2, texel n-1 → max_log2
  return std::exp2(min_log2 + u * (max_log2 - min_log2));
}

}  // namespace

DisplayTransform::Lut DisplayTransform::bake(const std::string& display, const std::string& view,
                                             uint32_t size) const {
  if (size < 3 || size > 256) {
    impl_->fail("bake(\"" + display + "\", \"" + view + "\"): LUT size " + std::to_string(size) +
                " out of range, expected 3..256");
  }
  const OCIO::ConstCPUProcessorRcPtr processor = impl_->processor(display, view);
  Lut lut;
  lut.size = size;
  std::vector<float> axis(size);
  for (uint32_t i = 0; i < size; ++i) {
    axis[i] = texel_value(i, size, lut.shaper_min_log2, lut.shaper_max_log2);
  }
  lut.rgba.resize(size_t(size) * size * size * 4);
  size_t p = 0;
  for (uint32_t b = 0; b < size; ++b) {
    for (uint32_t g = 0; g < size; ++g) {
      for (uint32_t r = 0; r < size; ++r) {
        lut.rgba[p++] = axis[r];
        lut.rgba[p++] = axis[g];
        lut.rgba[p++] = axis[b];
        lut.rgba[p++] = 1.0f;
      }
    }
  }
  OCIO::PackedImageDesc image(lut.rgba.data(), long(size) * size, long(size), 4);
  processor->apply(image);
  return lut;
}

glm::vec3 DisplayTransform::apply_cpu(const std::string& display, const std::string& view,
                                      glm::vec3 linear) const {
  float rgb[3] = {linear.r, linear.g, linear.b};
  impl_->processor(display, view)->applyRGB(rgb);
  return glm::vec3(rgb[0], rgb[1], rgb[2]);
}

float DisplayTransform::shaper(const Lut& lut, float linear) {
  const float x = linear > 0.0f ? linear : 0.0f;  // also maps NaN to 0
  const float d = 1.0f / float(lut.size - 1);
  const float lo = std::exp2(lut.shaper_min_log2);
  float t;
  if (x < lo) {
    t = d * x / lo;
  } else {
    t = d + (1.0f - d) * (std::log2(x) - lut.shaper_min_log2) /
                (lut.shaper_max_log2 - lut.shaper_min_log2);
  }
  return std::min(t, 1.0f);
}

glm::vec3 DisplayTransform::apply_lut(const Lut& lut, glm::vec3 linear) {
  const uint32_t n = lut.size;
  if (n < 2 || lut.rgba.size() != size_t(n) * n * n * 4) return glm::vec3(0.0f);
  // A texture lookup at coord = t * (n-1)/n + 0.5/n with linear filtering lands between
  // texels floor(t * (n-1)) and the next one: the same as this.
  float position[3];
  uint32_t i0[3], i1[3];
  float f[3];
  for (int c = 0; c < 3; ++c) {
    position[c] = shaper(lut, linear[c]) * float(n - 1);
    const float base = std::floor(position[c]);
    i0[c] = std::min(uint32_t(base), n - 1);
    i1[c] = std::min(i0[c] + 1, n - 1);
    f[c] = position[c] - base;
  }
  auto texel = [&](uint32_t r, uint32_t g, uint32_t b) {
    const float* p = lut.rgba.data() + ((size_t(b) * n + g) * n + r) * 4;
    return glm::vec3(p[0], p[1], p[2]);
  };
  const glm::vec3 c00 = glm::mix(texel(i0[0], i0[1], i0[2]), texel(i1[0], i0[1], i0[2]), f[0]);
  const glm::vec3 c10 = glm::mix(texel(i0[0], i1[1], i0[2]), texel(i1[0], i1[1], i0[2]), f[0]);
  const glm::vec3 c01 = glm::mix(texel(i0[0], i0[1], i1[2]), texel(i1[0], i0[1], i1[2]), f[0]);
  const glm::vec3 c11 = glm::mix(texel(i0[0], i1[1], i1[2]), texel(i1[0], i1[1], i1[2]), f[0]);
  return glm::mix(glm::mix(c00, c10, f[1]), glm::mix(c01, c11, f[1]), f[2]);
}

}  // namespace voxgi::color
