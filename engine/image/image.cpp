#include "engine/image/image.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <png.h>
#include <stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>

namespace voxgi::image {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason) {
  throw ImageError(path.string() + ": " + reason);
}

void check_image(const std::filesystem::path& path, const ImageRGBA32F& image) {
  if (image.width == 0 || image.height == 0) fail(path, "image is empty (width or height 0)");
  if (image.pixels.size() != size_t(image.width) * image.height * 4) {
    fail(path, "pixel array holds " + std::to_string(image.pixels.size()) +
                   " floats, expected width × height × 4 = " +
                   std::to_string(size_t(image.width) * image.height * 4));
  }
}

// A temporary file next to `target` that replaces it on commit() and is removed otherwise.
class AtomicWrite {
 public:
  explicit AtomicWrite(const std::filesystem::path& target) : target_(target) {
    std::error_code ec;
    const std::filesystem::path parent =
        target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::exists(parent, ec)) {
      fail(target, "directory " + parent.string() + " does not exist");
    }
    if (!std::filesystem::is_directory(parent, ec)) {
      fail(target, parent.string() + " is not a directory");
    }
    if (std::filesystem::is_directory(target, ec)) fail(target, "is a directory");
    static std::atomic<unsigned> counter{0};
    std::string name = ".";
    name.append(target.filename().string());
    name.append(".tmp-");
    name.append(std::to_string(getpid()));
    name.append("-");
    name.append(std::to_string(counter++));
    temp_ = parent / name;
  }
  ~AtomicWrite() {
    if (!committed_) {
      std::error_code ec;
      std::filesystem::remove(temp_, ec);
    }
  }
  AtomicWrite(const AtomicWrite&) = delete;
  AtomicWrite& operator=(const AtomicWrite&) = delete;

  const std::filesystem::path& temp() const { return temp_; }

  // Opens the temporary file, so that "permission denied" and the like name their cause.
  std::FILE* open() const {
    std::FILE* file = std::fopen(temp_.c_str(), "wb");
    if (!file)
      fail(target_, std::string("cannot create a file in its directory: ") + std::strerror(errno));
    return file;
  }

  void commit() {
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) fail(target_, "cannot replace the file: " + ec.message());
    committed_ = true;
  }

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

uint8_t to_byte(float v) {
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(std::lround(v * 255.0f));
}

std::vector<uint8_t> read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file does not exist");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<uint8_t> bytes;
  uint8_t chunk[65536];
  size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof(chunk), file)) > 0)
    bytes.insert(bytes.end(), chunk, chunk + n);
  const bool error = std::ferror(file);
  std::fclose(file);
  if (error) fail(path, "read error");
  return bytes;
}

// Channel names of one layer: R, G, B, A (or Y) in a part.
struct LayerChannels {
  int part = 0;
  std::map<std::string, std::string> channel;  // "R" → full channel name
};

// Layer name of a channel "a.b.R" → "a.b"; bare "R" → "".
std::pair<std::string, std::string> split_channel(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos) return {"", name};
  return {name.substr(0, dot), name.substr(dot + 1)};
}

std::map<std::string, LayerChannels> collect_layers(Imf::MultiPartInputFile& file) {
  std::map<std::string, LayerChannels> layers;
  for (int p = 0; p < file.parts(); ++p) {
    const Imf::Header& header = file.header(p);
    const std::string part_name = header.hasName() ? header.name() : "";
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      auto [layer, suffix] = split_channel(it.name());
      if (suffix != "R" && suffix != "G" && suffix != "B" && suffix != "A" && suffix != "Y") {
        continue;
      }
      // Bare channels of a named part form the layer named after the part.
      if (layer.empty() && !part_name.empty() && file.parts() > 1) layer = part_name;
      LayerChannels& entry = layers[layer];
      if (entry.channel.empty()) entry.part = p;
      if (entry.part == p) entry.channel[suffix] = it.name();
    }
  }
  return layers;
}

}  // namespace

void write_png(const std::filesystem::path& path, const ImageRGBA32F& display_referred) {
  check_image(path, display_referred);
  std::vector<uint8_t> bytes(display_referred.pixels.size());
  std::transform(display_referred.pixels.begin(), display_referred.pixels.end(), bytes.begin(),
                 to_byte);
  AtomicWrite write(path);
  std::FILE* file = write.open();
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = display_referred.width;
  png.height = display_referred.height;
  png.format = PNG_FORMAT_RGBA;
  const int ok = png_image_write_to_stdio(&png, file, 0, bytes.data(), 0, nullptr);
  const std::string message = png.message;
  png_image_free(&png);
  const bool closed = std::fclose(file) == 0;
  if (!ok) fail(path, "PNG encoding failed: " + message);
  if (!closed) fail(path, std::string("write failed: ") + std::strerror(errno));
  write.commit();
}

void write_exr(const std::filesystem::path& path, const ImageRGBA32F& linear, ExrPixelType type) {
  check_image(path, linear);
  AtomicWrite write(path);
  std::fclose(write.open());
  try {
    const int w = static_cast<int>(linear.width), h = static_cast<int>(linear.height);
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const char* names[4] = {"R", "G", "B", "A"};
    // OpenEXR converts pixel types when reading but not when writing: half files need a
    // half frame buffer.
    std::vector<Imath::half> halves;
    char* base = nullptr;
    size_t component = 0;
    if (type == ExrPixelType::Half) {
      // Finite values beyond the half range saturate instead of turning into Inf.
      halves.reserve(linear.pixels.size());
      for (float v : linear.pixels) {
        halves.emplace_back(std::isfinite(v) ? std::clamp(v, -65504.0f, 65504.0f) : v);
      }
      base = reinterpret_cast<char*>(halves.data());
      component = sizeof(Imath::half);
    } else {
      base = const_cast<char*>(reinterpret_cast<const char*>(linear.pixels.data()));
      component = sizeof(float);
    }
    const Imf::PixelType pixel = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
    for (int c = 0; c < 4; ++c) {
      header.channels().insert(names[c], Imf::Channel(pixel));
      frame.insert(names[c], Imf::Slice(pixel, base + size_t(c) * component, 4 * component,
                                        4 * component * size_t(w)));
    }
    Imf::OutputFile file(write.temp().c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(h);
  } catch (const std::exception& e) {
    fail(path, std::string("EXR write failed: ") + e.what());
  }
  write.commit();
}

std::vector<std::string> exr_layers(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file does not exist");
  try {
    Imf::MultiPartInputFile file(path.c_str());
    std::vector<std::string> names;
    for (const auto& [name, channels] : collect_layers(file)) {
      if (channels.channel.count("R") || channels.channel.count("Y")) names.push_back(name);
    }
    return names;
  } catch (const ImageError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, std::string("not a readable EXR file: ") + e.what());
  }
}

ImageRGBA32F read_exr(const std::filesystem::path& path, std::string_view layer) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file does not exist");
  try {
    Imf::MultiPartInputFile file(path.c_str());
    const auto layers = collect_layers(file);
    auto usable = [](const LayerChannels& l) {
      return (l.channel.count("R") && l.channel.count("G") && l.channel.count("B")) ||
             l.channel.count("Y");
    };
    const LayerChannels* chosen = nullptr;
    const std::string wanted(layer);
    for (const auto& [name, channels] : layers) {
      if (!usable(channels)) continue;
      const bool match = name == wanted || (!wanted.empty() && name.size() > wanted.size() &&
                                            name.ends_with("." + wanted));
      if (match) {
        chosen = &channels;
        break;
      }
    }
    if (!chosen && wanted.empty()) {
      if (auto it = layers.find("Combined"); it != layers.end() && usable(it->second)) {
        chosen = &it->second;
      }
    }
    if (!chosen) {
      std::string names;
      for (const auto& [name, channels] : layers) {
        if (usable(channels)) names += (names.empty() ? "\"" : ", \"") + name + "\"";
      }
      fail(path, "layer \"" + wanted + "\" not found; the file has layers " + names);
    }
    Imf::InputPart part(file, chosen->part);
    const Imath::Box2i window = part.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    if (w <= 0 || h <= 0) fail(path, "empty data window");
    ImageRGBA32F image{uint32_t(w), uint32_t(h)};
    Imf::FrameBuffer frame;
    // The slice base is offset so that the data window's corner lands on pixel (0, 0).
    char* base =
        reinterpret_cast<char*>(image.pixels.data()) -
        (ptrdiff_t(window.min.x) + ptrdiff_t(window.min.y) * w) * 4 * ptrdiff_t(sizeof(float));
    const size_t xs = 4 * sizeof(float), ys = xs * size_t(w);
    const auto& ch = chosen->channel;
    const bool grey = !ch.count("R");
    const char* suffixes[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      frame.insert(grey ? ch.at("Y") : ch.at(suffixes[c]),
                   Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
      if (grey) break;
    }
    frame.insert(ch.count("A") ? ch.at("A") : std::string("__voxgi_missing_alpha"),
                 Imf::Slice(Imf::FLOAT, base + 3 * sizeof(float), xs, ys, 1, 1, 1.0));
    part.setFrameBuffer(frame);
    part.readPixels(window.min.y, window.max.y);
    if (grey) {
      for (size_t p = 0; p < image.pixels.size(); p += 4) {
        image.pixels[p + 1] = image.pixels[p + 2] = image.pixels[p];
      }
    }
    return image;
  } catch (const ImageError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, std::string("not a readable EXR file: ") + e.what());
  }
}

ImageRGBA32F read_png(const std::filesystem::path& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0) {
    fail(path, "not a PNG file (bad signature)");
  }
  const int size = static_cast<int>(std::min<size_t>(bytes.size(), INT32_MAX));
  int w = 0, h = 0, comp = 0;
  ImageRGBA32F image;
  if (stbi_is_16_bit_from_memory(bytes.data(), size)) {
    stbi_us* data = stbi_load_16_from_memory(bytes.data(), size, &w, &h, &comp, 4);
    if (!data) fail(path, std::string("PNG decoding failed: ") + stbi_failure_reason());
    image = ImageRGBA32F(uint32_t(w), uint32_t(h));
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = data[i] / 65535.0f;
    stbi_image_free(data);
  } else {
    stbi_uc* data = stbi_load_from_memory(bytes.data(), size, &w, &h, &comp, 4);
    if (!data) fail(path, std::string("PNG decoding failed: ") + stbi_failure_reason());
    image = ImageRGBA32F(uint32_t(w), uint32_t(h));
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = data[i] / 255.0f;
    stbi_image_free(data);
  }
  return image;
}

bool has_non_finite(const ImageRGBA32F& image, size_t* count) {
  size_t bad = 0;
  for (size_t p = 0; p + 3 < image.pixels.size(); p += 4) {
    if (!std::isfinite(image.pixels[p]) || !std::isfinite(image.pixels[p + 1]) ||
        !std::isfinite(image.pixels[p + 2]) || !std::isfinite(image.pixels[p + 3])) {
      ++bad;
    }
  }
  if (count) *count = bad;
  return bad > 0;
}

}  // namespace voxgi::image
