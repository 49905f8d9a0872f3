// `voxgi bench` with bad bench files and arguments: one clear message naming the file, line,
// column and field, a non-zero exit, and no rendering (the checks run before a device opens).
// Also `voxgi bench bvh` and `voxgi bench voxel-light`, which need no device either.

#include <cmath>
#include <sstream>

#include "engine/image/image.hpp"
#include "tests/apps/voxgi_cli_fixture.hpp"

namespace voxgi::test {
namespace {

class VoxgiBenchErrors : public VoxgiCli {
 protected:
  // Writes `text` as bad.json in the test folder and runs `voxgi bench bad.json`.
  ProcessResult bench_text(const std::string& text, std::vector<std::string> extra = {}) {
    write_text(dir_ / "bad.json", text);
    std::vector<std::string> args = {"bench", "bad.json", "--out", "out"};
    args.insert(args.end(), extra.begin(), extra.end());
    return voxgi(args);
  }
  std::string where(const std::string& text, const std::string& part) {
    return "bad.json:" + std::to_string(line_of(text, part)) + ":";
  }
};

constexpr const char* kReference =
    R"("reference": { "graph": "graphs/default.json", "frames": 2 })";

TEST_F(VoxgiBenchErrors, WrongCommandLines) {
  EXPECT_TRUE(exited_with(voxgi({"bench"}), 2));
  const ProcessResult missing = voxgi({"bench", "missing.json"});
  EXPECT_TRUE(exited_with(missing, 1));
  EXPECT_TRUE(stderr_has(missing, {"missing.json: error: cannot open the bench file"}));
  const ProcessResult shard = bench_text(std::string(R"({ "scenes": ["cornell"],
    "graphs": ["graphs/default.json"], )") + kReference +
                                             "}",
                                         {"--shard", "3/2"});
  EXPECT_TRUE(exited_with(shard, 2));
  EXPECT_TRUE(stderr_has(shard, {"--shard '3/2': expected i/n with 1 <= i <= n"}));
  const ProcessResult option = voxgi({"bench", "x.json", "--sahrd", "1/2"});
  EXPECT_TRUE(exited_with(option, 2));
  EXPECT_TRUE(stderr_has(option, {"unknown option '--sahrd'", "did you mean '--shard'"}));
  const ProcessResult typo = voxgi({"bench", "mrege", "out", "shard1"});
  EXPECT_TRUE(exited_with(typo, 2));
  EXPECT_TRUE(stderr_has(typo, {"no bench file 'mrege' (did you mean 'voxgi bench merge'?)"}));
  EXPECT_TRUE(exited_with(voxgi({"bench", "merge", "out"}), 2));
  const ProcessResult merge = voxgi({"bench", "merge", "out", "no-such-shard"});
  EXPECT_TRUE(exited_with(merge, 1));
  EXPECT_TRUE(stderr_has(merge, {"no-such-shard/results.json: cannot read"}));
  std::filesystem::create_directories(dir_ / "broken");
  write_text(dir_ / "broken" / "results.json", "{ not json");
  const ProcessResult broken = voxgi({"bench", "merge", "out", "broken"});
  EXPECT_TRUE(exited_with(broken, 1));
  EXPECT_TRUE(stderr_has(broken, {"broken/results.json: not valid JSON"}));
}

TEST_F(VoxgiBenchErrors, BadBenchFilesNameTheSpot) {
  const std::string syntax = "{\n  \"scenes\": [\"cornell\"]\n  \"graphs\": []\n}\n";
  ProcessResult r = bench_text(syntax);
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(r, {"bad.json:3:", "error:"}));

  const std::string unknown = std::string("{\n  \"scenes\": [\"cornell\"],\n") +
                              "  \"graphs\": [\"graphs/default.json\"],\n  \"frmaes\": 2,\n  " +
                              kReference + "\n}\n";
  r = bench_text(unknown);
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(r, {where(unknown, "\"frmaes\"") + "3: error: field 'frmaes': unknown",
                             "did you mean 'frames'"}));
  EXPECT_FALSE(contains(r.err, "voxgi: device:")) << "no device is opened for a bad bench file";
}

TEST_F(VoxgiBenchErrors, UnknownSweptParametersAndCamerasAreFoundBeforeRendering) {
  const std::string sweep = std::string("{\n  \"scenes\": [\"cornell\"],\n  \"graphs\": [\n") +
                            "    { \"graph\": \"graphs/default.json\",\n" +
                            "      \"sweep\": { \"ambient.radiancee\": [0.1, 0.2] } }\n  ],\n  " +
                            kReference + "\n}\n";
  ProcessResult r = bench_text(sweep);
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(
      r, {where(sweep, "{ \"graph\"") + "5: error: field 'graphs[0]'", "configuration c000",
          "ambient.radiancee", "did you mean 'ambient.radiance'"}));
  EXPECT_FALSE(contains(r.err, "voxgi: device:"));

  const std::string camera = std::string("{\n  \"scenes\": [\n") +
                             "    { \"scene\": \"cornell\", \"cameras\": [\"nope\"] }\n  ],\n" +
                             "  \"graphs\": [\"graphs/default.json\"],\n  " + kReference + "\n}\n";
  r = bench_text(camera);
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(r, {where(camera, "{ \"scene\"") + "5: error: field 'scenes[0].cameras'",
                             "has no camera 'nope'"}));

  const std::string reference = std::string("{\n  \"scenes\": [\"cornell\"],\n") +
                                "  \"graphs\": [\"graphs/default.json\"],\n" +
                                "  \"reference\": { \"graph\": \"graphs/default.json\", " +
                                "\"frames\": 2,\n    \"set\": { \"nope.param\": 1 } }\n}\n";
  r = bench_text(reference);
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(
      r, {where(reference, "\"reference\"") + "16: error: field 'reference'", "nope.param"}));
}

TEST_F(VoxgiBenchErrors, CheckListsTheConfigurationsAndRendersNothing) {
  write_text(dir_ / "two.json", std::string(R"({ "scenes": ["cornell"], "resolution": [32, 32],
    "graphs": [{ "graph": "graphs/default.json", "sweep": { "ambient.radiance": [0.1, 0.2] } }],
    )") + kReference + "}");
  const ProcessResult r = voxgi({"bench", "two.json", "--check", "--out", "never"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(r, {"two.json: 2 of 2 configurations",
                             "c000  default ambient.radiance=0.1  on cornell / default / 32x32",
                             "c001  default ambient.radiance=0.2"}));
  EXPECT_FALSE(contains(r.err, "voxgi: device:"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "never"));
}

// Reference images from another renderer: a missing, unreadable, wrongly sized or misnamed
// file is one located message before any device opens.
TEST_F(VoxgiBenchErrors, BadReferenceImagesNameTheFileAndField) {
  image::write_exr(dir_ / "ref64.exr", image::ImageRGBA32F(64, 64), image::ExrPixelType::Float);
  image::write_exr(dir_ / "ref32.exr", image::ImageRGBA32F(32, 32), image::ExrPixelType::Float);
  write_text(dir_ / "broken.exr", "not an image");
  const auto bench_with = [&](const std::string& reference) {
    const std::string text =
        std::string("{\n  \"scenes\": [\"cornell\"],\n") + "  \"resolution\": [64, 64],\n" +
        "  \"graphs\": [\"graphs/default.json\"],\n" + "  \"reference\": " + reference + "\n}\n";
    return std::make_pair(text, bench_text(text));
  };
  struct Case {
    std::string reference, at;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {R"({ "image": "ref32.exr" })",
       "\"ref32.exr\"",
       {"field 'reference.image': 'ref32.exr' is 32x32 but configuration c000 renders 64x64"}},
      {R"({ "image": "ref64.exr", "indirect": "ref32.exr" })",
       "\"ref32.exr\"",
       {"field 'reference.indirect': 'ref32.exr' is 32x32 but the image 'ref64.exr' is 64x64"}},
      {R"({ "image": "nope.exr" })",
       "\"nope.exr\"",
       {"field 'reference.image': file 'nope.exr' not found"}},
      {R"({ "image": "broken.exr" })",
       "\"broken.exr\"",
       {"field 'reference.image': cannot read 'broken.exr'"}},
      {R"({ "image": "ref64.png" })",
       "\"ref64.png\"",
       {"field 'reference.image': 'ref64.png': expected a linear OpenEXR image (.exr)"}},
      {R"({ "indirect": "ref64.exr" })",
       "\"ref64.exr\"",
       {"field 'reference.indirect': an indirect image needs the full one beside it"}},
      {R"({ "frames": 2 })",
       "{ \"frames\"",
       {"field 'reference.graph': missing (required unless the reference is an image file"}},
  };
  for (const Case& c : cases) {
    const auto [text, r] = bench_with(c.reference);
    SCOPED_TRACE(c.reference);
    EXPECT_TRUE(exited_with(r, 1));
    const size_t column = text.find(c.at) - text.rfind('\n', text.find(c.at));
    std::vector<std::string> parts = c.parts;
    parts.push_back(where(text, c.at) + std::to_string(column) + ": error: ");
    EXPECT_TRUE(stderr_has(r, parts));
    EXPECT_FALSE(contains(r.err, "voxgi: device:"));
  }
}

TEST_F(VoxgiBenchErrors, CheckListsTheSameBounceReferences) {
  write_text(dir_ / "gi.json", std::string(R"({ "scenes": ["cornell"], "resolution": [32, 32],
    "graphs": [{ "graph": "graphs/vct.json", "set": { "voxel.resolution": 32, "voxel.levels": 1 } },
               { "graph": "graphs/dvs.json", "sweep": { "dvs.bounces": [0, 3] } },
               "graphs/default.json"],
    "reference": { "graph": "graphs/reference.json", "frames": 2,
                   "set": { "path_tracer.deferred_layers": true } } })"));
  const ProcessResult r = voxgi({"bench", "gi.json", "--check"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(
      r, {"c000  vct  on cornell / default / 32x32  (reference ",
          "indirect: 1 bounce, diffuse, front faces; same-bounce reference "
          "(path_tracer.lambert=true path_tracer.max_depth=2 path_tracer.pixel_jitter=false "
          "path_tracer.single_sided=true) ",
          "c001  dvs dvs.bounces=0", "c002  dvs dvs.bounces=3",
          "indirect: 4 bounces, diffuse, front faces; same-bounce reference "
          "(path_tracer.lambert=true path_tracer.max_depth=5 path_tracer.pixel_jitter=false "
          "path_tracer.single_sided=true) "}));
  // The default graph declares nothing: no same-bounce reference on its line.
  const size_t line = r.out.find("c003  default");
  ASSERT_NE(line, std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("indirect:", line), std::string::npos) << r.out;
}

TEST_F(VoxgiBenchErrors, TheShippedBenchChecksOut) {
  if (!std::filesystem::exists(std::filesystem::path(VOXGI_SHARED_DIR) / "scenes")) {
    GTEST_SKIP() << "graphs/bench.json uses scenes from " << VOXGI_SHARED_DIR
                 << "/scenes, which is absent";
  }
  // Shard 1 holds configuration c000, the first graph (ambient) on the first scene.
  const ProcessResult r = voxgi({"bench", "graphs/bench.json", "--check", "--shard", "1/3"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(
      stdout_has(r, {"bench.json: ", "(shard 1/3)", "ambient", "sponza-dabrovic / atrium"}));
}

TEST_F(VoxgiBenchErrors, BvhStatisticsOfABuiltInScene) {
  const ProcessResult r = voxgi({"bench", "bvh", "--scene", "cornell", "--repeat", "3"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(r, {"triangles", "SAH cost", "build ms", "median of 3"}));
  const ProcessResult bad = voxgi({"bench", "bvh", "--scene", "nope.glb"});
  EXPECT_TRUE(exited_with(bad, 1));
  EXPECT_TRUE(stderr_has(bad, {"nope.glb"}));
}

// The injected-light models are exact for voxels that hold one plane (the floor of
// plane-directional, away from its box), and the command names a scene it cannot measure.
TEST_F(VoxgiBenchErrors, VoxelLightOfABuiltInScene) {
  const ProcessResult r = voxgi({"bench", "voxel-light", "--scene", "plane-directional",
                                 "--voxel-mm", "100", "--sizes", "2"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(
      stdout_has(r, {"edge m", "all", "facing", "area", "groups", "by area", "[0.95,1.00)"}));
  // Each row: edge, voxels, exact, biases; then per band "[a,b) share all facing area groups
  // by-area".
  std::istringstream lines(r.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    const size_t band = line.find("[0.95,1.00)");
    if (line.find('|') == std::string::npos || band == std::string::npos) continue;
    std::istringstream fields(line.substr(band + 11));
    std::string share, all, facing, area, groups, by_area;
    fields >> share >> all >> facing >> area >> groups >> by_area;
    for (const std::string& bias : {all, facing, area, groups, by_area}) {
      EXPECT_LT(std::abs(std::stod(bias)), 0.2) << line;
    }
    ++rows;
  }
  EXPECT_EQ(rows, 2) << r.out;
  const ProcessResult none = voxgi({"bench", "voxel-light", "--scene", "cornell"});
  EXPECT_TRUE(exited_with(none, 1));
  EXPECT_TRUE(stderr_has(none, {"cornell", "no directional light"}));
  // More surface points than memory allows is refused before any is made.
  const ProcessResult huge = voxgi({"bench", "voxel-light", "--scene", "plane-directional",
                                    "--voxel-mm", "1", "--samples", "1024"});
  EXPECT_FALSE(exited_with(huge, 0));
  EXPECT_TRUE(stderr_has(huge, {"--voxel-mm", "--samples", "surface points"}));
}

}  // namespace
}  // namespace voxgi::test
