#pragma once
// Graph texts of the volume-level tests: uploaded radiance (and, with `with_normals`, voxel
// normals; with `with_faces`, the voxels' faces; with `with_light_shares` too, their light
// shares) -> vct.filter (isotropic or anisotropic),
// with the filtered volumes persistent so tests can read them afterwards.

#include <string>

namespace voxgi::test {

inline std::string filter_graph(int resolution, int levels, bool anisotropic,
                                bool with_normals = false, bool with_faces = false,
                                bool with_light_shares = false) {
  const std::string clipmap = "{ \"type\": \"clipmap\", \"format\": \"rgba16f\", \"resolution\": " +
                              std::to_string(resolution) +
                              ", \"levels\": " + std::to_string(levels);
  std::string resources =
      "\"voxel.clipmap_info\": { \"type\": \"buffer\", \"size\": 288, \"persistent\": true },\n"
      "\"vct.radiance\": " +
      clipmap + ", \"persistent\": true },\n";
  if (with_normals) resources += "\"vct.normal\": " + clipmap + ", \"persistent\": true },\n";
  std::string extra_slots = with_normals ? ", \"normal\": \"vct.normal\"" : "";
  // An uploaded integer clipmap vct.<slot>, bound to the filter's slot of that name.
  auto integer_input = [&](const std::string& slot, const std::string& format) {
    resources += "\"vct." + slot + "\": { \"type\": \"clipmap\", \"format\": \"" + format +
                 "\", \"resolution\": " + std::to_string(resolution) +
                 ", \"levels\": " + std::to_string(levels) + ", \"persistent\": true },\n";
    extra_slots += ", \"" + slot + "\": \"vct." + slot + "\"";
  };
  if (with_faces) integer_input("faces", "rgba32ui");
  if (with_faces && with_light_shares) integer_input("light_shares", "r32ui");
  std::string outputs;
  if (anisotropic) {
    const char* slots[] = {"pos_x", "neg_x", "pos_y", "neg_y", "pos_z", "neg_z"};
    for (const char* slot : slots) {
      resources += std::string("\"vct.") + slot + "\": " + clipmap +
                   ", \"mips\": \"full\", \"persistent\": true },\n";
      outputs +=
          std::string(outputs.empty() ? "" : ", ") + "\"" + slot + "\": \"vct." + slot + "\"";
    }
  } else {
    resources += "\"vct.filtered\": " + clipmap + ", \"mips\": \"full\", \"persistent\": true },\n";
    outputs = "\"filtered\": \"vct.filtered\"";
  }
  resources.erase(resources.size() - 2);  // the last ",\n"
  return "{ \"name\": \"vct-filter-test\",\n \"resources\": {\n" + resources +
         "},\n \"passes\": [\n"
         " { \"name\": \"volumes\", \"type\": \"vcttest.volumes\",\n"
         "   \"out\": { \"clipmap_info\": \"voxel.clipmap_info\", \"radiance\": \"vct.radiance\"" +
         extra_slots +
         " } "
         "},\n"
         " { \"name\": \"filter\", \"type\": \"vct.filter\", \"params\": { \"mode\": \"" +
         std::string(anisotropic ? "anisotropic" : "isotropic") +
         "\" },\n"
         "   \"in\": { \"clipmap_info\": \"voxel.clipmap_info\", \"radiance\": \"vct.radiance\"" +
         extra_slots +
         " },\n"
         "   \"out\": { " +
         outputs +
         " } }\n"
         " ],\n \"outputs\": { " +
         outputs + " } }\n";
}

inline std::vector<std::string> filtered_resources(bool anisotropic) {
  if (!anisotropic) return {"vct.filtered"};
  return {"vct.pos_x", "vct.neg_x", "vct.pos_y", "vct.neg_y", "vct.pos_z", "vct.neg_z"};
}

}  // namespace voxgi::test
