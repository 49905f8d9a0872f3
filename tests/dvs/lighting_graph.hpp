#pragma once
// Graph files (as text) the dvs tests build around uploaded voxels.

#include <cstdint>
#include <string>
#include <vector>

namespace voxgi::test {

// dvs_test.voxel_source -> dvs.voxel_lighting (-> optional extra passes), output "radiance"
// (dvs.radiance) and "direct". `lighting_params` is a JSON object body, e.g.
// "\"occlusion\": \"none\"". `shadow_maps`: add common.shadow_maps and bind it.
inline std::string voxel_lighting_graph(uint32_t resolution, uint32_t levels,
                                        const std::string& lighting_params,
                                        bool shadow_maps = false) {
  const std::string clipmap =
      "\"type\": \"clipmap\", \"resolution\": " + std::to_string(resolution) +
      ", \"levels\": " + std::to_string(levels) + ", \"persistent\": true";
  std::string g = R"G({ "name": "dvs-voxel-lighting-test", "resources": {
    "voxel.clipmap_info": { "type": "buffer", "size": 288, "persistent": true },
    "voxel.albedo": { "format": "rgba8", )G" +
                  clipmap + R"G( },
    "voxel.normal": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "voxel.emission": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "dvs.direct": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "dvs.radiance": { "format": "rgba16f", "mips": "full", )G" +
                  clipmap + R"G( })G";
  if (shadow_maps) {
    g += R"G(,
    "shadow.maps": { "type": "image2d", "format": "d32f", "size": 256, "layers": "6 * max(1, scene.light_count)", "persistent": true },
    "shadow.matrices": { "type": "buffer", "size": "(6 * 64 + 32) * max(1, scene.light_count)", "persistent": true })G";
  }
  g += R"G( },
  "passes": [
    { "name": "voxels", "type": "dvs_test.voxel_source",
      "out": { "clipmap_info": "voxel.clipmap_info", "albedo": "voxel.albedo",
               "normal": "voxel.normal", "emission": "voxel.emission" } },)G";
  if (shadow_maps) {
    g += R"G(
    { "name": "shadows", "type": "common.shadow_maps",
      "out": { "maps": "shadow.maps", "matrices": "shadow.matrices" } },)G";
  }
  g += R"G(
    { "name": "voxel_lighting", "type": "dvs.voxel_lighting", "params": { )G" +
       lighting_params +
       R"G( },
      "in": { "clipmap_info": "voxel.clipmap_info", "albedo": "voxel.albedo",
              "normal": "voxel.normal", "emission": "voxel.emission")G";
  if (shadow_maps) g += R"G(, "shadow_maps": "shadow.maps", "shadow_matrices": "shadow.matrices")G";
  g += R"G( },
      "out": { "radiance": "dvs.radiance", "direct": "dvs.direct" } }
  ],
  "outputs": { "radiance": "dvs.radiance", "direct": "dvs.direct" } })G";
  return g;
}

}  // namespace voxgi::test

namespace voxgi::test {

// dvs_test.voxel_source -> dvs.voxel_lighting -> vct.filter (of dvs.direct), then bounce k /
// filter k (of dvs.radiance) for k = 1..max_bounces, culled by "${dvs.bounces} >= k" as in
// graphs/dvs.json. Outputs "radiance" (dvs.radiance after the last bounce) and "direct".
inline std::string voxel_bounce_graph(uint32_t resolution, uint32_t levels, int max_bounces,
                                      bool anisotropic, const std::string& lighting_params,
                                      const std::string& bounce_params = "") {
  const std::string clipmap =
      "\"type\": \"clipmap\", \"resolution\": " + std::to_string(resolution) +
      ", \"levels\": " + std::to_string(levels) + ", \"persistent\": true";
  const std::vector<std::string> volumes =
      anisotropic ? std::vector<std::string>{"pos_x", "neg_x", "pos_y", "neg_y", "pos_z", "neg_z"}
                  : std::vector<std::string>{"filtered"};
  std::string bindings;
  for (const std::string& v : volumes) {
    bindings += (bindings.empty() ? "" : ", ") + ("\"" + v + "\": \"vct." + v + "\"");
  }
  std::string g = R"G({ "name": "dvs-voxel-bounce-test",
  "parameters": { "dvs.bounces": 1 },
  "resources": {
    "voxel.clipmap_info": { "type": "buffer", "size": 288, "persistent": true },
    "voxel.albedo": { "format": "rgba8", )G" +
                  clipmap + R"G( },
    "voxel.normal": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "voxel.emission": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "dvs.direct": { "format": "rgba16f", )G" +
                  clipmap + R"G( },
    "dvs.radiance": { "format": "rgba16f", )G" +
                  clipmap + R"G( })G";
  for (const std::string& v : volumes) {
    g += ",\n    \"vct." + v + "\": { \"format\": \"rgba16f\", \"mips\": \"full\", " + clipmap +
         " }";
  }
  g += R"G( },
  "passes": [
    { "name": "voxels", "type": "dvs_test.voxel_source",
      "out": { "clipmap_info": "voxel.clipmap_info", "albedo": "voxel.albedo",
               "normal": "voxel.normal", "emission": "voxel.emission" } },
    { "name": "voxel_lighting", "type": "dvs.voxel_lighting", "params": { )G" +
       lighting_params + R"G( },
      "in": { "clipmap_info": "voxel.clipmap_info", "albedo": "voxel.albedo",
              "normal": "voxel.normal", "emission": "voxel.emission" },
      "out": { "radiance": "dvs.radiance", "direct": "dvs.direct" } })G";
  const std::string mode = anisotropic ? "anisotropic" : "isotropic";
  auto filter = [&](int k) {
    return ",\n    { \"name\": \"filter" + std::to_string(k) + "\", \"type\": \"vct.filter\"," +
           (k > 0 ? " \"when\": \"${dvs.bounces} >= " + std::to_string(k) + "\"," : "") +
           " \"params\": { \"mode\": \"" + mode +
           "\" }, \"in\": { \"clipmap_info\": \"voxel.clipmap_info\", \"radiance\": \"" +
           (k == 0 ? "dvs.direct" : "dvs.radiance") + "\" }, \"out\": { " + bindings + " } }";
  };
  g += filter(0);
  for (int k = 1; k <= max_bounces; ++k) {
    g += ",\n    { \"name\": \"bounce" + std::to_string(k) +
         "\", \"type\": \"dvs.voxel_bounce\", \"when\": \"${dvs.bounces} >= " + std::to_string(k) +
         "\", \"params\": { " + bounce_params +
         " }, \"in\": { \"clipmap_info\": \"voxel.clipmap_info\", \"albedo\": \"voxel.albedo\", "
         "\"normal\": \"voxel.normal\", \"direct\": \"dvs.direct\", " +
         bindings + " }, \"out\": { \"radiance\": \"dvs.radiance\" } }";
    g += filter(k);
  }
  g += R"G(
  ],
  "outputs": { "radiance": "dvs.radiance", "direct": "dvs.direct" } })G";
  return g;
}

}  // namespace voxgi::test
