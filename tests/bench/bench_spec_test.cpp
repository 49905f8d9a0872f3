// Bench files: expansion into configurations, shards, and the errors bad files get.

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <set>
#include <string>

#include "apps/voxgi/bench_spec.hpp"
#include "apps/voxgi/cli_args.hpp"

namespace voxgi::cli {
namespace {

const std::filesystem::path kRepo = VOXGI_SOURCE_DIR;
const std::filesystem::path kBenchFile = "/nonexistent-folder/test-bench.json";

BenchSpec parse(const std::string& text) {
  return parse_bench(text, kBenchFile, kRepo);
}

// The error message of parsing `text`, "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const graph::GraphError& e) {
    return e.what();
  }
  return {};
}

// "file:line:col" of the first occurrence of `part` in `text`.
std::string location_of(const std::string& text, const std::string& part) {
  const size_t at = text.find(part);
  const size_t line_start = text.rfind('\n', at);
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + long(at), '\n'));
  const size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return kBenchFile.string() + ":" + std::to_string(line) + ":" + std::to_string(column);
}

constexpr const char* kReference =
    R"("reference": { "graph": "graphs/default.json", "frames": 4 })";

TEST(BenchSpec, ExpandsScenesCamerasGraphsAndSweeps) {
  const std::string text = std::string(R"({
    // comments and trailing commas are fine
    "name": "expansion",
    "scenes": [ "cornell", { "scene": "plane-point", "cameras": ["default", "side"] } ],
    "resolution": [64, 32],
    "warmup_frames": 1,
    "frames": 3,
    "graphs": [
      "graphs/default.json",
      { "graph": "graphs/default.json", "label": "swept", "set": { "lighting.pcf_radius": 2 },
        "sweep": { "ambient.radiance": [0.1, 0.2, 0.3], "composite.indirect_scale": [1, 2] } },
    ],
    )") + kReference + "}";
  const BenchSpec spec = parse(text);
  EXPECT_EQ(spec.name, "expansion");
  ASSERT_EQ(spec.resolutions.size(), 1u);
  EXPECT_EQ(spec.resolutions[0], (std::pair<uint32_t, uint32_t>{64, 32}));
  EXPECT_EQ(spec.warmup_frames, 1u);
  EXPECT_EQ(spec.frames, 3u);
  EXPECT_EQ(spec.graphs[0].label, "default") << "the graph file's stem by default";
  EXPECT_EQ(spec.reference.frames, 4u);

  const std::vector<BenchConfiguration> all = expand_configurations(spec);
  // 3 scene/camera pairs × (1 + 3 × 2) graph variants
  ASSERT_EQ(all.size(), 21u);
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].index, i);
  EXPECT_EQ(all[0].id, "c000");
  EXPECT_EQ(all[20].id, "c020");
  EXPECT_TRUE(all[0].overrides.empty());
  // The last sweep varies fastest; the fixed settings are in every variant.
  const std::map<std::string, std::string> second = {
      {"lighting.pcf_radius", "2"}, {"ambient.radiance", "0.1"}, {"composite.indirect_scale", "2"}};
  EXPECT_EQ(all[2].overrides, second);
  EXPECT_EQ(all[2].label(spec), "swept ambient.radiance=0.1 composite.indirect_scale=2");
  EXPECT_EQ(all[3].overrides.at("ambient.radiance"), "0.2");
  EXPECT_EQ(all[7].camera, "default");
  EXPECT_EQ(all[7].scene, 1u);
  EXPECT_EQ(all[14].camera, "side");
  EXPECT_EQ(all[0].width, 64u);
  EXPECT_EQ(all[0].height, 32u);
}

TEST(BenchSpec, DefaultsAndSeveralResolutions) {
  const BenchSpec spec = parse(std::string(R"({ "scenes": ["cornell"],
    "resolution": [[64, 64], [32, 16]], "graphs": ["graphs/default.json"], )") +
                               kReference + "}");
  EXPECT_EQ(spec.name, "test-bench") << "the bench file's stem";
  EXPECT_EQ(spec.scenes[0].cameras, std::vector<std::string>{"default"});
  const std::vector<BenchConfiguration> all = expand_configurations(spec);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].width, 32u);
  EXPECT_EQ(all[1].height, 16u);
  EXPECT_NE(spec.content_hash, parse(std::string(R"({ "scenes": ["cornell"],
    "resolution": [[64, 64]], "graphs": ["graphs/default.json"], )") +
                                     kReference + "}")
                                   .content_hash);
}

TEST(BenchSpec, MeasuredFramesChangeWhatTheFileSays) {
  const std::string rest =
      std::string(R"("scenes": ["cornell"], "graphs": ["graphs/default.json"], )") + kReference;
  EXPECT_EQ(parse("{" + rest + "}").changes, "none");
  EXPECT_EQ(parse(R"({ "changes": "lights", )" + rest + "}").changes, "lights");
  EXPECT_EQ(parse(R"({ "changes": "geometry", )" + rest + "}").changes, "geometry");
  const std::string message = error_of(R"({ "changes": "sometimes", )" + rest + "}");
  EXPECT_NE(message.find("field 'changes': unknown value 'sometimes'"), std::string::npos)
      << message;
  EXPECT_NE(message.find("\"lights\""), std::string::npos) << message;
}

TEST(BenchSpec, SweepValuesAreWrittenAsTheCommandLineTakesThem) {
  const BenchSpec spec = parse(std::string(R"({ "scenes": ["cornell"],
    "graphs": [{ "graph": "graphs/default.json",
                 "sweep": { "a.b": [64, 0.25, true, "Raw", -3, 1e-3] } }], )") +
                               kReference + "}");
  EXPECT_EQ(spec.graphs[0].sweeps[0].values,
            (std::vector<std::string>{"64", "0.25", "true", "Raw", "-3", "0.001"}));
}

TEST(BenchSpec, ShardsPartitionTheConfigurationsDeterministically) {
  const BenchSpec spec = parse(std::string(R"({ "scenes": ["cornell", "plane-spot"],
    "graphs": [{ "graph": "graphs/default.json", "sweep": { "x.y": [1, 2, 3, 4, 5] } }], )") +
                               kReference + "}");
  const std::vector<BenchConfiguration> all = expand_configurations(spec);
  ASSERT_EQ(all.size(), 10u);
  for (uint32_t n = 1; n <= 4; ++n) {
    std::multiset<size_t> seen;
    for (uint32_t i = 1; i <= n; ++i) {
      const std::vector<BenchConfiguration> part = select_shard(all, {i, n});
      const std::vector<BenchConfiguration> again = select_shard(all, {i, n});
      ASSERT_EQ(part.size(), again.size());
      for (size_t k = 0; k < part.size(); ++k) EXPECT_EQ(part[k].id, again[k].id);
      for (const BenchConfiguration& c : part) seen.insert(c.index);
    }
    EXPECT_EQ(seen.size(), all.size()) << "n = " << n;
    EXPECT_EQ(std::set<size_t>(seen.begin(), seen.end()).size(), all.size()) << "n = " << n;
  }
  const Shard shard = parse_shard("2/3");
  EXPECT_EQ(shard.index, 2u);
  EXPECT_EQ(shard.count, 3u);
  EXPECT_EQ(shard.text(), "2/3");
  for (const char* bad : {"0/2", "3/2", "1/0", "a/b", "2", "1/2/3", ""}) {
    EXPECT_THROW(parse_shard(bad), UsageError) << bad;
  }
}

TEST(BenchSpec, BadFilesNameFileLineColumnAndField) {
  struct Case {
    std::string text;
    std::string at;  // where the error points: the first occurrence of this text
    std::vector<std::string> parts;
  };
  const std::string ref = kReference;
  const std::vector<Case> cases = {
      {R"({ "scenes": ["cornell"], "grpahs": ["graphs/default.json"], )" + ref + "}",
       "\"grpahs\"",
       {"field 'grpahs': unknown field", "did you mean 'graphs'"}},
      {R"({ "scenes": ["cornel"], "graphs": ["graphs/default.json"], )" + ref + "}",
       "\"cornel\"",
       {"field 'scenes[0]'", "neither a .gltf/.glb file nor a built-in scene",
        "did you mean 'cornell'"}},
      {R"({ "scenes": ["missing/scene.gltf"], "graphs": ["graphs/default.json"], )" + ref + "}",
       "\"missing/scene.gltf\"",
       {"field 'scenes[0]'", "file 'missing/scene.gltf' not found"}},
      {R"({ "scenes": ["cornell"], "graphs": ["graphs/nope.json"], )" + ref + "}",
       "\"graphs/nope.json\"",
       {"field 'graphs[0]'", "file 'graphs/nope.json' not found"}},
      {R"({ "scenes": ["cornell", "spheres", "cornell"], "graphs": ["graphs/default.json"], )" +
           ref + "}",
       "\"cornell\"], \"graphs\"",
       {"field 'scenes[2]'", "scene 'cornell' is listed twice (first at line 1)"}},
      {R"({ "scenes": [{ "scene": "cornell", "cameras": ["default", "default"] }],
           "graphs": ["graphs/default.json"], )" +
           ref + "}",
       "{ \"scene\"",
       {"field 'scenes[0].cameras'", "camera 'default' is listed twice"}},
      {R"({ "scenes": ["cornell"], "graphs": [{ "graph": "graphs/vct.json", "sweep": {
             "voxel.resolution": [8, 16, 32, 64, 128, 256, 512, 8, 16, 32],
             "cone_trace.diffuse_cones": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10],
             "cone_trace.step_factor": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1],
             "cone_trace.normal_offset": [0, 1, 2, 3, 4, 5, 6, 7, 8, 0.5],
             "cone_trace.start_offset": [0, 1] } }], )" +
           ref + "}",
       "[{ \"graph\"",
       {"field 'graphs'", "make 20000 configurations, more than 10000 in one bench"}},
      {R"({ "scenes": ["cornell"], "graphs": [{ "graph": "graphs/default.json",
           "sweep": { "ambient.radiance": 0.5 } }], )" +
           ref + "}",
       "0.5",
       {"field 'graphs[0].sweep.ambient.radiance': expected an array"}},
      {R"({ "scenes": ["cornell"], "graphs": [{ "graph": "graphs/default.json",
           "sweep": { "ambient.radiance": [] } }], )" +
           ref + "}",
       "[] ",
       {"field 'graphs[0].sweep.ambient.radiance': must not be empty"}},
      {R"({ "scenes": ["cornell"], "resolution": [64], "graphs": ["graphs/default.json"], )" + ref +
           "}",
       "[64]",
       {"field 'resolution': expected [width, height]"}},
      {R"({ "scenes": ["cornell"], "frames": 0, "graphs": ["graphs/default.json"], )" + ref + "}",
       "0,",
       {"field 'frames': expected an integer in [1, 100000], found 0"}},
      {R"({ "scenes": ["cornell"], "graphs": ["graphs/default.json", "graphs/default.json"], )" +
           ref + "}",
       "\"graphs/default.json\"]",
       {"field 'graphs[1]'", "label 'default' is used twice"}},
      {R"({ "scenes": ["cornell"], "graphs": ["graphs/default.json"],
            "reference": { "graph": "graphs/default.json" } })",
       "{ \"graph\": \"graphs/default.json\" }",
       {"field 'reference.frames': missing (required)"}},
      {R"({ "scenes": ["cornell"], "graphs": ["graphs/default.json"] })",
       "{",
       {"field 'reference': missing (required)"}},
      {R"({ "scenes": ["cornell"], "graphs": [{ "graph": "graphs/default.json",
           "set": { "a.b": 1 }, "sweep": { "a.b": [1, 2] } }], )" +
           ref + "}",
       "\"a.b\": [",
       {"field 'graphs[0].sweep.a.b': is both set and swept"}},
      {R"({ "scenes": ["cornell"], "graphs": [{ "graph": "graphs/default.json",
           "set": { "a.b": [1] } }], )" +
           ref + "}",
       "[1]",
       {"field 'graphs[0].set.a.b': expected a number, bool or string, found"}},
      {R"({ "scenes": ["cornell"] "graphs": [] })", "\"graphs\"", {"error:"}},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.text);
    ASSERT_FALSE(message.empty()) << "no error for:\n" << c.text;
    EXPECT_NE(message.find(location_of(c.text, c.at) + ": error: "), std::string::npos)
        << "expected the location " << location_of(c.text, c.at) << " in:\n"
        << message;
    for (const std::string& part : c.parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "missing \"" << part << "\" in:\n"
                                                       << message;
    }
  }
}

TEST(BenchSpec, EveryProblemIsReportedAtOnce) {
  const std::string message = error_of(R"({ "scenes": ["cornel"], "frames": -1,
    "graphs": ["graphs/nope.json"], "reference": { "graph": "graphs/default.json", "frames": 1 } })");
  for (const char* part : {"scenes[0]", "field 'frames'", "graphs[0]"}) {
    EXPECT_NE(message.find(part), std::string::npos) << part << " in:\n" << message;
  }
}

TEST(BenchSpec, TheShippedBenchFilesParse) {
  for (const char* name :
       {"graphs/bench.json", "docs/bench-report/bench.json", "docs/lpv-bench/bench.json",
        "docs/bench-gltf-box/bench.json", "tests/bench/bench-ci.json"}) {
    const std::filesystem::path file = kRepo / name;
    if (std::string(name) != "tests/bench/bench-ci.json" &&
        !std::filesystem::exists(std::filesystem::path(VOXGI_SHARED_DIR) / "scenes")) {
      std::cout << "skipping " << name << ": it uses scenes from " << VOXGI_SHARED_DIR
                << "/scenes, which is absent\n";
      continue;
    }
    const BenchSpec spec = load_bench_file(file, kRepo);
    EXPECT_FALSE(expand_configurations(spec).empty()) << name;
  }
}

}  // namespace
}  // namespace voxgi::cli
