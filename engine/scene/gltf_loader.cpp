#include "engine/scene/gltf_loader.hpp"

#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>

#include "engine/scene/geometry.hpp"
#include "engine/scene/gltf_normalize.hpp"

namespace voxgi::scene {

namespace {

constexpr int kModeTriangles = 4;
constexpr int kModeTriangleStrip = 5;
constexpr int kModeTriangleFan = 6;

// Triangle list of a strip or fan (glTF 2.0, 3.7.2.1: strip triangle i is
// {p_i, p_(i+1+i%2), p_(i+2-i%2)}, fan triangle i is {p_(i+1), p_(i+2), p_0}).
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& indices, int mode) {
  std::vector<uint32_t> list;
  if (indices.size() < 3) return list;
  list.reserve((indices.size() - 2) * 3);
  for (size_t i = 0; i + 2 < indices.size(); ++i) {
    if (mode == kModeTriangleStrip) {
      list.insert(list.end(), {indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]});
    } else {
      list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
    }
  }
  return list;
}

// Decodes embedded and external images with stb_image, keeping bit depth and channel count.
// Unlike tinygltf's default loader, an image that does not decode is a warning, not a
// failed load: the textures that use it are dropped later.
bool decode_image(tinygltf::Image* image, const int index, std::string*, std::string* warn, int,
                  int, const unsigned char* bytes, int size, void*) {
  int w = 0, h = 0, comp = 0;
  void* data = nullptr;
  int bits = 8;
  if (stbi_is_16_bit_from_memory(bytes, size)) {
    data = stbi_load_16_from_memory(bytes, size, &w, &h, &comp, 0);
    bits = 16;
  }
  if (!data) {
    data = stbi_load_from_memory(bytes, size, &w, &h, &comp, 0);
    bits = 8;
  }
  if (!data || w < 1 || h < 1 || comp < 1 || comp > 4) {
    if (warn) {
      *warn += "images[" + std::to_string(index) + "] \"" + image->name + "\": cannot decode (" +
               (stbi_failure_reason() ? stbi_failure_reason() : "?") + ")\n";
    }
    if (data) stbi_image_free(data);
    image->image.clear();
    return true;
  }
  const size_t byte_count = size_t(w) * size_t(h) * size_t(comp) * size_t(bits / 8);
  image->width = w;
  image->height = h;
  image->component = comp;
  image->bits = bits;
  image->pixel_type =
      bits == 16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  const auto* begin = static_cast<const unsigned char*>(data);
  image->image.assign(begin, begin + byte_count);
  stbi_image_free(data);
  return true;
}

// The files a glTF's buffer and image URIs name. Only regular files of at most 4 GiB are read:
// a URI that names a folder or a device would otherwise be "read" as a file of absurd size.
constexpr uintmax_t kMaxReferencedFileBytes = uintmax_t{4} << 30;

bool read_referenced_file(std::vector<unsigned char>* out, std::string* err,
                          const std::string& path, void*) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::is_regular_file(status)) {
    if (err) {
      *err += "'" + path + "' is " +
              (std::filesystem::is_directory(status) ? "a folder" : "not a regular file") +
              ", expected a file\n";
    }
    return false;
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxReferencedFileBytes) {
    if (err) *err += "'" + path + "' is larger than 4 GiB\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(static_cast<size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    if (err) *err += "'" + path + "' could not be read\n";
    return false;
  }
  return true;
}

size_t component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

// One component as float; normalized integers map to [0,1] / [-1,1] as the glTF spec says.
float read_component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float v = float(*p);
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = float(static_cast<int8_t>(*p));
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default:
      return 0.0f;
  }
}

uint32_t read_index(const unsigned char* p, int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

class Loader {
 public:
  explicit Loader(std::filesystem::path path) : path_(std::move(path)) {}

  Scene load() {
    parse_file();
    scene_.name = path_.stem().string();
    scene_.source = path_.string();
    check_extensions();
    load_nodes();
    load_materials();
    load_meshes();
    expand_gpu_instancing();
    load_lights_and_cameras();
    load_animations();
    scene_.update_transforms();
    finish_cameras();
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw SceneError(path_.string() + ": " + field + ": " + what);
  }

  void warn(const std::string& message) { scene_.warnings.push_back(message); }

  void check_index(int index, size_t size, const std::string& field, const char* what) const {
    if (index < 0 || static_cast<size_t>(index) >= size) {
      fail(field, std::string(what) + " " + std::to_string(index) + " out of range (" +
                      std::to_string(size) + " " + what + "s)");
    }
  }

  // Documents the specification allows and the parser refuses, rewritten (gltf_normalize).
  // The JSON of a .gltf, or of a GLB's JSON chunk ("" when the container is malformed: the
  // parser says what is wrong).
  static std::string json_text_of(const std::vector<unsigned char>& bytes, bool binary) {
    if (!binary) return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    uint32_t json_length = 0;
    if (bytes.size() < 20) return {};
    std::memcpy(&json_length, bytes.data() + 12, sizeof json_length);
    if (size_t{json_length} > bytes.size() - 20) return {};
    return std::string(reinterpret_cast<const char*>(bytes.data()) + 20, json_length);
  }

  void rewrite_what_the_parser_refuses(std::vector<unsigned char>& bytes, bool binary) {
    const std::string text = json_text_of(bytes, binary);
    if (text.empty()) return;
    const std::optional<NormalizedGltf> normalized = normalize_gltf_json(text, binary);
    if (!normalized || !normalized->changed) return;
    if (binary) {
      std::optional<std::vector<unsigned char>> rebuilt = replace_glb_json(bytes, normalized->json);
      if (!rebuilt) return;
      bytes = std::move(*rebuilt);
    } else {
      bytes.assign(normalized->json.begin(), normalized->json.end());
    }
    for (const std::string& w : normalized->warnings) warn(w);
  }

  void parse_file() {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) fail("file", "does not exist");
    if (std::filesystem::is_directory(path_, ec))
      fail("file", "is a directory, expected a .gltf or .glb file");
    std::ifstream file(path_, std::ios::binary);
    if (!file) fail("file", "cannot be opened for reading");
    char header[12] = {};
    file.read(header, sizeof header);
    const std::streamsize header_bytes = file.gcount();
    const bool binary = header_bytes >= 4 && std::memcmp(header, "glTF", 4) == 0;
    file.close();
    // A cut-off download or copy is the usual broken GLB; tinygltf only says "Invalid glTF
    // binary", so compare the file with the length its header declares.
    if (binary) {
      const uintmax_t size = std::filesystem::file_size(path_, ec);
      if (header_bytes < static_cast<std::streamsize>(sizeof header)) {
        fail("glb", "truncated: " + std::to_string(header_bytes) +
                        " bytes, shorter than the 12-byte GLB header");
      }
      uint32_t declared = 0;
      std::memcpy(&declared, header + 8, sizeof declared);
      if (!ec && size < declared) {
        fail("glb", "truncated: the header declares " + std::to_string(declared) +
                        " bytes but the file has " + std::to_string(size));
      }
    }

    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(decode_image, nullptr);
    gltf.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &read_referenced_file,
                         &tinygltf::WriteWholeFile, nullptr});
    std::string err, warning;
    std::vector<unsigned char> bytes;
    if (!read_referenced_file(&bytes, &err, path_.string(), nullptr)) {
      fail("file", err.empty() ? std::string("cannot be read") : err);
    }
    rewrite_what_the_parser_refuses(bytes, binary);
    const std::string base_dir = path_.parent_path().string();
    const auto length = static_cast<unsigned int>(bytes.size());
    bool ok = false;
    try {
      ok = binary
               ? gltf.LoadBinaryFromMemory(&model_, &err, &warning, bytes.data(), length, base_dir)
               : gltf.LoadASCIIFromString(&model_, &err, &warning,
                                          reinterpret_cast<const char*>(bytes.data()), length,
                                          base_dir);
    } catch (const std::exception& e) {
      // The parser indexes some of its own arrays unchecked (a node naming a light that the
      // file's light list does not have); say which file and what it was reading.
      fail(binary ? "glb" : "gltf",
           std::string("not a valid glTF 2.0 file: the parser stopped on an inconsistent "
                       "reference (") +
               e.what() + ")");
    }
    std::istringstream warnings(warning);
    for (std::string line; std::getline(warnings, line);) {
      if (!line.empty()) warn(line);
    }
    if (!ok || !err.empty()) {
      // A buffer file that is not there: name the field and the folder looked in.
      const std::vector<std::string> missing =
          missing_referenced_files(json_text_of(bytes, binary), path_.parent_path());
      for (const std::string& m : missing) {
        if (m.rfind("buffers", 0) == 0) {
          const size_t colon = m.find(": ");
          fail(m.substr(0, colon), m.substr(colon + 2));
        }
      }
      while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
      fail(binary ? "glb" : "gltf",
           "not a valid glTF 2.0 file: " + (err.empty() ? std::string("parse failed") : err));
    }
  }

  void check_extensions() {
    static const std::set<std::string> supported = {
        "EXT_mesh_gpu_instancing", "KHR_materials_emissive_strength", "KHR_lights_punctual",
        "KHR_mesh_quantization", "KHR_texture_transform"};
    std::vector<std::string> required, used;
    for (const std::string& ext : model_.extensionsRequired) {
      if (!supported.count(ext)) required.push_back(ext);
    }
    for (const std::string& ext : model_.extensionsUsed) {
      if (!supported.count(ext) &&
          std::find(required.begin(), required.end(), ext) == required.end()) {
        used.push_back(ext);
      }
    }
    // The file says it cannot be read correctly without these (glTF 2.0, 3.12): refuse it.
    if (!required.empty()) {
      fail("extensionsRequired",
           "unsupported extension" + std::string(required.size() > 1 ? "s " : " ") +
               join(required) + ", without which the file cannot be read correctly (supported: " +
               join(std::vector<std::string>(supported.begin(), supported.end())) + ")");
    }
    if (!used.empty()) warn("extensionsUsed: unsupported extensions " + join(used) + " ignored");
  }

  // Reads `accessor` as up to four float components per element (normalized ints are
  // converted); validates every index and byte range first.
  std::vector<glm::vec4> read_accessor(int accessor_index, const std::string& field,
                                       std::initializer_list<int> allowed_types) {
    check_index(accessor_index, model_.accessors.size(), field, "accessor");
    const tinygltf::Accessor& accessor = model_.accessors[size_t(accessor_index)];
    const std::string where = field + " (accessors[" + std::to_string(accessor_index) + "])";
    if (std::find(allowed_types.begin(), allowed_types.end(), accessor.type) ==
        allowed_types.end()) {
      fail(where, "unexpected accessor type " + std::to_string(accessor.type));
    }
    const size_t components = component_count(accessor.type);
    const size_t csize = component_size(accessor.componentType);
    if (components == 0 || components > 4 || csize == 0) {
      fail(where, "unsupported componentType " + std::to_string(accessor.componentType));
    }
    std::vector<glm::vec4> values;
    if (accessor.bufferView >= 0) {
      const unsigned char* base = nullptr;
      size_t stride = 0;
      // Checked against the buffer before anything the size of `count` is allocated.
      view_range(accessor.bufferView, accessor.byteOffset, accessor.count, components * csize,
                 where, base, stride);
      values.assign(accessor.count, glm::vec4(0.0f));
      for (size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* element = base + i * stride;
        for (size_t c = 0; c < components; ++c) {
          values[i][int(c)] =
              read_component(element + c * csize, accessor.componentType, accessor.normalized);
        }
      }
    } else {
      check_zero_accessor_count(accessor.count, where);
      values.assign(accessor.count, glm::vec4(0.0f));
    }
    if (accessor.sparse.isSparse) apply_sparse(accessor, components, csize, where, values);
    return values;
  }

  // An accessor without a bufferView reads as zeros (glTF 2.0, 3.6.2.1), so nothing in the file
  // bounds its count: refuse counts no mesh of a real-time scene has before allocating them.
  void check_zero_accessor_count(size_t count, const std::string& where) {
    constexpr size_t kMaxZeroElements = size_t{1} << 24;
    if (count > kMaxZeroElements) {
      fail(where, "count " + std::to_string(count) + " without a bufferView: more than the " +
                      std::to_string(kMaxZeroElements) + " elements voxgi reads as zeros");
    }
  }

  // Start pointer and stride of `count` elements of `element_size` bytes at `offset` in a
  // buffer view, after checking that they all lie inside the view and its buffer.
  void view_range(int view_index, size_t offset, size_t count, size_t element_size,
                  const std::string& where, const unsigned char*& base, size_t& stride) {
    check_index(view_index, model_.bufferViews.size(), where + ".bufferView", "bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(view_index)];
    const std::string view_field = "bufferViews[" + std::to_string(view_index) + "]";
    check_index(view.buffer, model_.buffers.size(), view_field + ".buffer", "buffer");
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    if (view.byteOffset > buffer.data.size() ||
        view.byteLength > buffer.data.size() - view.byteOffset) {
      fail(view_field, "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                           std::to_string(view.byteLength) + " exceeds buffer size " +
                           std::to_string(buffer.data.size()));
    }
    stride = view.byteStride ? view.byteStride : element_size;
    if (stride < element_size) {
      fail(view_field + ".byteStride", "stride " + std::to_string(stride) +
                                           " smaller than the element size " +
                                           std::to_string(element_size));
    }
    if (count > 0) {
      const size_t needed = offset + (count - 1) * stride + element_size;
      if (needed > view.byteLength || offset > view.byteLength) {
        fail(where, std::to_string(count) + " elements at byteOffset " + std::to_string(offset) +
                        " need " + std::to_string(needed) + " bytes but " + view_field + " has " +
                        std::to_string(view.byteLength));
      }
    }
    base = buffer.data.data() + view.byteOffset + offset;
  }

  void apply_sparse(const tinygltf::Accessor& accessor, size_t components, size_t csize,
                    const std::string& where, std::vector<glm::vec4>& values) {
    const auto count = static_cast<size_t>(std::max(accessor.sparse.count, 0));
    const int index_type = accessor.sparse.indices.componentType;
    const size_t isize = component_size(index_type);
    if (isize == 0 || index_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
      fail(where + ".sparse.indices.componentType", "expected an unsigned integer type");
    }
    const unsigned char* indices = nullptr;
    const unsigned char* data = nullptr;
    size_t istride = 0, vstride = 0;
    view_range(accessor.sparse.indices.bufferView, size_t(accessor.sparse.indices.byteOffset),
               count, isize, where + ".sparse.indices", indices, istride);
    view_range(accessor.sparse.values.bufferView, size_t(accessor.sparse.values.byteOffset), count,
               components * csize, where + ".sparse.values", data, vstride);
    for (size_t i = 0; i < count; ++i) {
      const uint32_t target = read_index(indices + i * isize, index_type);
      if (target >= values.size()) {
        fail(where + ".sparse.indices", "index " + std::to_string(target) + " out of range (" +
                                            std::to_string(values.size()) + " elements)");
      }
      for (size_t c = 0; c < components; ++c) {
        values[target][int(c)] = read_component(data + i * components * csize + c * csize,
                                                accessor.componentType, accessor.normalized);
      }
    }
  }

  std::vector<uint32_t> read_indices(int accessor_index, const std::string& field,
                                     size_t vertex_count) {
    check_index(accessor_index, model_.accessors.size(), field, "accessor");
    const tinygltf::Accessor& accessor = model_.accessors[size_t(accessor_index)];
    const std::string where = field + " (accessors[" + std::to_string(accessor_index) + "])";
    if (accessor.type != TINYGLTF_TYPE_SCALAR) fail(where, "indices must be SCALAR");
    const int ct = accessor.componentType;
    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      fail(where, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " +
                      std::to_string(ct));
    }
    if (accessor.sparse.isSparse) fail(where, "sparse index accessors are not supported");
    if (accessor.bufferView < 0) {
      check_zero_accessor_count(accessor.count, where);
      return std::vector<uint32_t>(accessor.count, 0);
    }
    const unsigned char* base = nullptr;
    size_t stride = 0;
    view_range(accessor.bufferView, accessor.byteOffset, accessor.count, component_size(ct), where,
               base, stride);
    std::vector<uint32_t> indices(accessor.count, 0);
    for (size_t i = 0; i < accessor.count; ++i) {
      indices[i] = read_index(base + i * stride, ct);
      if (indices[i] >= vertex_count) {
        fail(where, "index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                        " out of range (" + std::to_string(vertex_count) + " vertices)");
      }
    }
    return indices;
  }

  void load_nodes() {
    const size_t count = model_.nodes.size();
    scene_.nodes.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const tinygltf::Node& src = model_.nodes[i];
      Node& node = scene_.nodes[i];
      const std::string field = "nodes[" + std::to_string(i) + "]";
      node.name = src.name.empty() ? field : src.name;
      if (src.matrix.size() == 16) {
        glm::mat4 m;
        for (int c = 0; c < 16; ++c) m[c / 4][c % 4] = static_cast<float>(src.matrix[size_t(c)]);
        node.matrix = m;
      } else if (!src.matrix.empty()) {
        fail(field + ".matrix", "expected 16 numbers, got " + std::to_string(src.matrix.size()));
      }
      if (src.translation.size() == 3) {
        node.translation = glm::vec3(src.translation[0], src.translation[1], src.translation[2]);
      } else if (!src.translation.empty()) {
        fail(field + ".translation", "expected 3 numbers");
      }
      if (src.rotation.size() == 4) {
        glm::quat q(float(src.rotation[3]), float(src.rotation[0]), float(src.rotation[1]),
                    float(src.rotation[2]));
        const float len = glm::length(q);
        node.rotation = len > 1e-20f && std::isfinite(len) ? q / len : glm::quat(1, 0, 0, 0);
      } else if (!src.rotation.empty()) {
        fail(field + ".rotation", "expected 4 numbers (quaternion x, y, z, w)");
      }
      if (src.scale.size() == 3) {
        node.scale = glm::vec3(src.scale[0], src.scale[1], src.scale[2]);
      } else if (!src.scale.empty()) {
        fail(field + ".scale", "expected 3 numbers");
      }
      if (src.mesh >= 0) check_index(src.mesh, model_.meshes.size(), field + ".mesh", "mesh");
      node.mesh = src.mesh;
      if (src.skin >= 0) warn(field + ".skin: skinning is not supported, drawn in bind pose");
      for (size_t c = 0; c < src.children.size(); ++c) {
        const int child = src.children[c];
        const std::string child_field = field + ".children[" + std::to_string(c) + "]";
        check_index(child, count, child_field, "node");
        Node& child_node = scene_.nodes[size_t(child)];
        if (child_node.parent >= 0 || child == int(i)) {
          fail(child_field, "node " + std::to_string(child) + " has more than one parent");
        }
        child_node.parent = int(i);
        node.children.push_back(child);
      }
    }
    // A cycle leaves nodes that no root reaches even though each has exactly one parent.
    std::vector<bool> reached(count, false);
    std::vector<int> stack;
    for (size_t i = 0; i < count; ++i) {
      if (scene_.nodes[i].parent < 0) stack.push_back(int(i));
    }
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      reached[size_t(n)] = true;
      for (int c : scene_.nodes[size_t(n)].children) stack.push_back(c);
    }
    for (size_t i = 0; i < count; ++i) {
      if (!reached[i]) fail("nodes[" + std::to_string(i) + "]", "node hierarchy has a cycle");
    }
    // Only nodes of the displayed scene are drawn; others keep their slot for animations.
    if (!model_.scenes.empty()) {
      const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      check_index(scene_index, model_.scenes.size(), "scene", "scene");
      const tinygltf::Scene& shown = model_.scenes[size_t(scene_index)];
      if (!shown.name.empty()) scene_name_ = shown.name;
      std::vector<bool> visible(count, false);
      for (size_t r = 0; r < shown.nodes.size(); ++r) {
        const int root = shown.nodes[r];
        check_index(root, count,
                    "scenes[" + std::to_string(scene_index) + "].nodes[" + std::to_string(r) + "]",
                    "node");
        stack.push_back(root);
      }
      while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        visible[size_t(n)] = true;
        for (int c : scene_.nodes[size_t(n)].children) stack.push_back(c);
      }
      visible_ = visible;
      for (size_t i = 0; i < count; ++i) {
        if (!visible[i]) scene_.nodes[i].mesh = -1;
      }
    } else {
      visible_.assign(count, true);
    }
  }

  // Scene texture index for glTF texture `index` used as sRGB or linear; -1 when the image is
  // missing or did not decode (with a warning).
  int texture(int index, bool srgb, const std::string& field) {
    if (index < 0) return -1;
    check_index(index, model_.textures.size(), field + ".index", "texture");
    const auto key = std::make_pair(index, srgb);
    if (auto it = texture_cache_.find(key); it != texture_cache_.end()) return it->second;
    const tinygltf::Texture& src = model_.textures[size_t(index)];
    const std::string tex_field = "textures[" + std::to_string(index) + "]";
    int result = -1;
    if (src.source < 0 || size_t(src.source) >= model_.images.size()) {
      warn(tex_field + ".source: image " + std::to_string(src.source) +
           " missing; texture dropped");
    } else {
      const tinygltf::Image& image = model_.images[size_t(src.source)];
      if (image.image.empty() || image.width < 1 || image.height < 1 || image.component < 1 ||
          image.component > 4 || (image.bits != 8 && image.bits != 16)) {
        warn(tex_field + ": image " + std::to_string(src.source) + " (" +
             (image.uri.empty() ? image.name : image.uri) +
             ") missing or not decodable; texture dropped");
      } else {
        Texture texture;
        texture.name = !src.name.empty() ? src.name : !image.name.empty() ? image.name : image.uri;
        texture.width = uint32_t(image.width);
        texture.height = uint32_t(image.height);
        texture.channels = 4;
        texture.bits = uint32_t(image.bits);
        texture.srgb = srgb;
        expand_to_rgba(image, texture);
        if (src.sampler >= 0) {
          check_index(src.sampler, model_.samplers.size(), tex_field + ".sampler", "sampler");
          const tinygltf::Sampler& sampler = model_.samplers[size_t(src.sampler)];
          texture.wrap_repeat = sampler.wrapS != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
                                sampler.wrapT != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
          if (sampler.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ||
              sampler.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) {
            warn(tex_field + ".sampler: MIRRORED_REPEAT is drawn as REPEAT");
          }
        }
        result = int(scene_.textures.size());
        scene_.textures.push_back(std::move(texture));
      }
    }
    texture_cache_[key] = result;
    return result;
  }

  static void expand_to_rgba(const tinygltf::Image& image, Texture& texture) {
    const size_t pixels = size_t(image.width) * size_t(image.height);
    const size_t bytes = size_t(image.bits / 8);
    const size_t comp = size_t(image.component);
    texture.pixels.assign(pixels * 4 * bytes, 0);
    const uint8_t* src = image.image.data();
    uint8_t* dst = texture.pixels.data();
    const uint8_t opaque[2] = {0xff, 0xff};
    for (size_t p = 0; p < pixels; ++p) {
      const uint8_t* in = src + p * comp * bytes;
      uint8_t* out = dst + p * 4 * bytes;
      // Grey (+alpha) replicates into RGB; missing alpha is opaque.
      const uint8_t* channel[4];
      if (comp <= 2) {
        channel[0] = channel[1] = channel[2] = in;
        channel[3] = comp == 2 ? in + bytes : opaque;
      } else {
        channel[0] = in;
        channel[1] = in + bytes;
        channel[2] = in + 2 * bytes;
        channel[3] = comp == 4 ? in + 3 * bytes : opaque;
      }
      for (int c = 0; c < 4; ++c) std::memcpy(out + size_t(c) * bytes, channel[c], bytes);
    }
  }

  static float extension_number(const tinygltf::ExtensionMap& extensions, const char* extension,
                                const char* key, float fallback) {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    return value.IsNumber() || value.IsInt() ? float(value.GetNumberAsDouble()) : fallback;
  }

  // The texture coordinates a material slot samples: its texCoord, then KHR_texture_transform
  // (whose own texCoord overrides the slot's). Sets beyond TEXCOORD_1 fall back to TEXCOORD_0.
  template <typename TextureInfo>
  TextureMapping mapping(const TextureInfo& info, const std::string& field) {
    TextureMapping m;
    if (info.index < 0) return m;
    int tex_coord = info.texCoord;
    const auto ext = info.extensions.find("KHR_texture_transform");
    if (ext != info.extensions.end()) {
      const std::string ext_field = field + ".extensions.KHR_texture_transform";
      const tinygltf::Value& t = ext->second;
      const auto number = [&](const tinygltf::Value& v, const std::string& key) {
        if (!(v.IsNumber() || v.IsInt()) || !std::isfinite(v.GetNumberAsDouble())) {
          fail(ext_field + "." + key, "expected a finite number");
        }
        return float(v.GetNumberAsDouble());
      };
      const auto pair = [&](const char* key, glm::vec2 fallback) {
        if (!t.Has(key)) return fallback;
        const tinygltf::Value& v = t.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2) fail(ext_field + "." + key, "expected 2 numbers");
        return glm::vec2(number(v.Get(0), std::string(key) + "[0]"),
                         number(v.Get(1), std::string(key) + "[1]"));
      };
      m.offset = pair("offset", m.offset);
      m.scale = pair("scale", m.scale);
      if (t.Has("rotation")) m.rotation = number(t.Get("rotation"), "rotation");
      if (t.Has("texCoord")) {
        const tinygltf::Value& v = t.Get("texCoord");
        if (!v.IsInt() || v.GetNumberAsInt() < 0) {
          fail(ext_field + ".texCoord", "expected an integer >= 0");
        }
        tex_coord = v.GetNumberAsInt();
      }
    }
    for (const auto& [name, value] : info.extensions) {
      if (name != "KHR_texture_transform") {
        warn(field + ".extensions." + name + ": not supported, ignored");
      }
    }
    if (tex_coord > 1) {
      warn(field + ".texCoord: TEXCOORD_" + std::to_string(tex_coord) +
           " is not supported (TEXCOORD_0 and TEXCOORD_1 are), TEXCOORD_0 used instead");
      tex_coord = 0;
    }
    m.tex_coord = tex_coord;
    return m;
  }

  void load_materials() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& src = model_.materials[i];
      const std::string field = "materials[" + std::to_string(i) + "]";
      Material m;
      m.name = src.name.empty() ? field : src.name;
      const auto& pbr = src.pbrMetallicRoughness;
      if (pbr.baseColorFactor.size() == 4) {
        m.base_color = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                 pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
      }
      m.metallic = glm::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
      m.roughness = glm::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
      if (src.emissiveFactor.size() == 3) {
        m.emissive = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
      }
      const float strength = extension_number(src.extensions, "KHR_materials_emissive_strength",
                                              "emissiveStrength", 1.0f);
      if (!(strength >= 0.0f) || !std::isfinite(strength)) {
        fail(field + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
             "expected a finite number >= 0");
      }
      m.emissive *= strength;
      m.normal_scale = float(src.normalTexture.scale);
      m.occlusion_strength = float(src.occlusionTexture.strength);
      m.alpha_cutoff = float(src.alphaCutoff);
      if (src.alphaMode == "MASK") {
        m.alpha_mode = AlphaMode::Mask;
      } else if (src.alphaMode == "BLEND") {
        m.alpha_mode = AlphaMode::Blend;
      } else if (src.alphaMode.empty() || src.alphaMode == "OPAQUE") {
        m.alpha_mode = AlphaMode::Opaque;
      } else {
        fail(field + ".alphaMode", "expected OPAQUE, MASK or BLEND, got \"" + src.alphaMode + "\"");
      }
      m.double_sided = src.doubleSided;
      const std::string base = field + ".pbrMetallicRoughness.baseColorTexture";
      const std::string mr = field + ".pbrMetallicRoughness.metallicRoughnessTexture";
      m.base_color_tex = texture(pbr.baseColorTexture.index, true, base);
      m.metallic_roughness_tex = texture(pbr.metallicRoughnessTexture.index, false, mr);
      m.normal_tex = texture(src.normalTexture.index, false, field + ".normalTexture");
      m.occlusion_tex = texture(src.occlusionTexture.index, false, field + ".occlusionTexture");
      m.emissive_tex = texture(src.emissiveTexture.index, true, field + ".emissiveTexture");
      m.mappings[0] = mapping(pbr.baseColorTexture, base);
      m.mappings[1] = mapping(pbr.metallicRoughnessTexture, mr);
      m.mappings[2] = mapping(src.normalTexture, field + ".normalTexture");
      m.mappings[3] = mapping(src.occlusionTexture, field + ".occlusionTexture");
      m.mappings[4] = mapping(src.emissiveTexture, field + ".emissiveTexture");
      for (const auto& [name, value] : src.extensions) {
        if (name != "KHR_materials_emissive_strength") {
          warn(field + ".extensions." + name + ": not supported, ignored");
        }
      }
      scene_.materials.push_back(std::move(m));
    }
  }

  void load_meshes() {
    for (size_t mi = 0; mi < model_.meshes.size(); ++mi) {
      const tinygltf::Mesh& src = model_.meshes[mi];
      Mesh mesh;
      mesh.name = src.name.empty() ? "meshes[" + std::to_string(mi) + "]" : src.name;
      for (size_t pi = 0; pi < src.primitives.size(); ++pi) {
        const std::string field =
            "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(pi) + "]";
        Primitive primitive;
        if (load_primitive(src.primitives[pi], field, primitive)) {
          mesh.primitives.push_back(std::move(primitive));
        }
      }
      scene_.meshes.push_back(std::move(mesh));
    }
  }

  bool load_primitive(const tinygltf::Primitive& src, const std::string& field, Primitive& out) {
    const bool triangles = src.mode == kModeTriangles || src.mode == -1;
    if (!triangles && src.mode != kModeTriangleStrip && src.mode != kModeTriangleFan) {
      warn(field + ".mode: points and lines (mode " + std::to_string(src.mode) +
           ") have no surface to draw; primitive skipped");
      return false;
    }
    if (!src.targets.empty()) {
      warn(field + ".targets: morph targets are not supported; drawn in the rest pose");
    }
    const auto attribute = [&](const char* name) {
      const auto it = src.attributes.find(name);
      return it == src.attributes.end() ? -1 : it->second;
    };
    const int position = attribute("POSITION");
    if (position < 0) {
      warn(field + ".attributes.POSITION: missing, primitive skipped");
      return false;
    }
    const std::string attr = field + ".attributes.";
    const std::vector<glm::vec4> positions =
        read_accessor(position, attr + "POSITION", {TINYGLTF_TYPE_VEC3});
    out.vertices.resize(positions.size());
    bool bad_position = false;
    for (size_t i = 0; i < positions.size(); ++i) {
      glm::vec3 p(positions[i]);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        p = glm::vec3(0.0f);
        bad_position = true;
      }
      out.vertices[i].position = p;
    }
    if (bad_position) warn(attr + "POSITION: non-finite positions replaced by the origin");

    read_uvs(attribute("TEXCOORD_0"), attr + "TEXCOORD_0", out, &Vertex::uv);
    if (const int uv1 = attribute("TEXCOORD_1"); uv1 >= 0) {
      read_uvs(uv1, attr + "TEXCOORD_1", out, &Vertex::uv1);
    } else {
      // A material may name set 1 on a primitive that has none: it reads set 0 instead.
      for (Vertex& v : out.vertices) v.uv1 = v.uv;
    }
    if (const int color = attribute("COLOR_0"); color >= 0) {
      read_colors(color, attr + "COLOR_0", out);
    }
    if (src.indices >= 0) {
      out.indices = read_indices(src.indices, field + ".indices", out.vertices.size());
    } else {
      out.indices.resize(out.vertices.size());
      for (size_t i = 0; i < out.indices.size(); ++i) out.indices[i] = uint32_t(i);
    }
    if (!triangles) out.indices = triangle_list(out.indices, src.mode);
    if (out.indices.size() % 3 != 0) {
      warn(field + ".indices: count " + std::to_string(out.indices.size()) +
           " is not a multiple of 3; trailing indices dropped");
      out.indices.resize(out.indices.size() / 3 * 3);
    }

    const int normal = attribute("NORMAL");
    if (normal >= 0) {
      const auto normals = read_accessor(normal, attr + "NORMAL", {TINYGLTF_TYPE_VEC3});
      check_count(normals.size(), out.vertices.size(), attr + "NORMAL");
      for (size_t i = 0; i < normals.size(); ++i) out.vertices[i].normal = glm::vec3(normals[i]);
      repair_normals(out);
    } else {
      make_flat_normals(out);
    }
    const int tangent = attribute("TANGENT");
    if (tangent >= 0 && normal >= 0) {
      const auto tangents = read_accessor(tangent, attr + "TANGENT", {TINYGLTF_TYPE_VEC4});
      check_count(tangents.size(), out.vertices.size(), attr + "TANGENT");
      for (size_t i = 0; i < tangents.size(); ++i) out.vertices[i].tangent = tangents[i];
      repair_tangents(out);
    } else {
      generate_tangents(out);
    }
    out.material = src.material;
    if (src.material >= 0) {
      check_index(src.material, model_.materials.size(), field + ".material", "material");
    }
    compute_bounds(out);
    return true;
  }

  void read_uvs(int accessor, const std::string& field, Primitive& out, glm::vec2 Vertex::*set) {
    if (accessor < 0) return;
    const auto uvs = read_accessor(accessor, field, {TINYGLTF_TYPE_VEC2});
    check_count(uvs.size(), out.vertices.size(), field);
    for (size_t i = 0; i < uvs.size(); ++i) {
      const glm::vec2 t(uvs[i]);
      out.vertices[i].*set = std::isfinite(t.x) && std::isfinite(t.y) ? t : glm::vec2(0.0f);
    }
  }

  // COLOR_0: RGB or RGBA, float or normalized unsigned byte/short (glTF 2.0, 3.7.2.1).
  void read_colors(int accessor, const std::string& field, Primitive& out) {
    auto colors = read_accessor(accessor, field, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4});
    check_count(colors.size(), out.vertices.size(), field);
    const tinygltf::Accessor& a = model_.accessors[size_t(accessor)];
    const bool rgb = a.type == TINYGLTF_TYPE_VEC3;
    float scale = 1.0f;
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized) {
      if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        scale = 1.0f / 255.0f;
      } else if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        scale = 1.0f / 65535.0f;
      } else {
        fail(field, "componentType " + std::to_string(a.componentType) +
                        " is not allowed for COLOR_0 (float, unsigned byte or unsigned short)");
      }
      warn(field + ": integer colours must be normalized; read as normalized");
    }
    bool clamped = false;
    for (size_t i = 0; i < colors.size(); ++i) {
      glm::vec4 c = colors[i] * scale;
      if (rgb) c.w = 1.0f;
      for (int k = 0; k < 4; ++k) {
        // Colours are factors of the base colour: [0, 1] like it.
        const float v = std::isfinite(c[k]) ? glm::clamp(c[k], 0.0f, 1.0f) : 1.0f;
        clamped |= v != c[k];
        c[k] = v;
      }
      out.vertices[i].color = c;
    }
    if (clamped) warn(field + ": colours outside [0, 1] (or not finite) clamped");
  }

  void check_count(size_t got, size_t expected, const std::string& field) const {
    if (got != expected) {
      fail(field,
           "has " + std::to_string(got) + " elements, POSITION has " + std::to_string(expected));
    }
  }

  // EXT_mesh_gpu_instancing: a node draws its mesh once per element of its TRANSLATION,
  // ROTATION and SCALE accessors, each placed by those under the node. Each instance becomes a
  // child node (appended after the file's nodes, so every index the file uses stays valid).
  void expand_gpu_instancing() {
    constexpr size_t kMaxInstances = size_t{1} << 20;
    const size_t file_nodes = model_.nodes.size();
    for (size_t i = 0; i < file_nodes; ++i) {
      const auto ext = model_.nodes[i].extensions.find("EXT_mesh_gpu_instancing");
      if (ext == model_.nodes[i].extensions.end()) continue;
      const std::string field =
          "nodes[" + std::to_string(i) + "].extensions.EXT_mesh_gpu_instancing";
      if (!ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject()) {
        fail(field + ".attributes", "expected an object of accessors");
      }
      const tinygltf::Value& attributes = ext->second.Get("attributes");
      std::vector<glm::vec4> trs[3];
      const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
      size_t count = 0;
      bool any = false;
      for (int k = 0; k < 3; ++k) {
        if (!attributes.Has(names[k])) continue;
        const tinygltf::Value& index = attributes.Get(names[k]);
        const std::string attr = field + ".attributes." + names[k];
        if (!index.IsInt()) fail(attr, "expected an accessor index");
        trs[k] = read_accessor(index.GetNumberAsInt(), attr,
                               {k == 1 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3});
        if (any && trs[k].size() != count) {
          fail(attr, "has " + std::to_string(trs[k].size()) + " elements, the other attributes " +
                         std::to_string(count));
        }
        count = trs[k].size();
        any = true;
      }
      if (count > kMaxInstances) {
        fail(field,
             std::to_string(count) + " instances (at most " + std::to_string(kMaxInstances) + ")");
      }
      if (scene_.nodes[i].mesh < 0 || !any) continue;
      const int mesh = scene_.nodes[i].mesh;
      scene_.nodes[i].mesh = -1;  // drawn by its instances only
      size_t skipped = 0;
      for (size_t n = 0; n < count; ++n) {
        Node instance;
        instance.name = scene_.nodes[i].name + "#" + std::to_string(n);
        instance.parent = int(i);
        instance.mesh = mesh;
        if (!trs[0].empty()) instance.translation = glm::vec3(trs[0][n]);
        if (!trs[1].empty()) {
          const glm::vec4 q = trs[1][n];  // x, y, z, w
          instance.rotation = glm::normalize(glm::quat(q.w, q.x, q.y, q.z));
        }
        if (!trs[2].empty()) instance.scale = glm::vec3(trs[2][n]);
        const glm::mat4 local = instance.local();
        bool finite = true;
        for (int c = 0; c < 4; ++c) {
          for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(local[c][r]);
        }
        if (!finite) {
          ++skipped;
          continue;
        }
        scene_.nodes[i].children.push_back(int(scene_.nodes.size()));
        scene_.nodes.push_back(std::move(instance));
        visible_.push_back(visible_[i]);
      }
      // One warning per node: an accessor of zeros would otherwise give one per instance.
      if (skipped > 0) {
        warn(field + ": " + std::to_string(skipped) + " of " + std::to_string(count) +
             " instances have a non-finite transform; skipped");
      }
    }
  }

  void load_lights_and_cameras() {
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
      const tinygltf::Node& src = model_.nodes[i];
      Node& node = scene_.nodes[i];
      const std::string field = "nodes[" + std::to_string(i) + "]";
      if (src.camera >= 0 && visible_[i]) {
        check_index(src.camera, model_.cameras.size(), field + ".camera", "camera");
        const tinygltf::Camera& cam = model_.cameras[size_t(src.camera)];
        const std::string cam_field = "cameras[" + std::to_string(src.camera) + "]";
        if (cam.type == "perspective") {
          Camera camera;
          camera.name = cam.name.empty() ? (src.name.empty() ? cam_field : src.name) : cam.name;
          const auto& p = cam.perspective;
          if (!(p.yfov > 0.0 && p.yfov < 3.14159)) {
            fail(cam_field + ".perspective.yfov", "expected radians in (0, pi)");
          }
          if (!(p.znear > 0.0)) fail(cam_field + ".perspective.znear", "expected a number > 0");
          camera.yfov = float(p.yfov);
          camera.znear = float(p.znear);
          camera.zfar = p.zfar > p.znear ? float(p.zfar) : 0.0f;  // 0: set from the bounds
          camera.aspect = p.aspectRatio > 0.0 ? float(p.aspectRatio) : 0.0f;
          camera.node = int(i);
          node.camera = int(scene_.cameras.size());
          scene_.cameras.push_back(std::move(camera));
        } else {
          warn(cam_field + ".type: \"" + cam.type + "\" cameras are not supported, skipped");
        }
      }
      const auto ext = src.extensions.find("KHR_lights_punctual");
      if (ext != src.extensions.end() && ext->second.Has("light") && visible_[i]) {
        const tinygltf::Value& v = ext->second.Get("light");
        const std::string ext_field = field + ".extensions.KHR_lights_punctual.light";
        if (!v.IsInt() && !v.IsNumber()) fail(ext_field, "expected a light index");
        // A number outside int's range would overflow the conversion: range-check it first.
        const double number = v.GetNumberAsDouble();
        if (!(number >= 0.0 && number < double(model_.lights.size())) ||
            number != std::floor(number)) {
          fail(ext_field, "expected a light index from 0 to " +
                              std::to_string(int(model_.lights.size()) - 1) + ", got " +
                              std::to_string(number));
        }
        const int index = int(number);
        const tinygltf::Light& l = model_.lights[size_t(index)];
        const std::string light_field =
            "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
        Light light;
        light.name = l.name.empty() ? (src.name.empty() ? light_field : src.name) : l.name;
        if (l.type == "directional") {
          light.type = LightType::Directional;
        } else if (l.type == "point") {
          light.type = LightType::Point;
        } else if (l.type == "spot") {
          light.type = LightType::Spot;
        } else {
          fail(light_field + ".type",
               "expected directional, point or spot, got \"" + l.type + "\"");
        }
        if (l.color.size() == 3) light.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
        light.intensity = float(l.intensity);
        if (!(light.intensity >= 0.0f) || !std::isfinite(light.intensity)) {
          fail(light_field + ".intensity", "expected a finite number >= 0");
        }
        light.range = l.range > 0.0 ? float(l.range) : 0.0f;
        light.inner_cone = float(l.spot.innerConeAngle);
        light.outer_cone = float(l.spot.outerConeAngle);
        if (light.type == LightType::Spot &&
            !(light.inner_cone >= 0.0f && light.inner_cone < light.outer_cone &&
              light.outer_cone <= 1.5707964f)) {
          fail(light_field + ".spot", "expected 0 <= innerConeAngle < outerConeAngle <= pi/2");
        }
        light.node = int(i);
        node.light = int(scene_.lights.size());
        scene_.lights.push_back(std::move(light));
      }
    }
  }

  void load_animations() {
    for (size_t ai = 0; ai < model_.animations.size(); ++ai) {
      const tinygltf::Animation& src = model_.animations[ai];
      const std::string field = "animations[" + std::to_string(ai) + "]";
      Animation animation;
      animation.name = src.name.empty() ? field : src.name;
      for (size_t ci = 0; ci < src.channels.size(); ++ci) {
        const tinygltf::AnimationChannel& ch = src.channels[ci];
        const std::string ch_field = field + ".channels[" + std::to_string(ci) + "]";
        AnimationChannel channel;
        if (ch.target_path == "translation") {
          channel.path = AnimationPath::Translation;
        } else if (ch.target_path == "rotation") {
          channel.path = AnimationPath::Rotation;
        } else if (ch.target_path == "scale") {
          channel.path = AnimationPath::Scale;
        } else {
          warn(ch_field + ".target.path: \"" + ch.target_path + "\" not supported, skipped");
          continue;
        }
        if (ch.target_node < 0) continue;  // glTF allows channels that target nothing
        check_index(ch.target_node, scene_.nodes.size(), ch_field + ".target.node", "node");
        check_index(ch.sampler, src.samplers.size(), ch_field + ".sampler", "sampler");
        const tinygltf::AnimationSampler& sampler = src.samplers[size_t(ch.sampler)];
        const std::string s_field = field + ".samplers[" + std::to_string(ch.sampler) + "]";
        if (sampler.interpolation == "STEP") {
          channel.interpolation = Interpolation::Step;
        } else if (sampler.interpolation == "CUBICSPLINE") {
          channel.interpolation = Interpolation::CubicSpline;
        } else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") {
          channel.interpolation = Interpolation::Linear;
        } else {
          fail(s_field + ".interpolation",
               "expected LINEAR, STEP or CUBICSPLINE, got \"" + sampler.interpolation + "\"");
        }
        for (const glm::vec4& t :
             read_accessor(sampler.input, s_field + ".input", {TINYGLTF_TYPE_SCALAR})) {
          channel.times.push_back(t.x);
        }
        for (size_t k = 0; k < channel.times.size(); ++k) {
          if (!std::isfinite(channel.times[k]) ||
              (k > 0 && channel.times[k] < channel.times[k - 1])) {
            fail(s_field + ".input", "key times must be finite and increasing");
          }
        }
        const int type =
            channel.path == AnimationPath::Rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
        channel.values = read_accessor(sampler.output, s_field + ".output", {type});
        const size_t per_key = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
        if (channel.values.size() != channel.times.size() * per_key) {
          fail(s_field + ".output", "has " + std::to_string(channel.values.size()) +
                                        " values, expected " +
                                        std::to_string(channel.times.size() * per_key));
        }
        if (channel.times.empty()) continue;
        channel.node = ch.target_node;
        if (scene_.nodes[size_t(channel.node)].matrix) {
          fail(ch_field + ".target.node", "animated nodes must not use \"matrix\"");
        }
        scene_.nodes[size_t(channel.node)].animated = true;
        animation.duration = std::max(animation.duration, channel.times.back());
        animation.channels.push_back(std::move(channel));
      }
      scene_.animations.push_back(std::move(animation));
    }
  }

  // glTF's infinite far plane becomes a finite one that encloses the scene from the camera.
  void finish_cameras() {
    glm::vec3 mn, mx;
    scene_.bounds(mn, mx);
    const float radius = 0.5f * glm::length(mx - mn);
    for (Camera& camera : scene_.cameras) {
      if (camera.zfar > 0.0f) continue;
      const glm::vec3 eye(camera.world[3]);
      const float distance = glm::length(eye - 0.5f * (mn + mx));
      camera.zfar = std::max((distance + radius) * 1.5f, camera.znear * 1000.0f);
    }
    if (!scene_name_.empty()) scene_.name = scene_name_;
  }

  std::filesystem::path path_;
  tinygltf::Model model_;
  Scene scene_;
  std::string scene_name_;
  std::vector<bool> visible_;
  std::map<std::pair<int, bool>, int> texture_cache_;
};

}  // namespace

Scene load_gltf(const std::filesystem::path& path) {
  return Loader(path).load();
}

}  // namespace voxgi::scene
