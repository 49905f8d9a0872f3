#include "engine/runtime/output_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "engine/runtime/graph_instance.hpp"

namespace voxgi::runtime {

namespace fs = std::filesystem;

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path temp = path.string() + ".tmp";
  {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
    out << text;
    if (!out) throw std::runtime_error(path.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw std::runtime_error(path.string() + ": cannot write: " + ec.message());
  }
}

std::vector<fs::path> write_outputs(GraphInstance& graph, const fs::path& stem) {
  if (stem.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(stem.parent_path(), ec);
    if (ec) {
      throw std::runtime_error(stem.parent_path().string() +
                               ": cannot create the output folder: " + ec.message());
    }
  }
  std::vector<fs::path> written;
  for (const auto& [name, resource] : graph.compiled().outputs) {
    if (name.rfind("viewer.", 0) == 0) continue;
    const graph::CompiledResource& r = graph.compiled().resources[static_cast<size_t>(resource)];
    if (r.info.kind == graph::ResourceKind::Buffer) continue;
    const image::ImageRGBA32F picture = graph.read(name);
    fs::path file;
    if (name == "display") {
      file = stem.string() + ".png";
      image::write_png(file, picture);
    } else {
      file = stem.string() + (name == "linear" ? "" : "-" + name) + ".exr";
      image::write_exr(file, picture);
    }
    written.push_back(file);
  }
  return written;
}

image::ImageRGBA32F difference(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b,
                               float gain) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("difference: images of different sizes (" +
                                std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  }
  image::ImageRGBA32F d(a.width, a.height);
  for (size_t i = 0; i < d.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c)
      d.pixels[i + c] = std::abs(a.pixels[i + c] - b.pixels[i + c]) * gain;
    d.pixels[i + 3] = 1.0f;
  }
  return d;
}

DifferenceStats difference_stats(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b) {
  const image::ImageRGBA32F d = difference(a, b);
  DifferenceStats stats;
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < d.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float v = d.pixels[i + c];
      stats.max_abs = std::max(stats.max_abs, std::isfinite(v) ? v : INFINITY);
      sum += v;
      ++count;
    }
  }
  stats.mean_abs = count ? sum / static_cast<double>(count) : 0.0;
  return stats;
}

uint32_t level_count(const graph::ResourceInfo& info) {
  return info.kind == graph::ResourceKind::Clipmap ? std::max(1u, info.clipmap_levels) : 1u;
}

uint32_t slice_count(const graph::ResourceInfo& info) {
  if (info.kind == graph::ResourceKind::Clipmap) {
    return info.extent.depth / std::max(1u, info.clipmap_levels);
  }
  return std::max(1u, info.extent.depth);
}

image::ImageRGBA32F slice_of(const graph::ResourceInfo& info, const std::vector<float>& texels,
                             uint32_t level, uint32_t slice) {
  const uint32_t w = info.extent.width, h = info.extent.height;
  const uint32_t levels = level_count(info);
  const uint32_t slices = slice_count(info);
  level = std::min(level, levels - 1);
  slice = std::min(slice, slices - 1);
  const size_t z = static_cast<size_t>(level) * slices + slice;
  const size_t plane = static_cast<size_t>(w) * h * 4;
  if (texels.size() < (z + 1) * plane) {
    throw std::invalid_argument("slice_of('" + info.name + "'): " + std::to_string(texels.size()) +
                                " values are too few for slice " + std::to_string(z));
  }
  image::ImageRGBA32F out(w, h);
  std::copy(texels.begin() + static_cast<std::ptrdiff_t>(z * plane),
            texels.begin() + static_cast<std::ptrdiff_t>((z + 1) * plane), out.pixels.begin());
  return out;
}

}  // namespace voxgi::runtime
