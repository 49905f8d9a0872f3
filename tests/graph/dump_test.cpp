#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "engine/graph/dump.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

const char* kGraph = R"({
  "name": "dumped",
  "parameters": { "res": 8 },
  "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": "${res}" },
    "spec": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "history": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
  "passes": [
    { "name": "clear", "type": "test.clear", "params": { "value": 0.25 }, "out": { "color": "hdr" } },
    { "name": "spec", "type": "test.blur", "when": "scene.has_glossy", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "acc", "type": "test.accumulate", "in": { "src": "hdr" }, "out": { "acc": "history" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "history" }, "out": { "color": "ldr" } } ],
  "outputs": { "display": "ldr" } })";

struct Compiled {
  GraphDesc desc;
  CompiledGraph graph;
};

Compiled compile_sample() {
  static const Registry registry = test::make_registry();
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 0}};
  GraphDesc desc = parse_graph(kGraph, "graphs/dumped.json");
  CompiledGraph graph = compile(desc, registry, options);
  return {std::move(desc), std::move(graph)};
}

TEST(Dump, ExplainListsDeviceFeaturesAndTheConditionsTheyDecided) {
  static const Registry registry = test::make_registry();
  CompileOptions options;
  options.device_features = {{"device.ray_query", 1}};
  options.device_name = "test gpu";
  const char* text = R"({
  "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "spec": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
  "passes": [
    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
    { "name": "traced", "type": "test.blur", "when": "device.ray_query", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "meshed", "type": "test.blur", "when": "!device.ray_query && device.mesh_shader", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "spec" }, "out": { "color": "ldr" } } ],
  "outputs": { "display": "ldr" } })";
  const CompiledGraph g = compile(parse_graph(text, "graphs/device.json"), registry, options);
  const std::string out = explain(g);
  EXPECT_NE(out.find("device features (of 'test gpu'):\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  device.ray_query = true\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  device.mesh_shader = false\n"), std::string::npos) << out;
  EXPECT_NE(out.find("conditions decided by device features:\n"
                     "  traced: when 'device.ray_query' is true (reads device.ray_query)\n"
                     "  meshed: when '!device.ray_query && device.mesh_shader' is false (reads "
                     "device.ray_query, device.mesh_shader): pass culled\n"),
            std::string::npos)
      << out;

  const CompiledGraph none = compile(parse_graph(text, "graphs/device.json"), registry, {});
  EXPECT_NE(explain(none).find("device features (no device: every feature reads as absent; "
                               "--device D queries one):"),
            std::string::npos);
}

TEST(Dump, ExplainListsScheduleCulledResourcesAndMemory) {
  const Compiled c = compile_sample();
  const std::string text = explain(c.graph);
  EXPECT_NE(text.find("1. clear (test.clear)"), std::string::npos) << text;
  EXPECT_NE(text.find("param value = 0.25"), std::string::npos) << text;
  EXPECT_NE(text.find("spec (test.blur): when 'scene.has_glossy' is false for this scene"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("barrier hdr mips 0..0 COLOR_ATTACHMENT_OPTIMAL -> SHADER_READ_ONLY_OPTIMAL"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("frame start:"), std::string::npos) << text;
  EXPECT_NE(text.find("history: image2d rgba16f 8x8, mips 1, layers 1, persistent"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("memory: "), std::string::npos) << text;
}

TEST(Dump, EveryPhaseIsValidJson) {
  const Compiled c = compile_sample();
  for (const nlohmann::json& j :
       {desc_to_json(c.desc), resolved_to_json(c.graph), culled_to_json(c.graph),
        schedule_to_json(c.graph), barriers_to_json(c.graph), resources_to_json(c.graph)}) {
    const nlohmann::json round_trip = nlohmann::json::parse(j.dump());
    EXPECT_EQ(round_trip, j);
  }
  const nlohmann::json desc = desc_to_json(c.desc);
  EXPECT_EQ(desc["passes"][1]["when"], "scene.has_glossy");
  const nlohmann::json culled = culled_to_json(c.graph);
  ASSERT_EQ(culled.size(), 1u);
  EXPECT_EQ(culled[0]["name"], "spec");
  const nlohmann::json schedule = schedule_to_json(c.graph);
  EXPECT_EQ(schedule[2]["name"], "shade");
  EXPECT_EQ(schedule[2]["depends_on"], nlohmann::json::array({"clear", "acc"}));
  const nlohmann::json resources = resources_to_json(c.graph);
  EXPECT_EQ(resources["resources"][0]["extent"], nlohmann::json::array({8, 8, 1}));
  const nlohmann::json barriers = barriers_to_json(c.graph);
  EXPECT_EQ(barriers["frame_start"][0]["resource"], "history");
  EXPECT_EQ(barriers["frame_end"][0]["new_layout"], "TRANSFER_SRC_OPTIMAL");
}

TEST(Dump, DotShowsPassesResourcesAndCulledPasses) {
  const Compiled c = compile_sample();
  const std::string dot = to_dot(c.graph);
  EXPECT_EQ(dot.rfind("digraph \"dumped\" {", 0), 0u);
  EXPECT_NE(dot.find("\"p:clear\" [shape=box"), std::string::npos);
  EXPECT_NE(dot.find("\"r:hdr\" [shape=ellipse"), std::string::npos);
  EXPECT_NE(dot.find("\"p:clear\" -> \"r:hdr\""), std::string::npos);
  EXPECT_NE(dot.find("\"p:spec\" [shape=box, style=dashed, color=grey"), std::string::npos);
  EXPECT_NE(dot.find("tooltip=\"when 'scene.has_glossy' is false for this scene\""),
            std::string::npos);
  EXPECT_EQ(dot.back(), '\n');
  EXPECT_EQ(std::count(dot.begin(), dot.end(), '{'), std::count(dot.begin(), dot.end(), '}'));
}

TEST(Dump, DumpPhasesWritesOneFilePerPhase) {
  const Compiled c = compile_sample();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("voxgi-dump-" + std::to_string(::getpid()));
  dump_phases(c.desc, c.graph, dir);
  for (const char* name : {"1-parsed.json", "2-resolved.json", "3-culled.json", "4-schedule.json",
                           "5-barriers.json", "6-resources.json"}) {
    std::ifstream in(dir / name);
    ASSERT_TRUE(in) << name;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_FALSE(nlohmann::json::parse(text.str(), nullptr, false).is_discarded()) << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "graph.dot"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxgi::graph
