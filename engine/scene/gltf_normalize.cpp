#include "engine/scene/gltf_normalize.hpp"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

namespace voxgi::scene {

namespace {

using nlohmann::json;

// Every number that is a float with an integral value in the int64 range becomes an integer:
// the parser reads float fields from integers too, but integer fields only from integers.
void integral_floats_to_integers(json& value, bool& changed) {
  if (value.is_number_float()) {
    const double d = value.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 9.0e15) {
      value = static_cast<int64_t>(d);
      changed = true;
    }
  } else if (value.is_array() || value.is_object()) {
    for (json& item : value) integral_floats_to_integers(item, changed);
  }
}

// Base64 of `bytes` zero bytes as a data URI.
std::string zero_bytes_data_uri(size_t bytes) {
  std::string text = "data:application/octet-stream;base64,";
  const size_t groups = bytes / 3;
  text.reserve(text.size() + (groups + 1) * 4);
  for (size_t i = 0; i < groups; ++i) text += "AAAA";
  if (bytes % 3 == 1) text += "AA==";
  if (bytes % 3 == 2) text += "AAA=";
  return text;
}

}  // namespace

std::optional<NormalizedGltf> normalize_gltf_json(const std::string& text, bool glb) {
  json doc = json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return std::nullopt;
  NormalizedGltf out;

  // Silent: float fields written as 1.0 are common and mean the same after the rewrite.
  bool integers = false;
  integral_floats_to_integers(doc, integers);

  if (doc.contains("skins") && doc["skins"].is_array()) {
    for (size_t i = 0; i < doc["skins"].size(); ++i) {
      if (doc["skins"][i].is_object() && !doc["skins"][i].contains("inverseBindMatrices")) {
        out.warnings.push_back("skins[" + std::to_string(i) +
                               "]: no inverseBindMatrices (identity); skins are not supported "
                               "and were dropped, meshes drawn in bind pose");
        doc.erase("skins");
        break;
      }
    }
  }

  if (doc.contains("buffers") && doc["buffers"].is_array()) {
    constexpr int64_t kMaxZeroBuffer = int64_t{64} << 20;
    for (size_t i = 0; i < doc["buffers"].size(); ++i) {
      json& buffer = doc["buffers"][i];
      if (!buffer.is_object() || buffer.contains("uri") || (glb && i == 0)) continue;
      const json length = buffer.value("byteLength", json());
      if (!length.is_number_integer() || length.get<int64_t>() < 0 ||
          length.get<int64_t>() > kMaxZeroBuffer) {
        continue;  // the parser names what is wrong with it
      }
      buffer["uri"] = zero_bytes_data_uri(static_cast<size_t>(length.get<int64_t>()));
      out.warnings.push_back("buffers[" + std::to_string(i) +
                             "]: no uri; its bytes are undefined, read as zeros");
    }
  }

  if (doc.contains("animations") && doc["animations"].is_array()) {
    json kept = json::array();
    for (size_t a = 0; a < doc["animations"].size(); ++a) {
      json animation = doc["animations"][a];
      if (animation.is_object() && animation.contains("channels") &&
          animation["channels"].is_array()) {
        json channels = json::array();
        for (size_t c = 0; c < animation["channels"].size(); ++c) {
          const json& channel = animation["channels"][c];
          if (channel.is_object() && channel.contains("target") && channel["target"].is_object() &&
              !channel["target"].contains("node")) {
            out.warnings.push_back("animations[" + std::to_string(a) + "].channels[" +
                                   std::to_string(c) +
                                   "]: the target names no node (an animation pointer); "
                                   "ignored");
            continue;
          }
          channels.push_back(channel);
        }
        if (channels.empty() && !animation["channels"].empty()) continue;  // nothing left
        animation["channels"] = channels;
      }
      kept.push_back(animation);
    }
    doc["animations"] = kept;
    if (doc["animations"].empty()) doc.erase("animations");
  }

  out.changed = integers || !out.warnings.empty();
  if (out.changed) out.json = doc.dump();
  return out;
}

std::vector<std::string> missing_referenced_files(const std::string& text,
                                                  const std::filesystem::path& base_dir) {
  std::vector<std::string> missing;
  const json doc = json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return missing;
  for (const char* list : {"buffers", "images"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    for (size_t i = 0; i < doc[list].size(); ++i) {
      const json& item = doc[list][i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      std::error_code ec;
      if (!std::filesystem::exists(base_dir / uri, ec)) {
        missing.push_back(std::string(list) + "[" + std::to_string(i) + "].uri: file '" + uri +
                          "' not found in " + base_dir.string());
      }
    }
  }
  return missing;
}

std::optional<std::vector<unsigned char>> replace_glb_json(const std::vector<unsigned char>& glb,
                                                           const std::string& json_text) {
  const auto u32 = [&](size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  if (glb.size() < 20 || std::memcmp(glb.data(), "glTF", 4) != 0) return std::nullopt;
  const uint32_t json_length = u32(12);
  if (u32(16) != 0x4E4F534Au || size_t{json_length} > glb.size() - 20) return std::nullopt;
  std::string padded = json_text;
  while (padded.size() % 4) padded.push_back(' ');
  const size_t rest = 20 + json_length;
  std::vector<unsigned char> out;
  out.reserve(20 + padded.size() + glb.size() - rest);
  const auto put = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
  };
  out.insert(out.end(), glb.begin(), glb.begin() + 8);  // magic, version
  put(static_cast<uint32_t>(20 + padded.size() + (glb.size() - rest)));
  put(static_cast<uint32_t>(padded.size()));
  put(0x4E4F534Au);
  out.insert(out.end(), padded.begin(), padded.end());
  out.insert(out.end(), glb.begin() + static_cast<long>(rest), glb.end());
  return out;
}

}  // namespace voxgi::scene
