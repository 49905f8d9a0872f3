// `voxgi bench` end to end on the Vulkan device with a tiny bench (one scene, two
// configurations, 64x64, a few frames): every output file, the report agreeing with
// results.json, the reference cache, and shards + merge against an unsharded run.

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>
#include <sstream>

#include "engine/image/image.hpp"
#include "tests/apps/voxgi_cli_fixture.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The reference path tracer's graph when it is in the tree, else the default graph with a
// brighter ambient term, so that the two configurations have a non-zero error either way.
std::string reference_entry() {
  if (fs::exists(fs::path(VOXGI_SOURCE_DIR) / "graphs" / "reference.json")) {
    return R"("reference": { "graph": "graphs/reference.json", "frames": 4 })";
  }
  return R"("reference": { "graph": "graphs/default.json", "frames": 2,
                           "set": { "ambient.radiance": 0.08 } })";
}

std::string tiny_bench() {
  return R"({
  "name": "tiny",
  "scenes": ["cornell"],
  "resolution": [64, 64],
  "warmup_frames": 1,
  "frames": 3,
  "graphs": [
    { "graph": "graphs/default.json", "label": "ambient",
      "sweep": { "ambient.radiance": [0.02, 0.05] } }
  ],
  )" + reference_entry() +
         "\n}\n";
}

json read_json(const fs::path& path) {
  return json::parse(read_text(path));
}

std::vector<std::string> split_cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  for (size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|') {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return cells;
}

// The report shows 4 significant digits.
::testing::AssertionResult same_number(const std::string& shown, double value) {
  const double parsed = std::stod(shown);
  if (std::fabs(parsed - value) <= 5e-4 * std::fabs(value) + 1e-12) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "report shows " << shown << ", results.json has " << value;
}

class VoxgiBench : public VoxgiCli {
 protected:
  void SetUp() override {
    VoxgiCli::SetUp();
    write_text(dir_ / "tiny.json", tiny_bench());
  }
  ProcessResult bench(const std::string& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"bench", "tiny.json",   "--out", out, "--reference-cache",
                                     "cache", "--validation"};
    args.insert(args.end(), extra.begin(), extra.end());
    ProcessOptions options;
    options.timeout = std::chrono::milliseconds(120000);
    return voxgi(args, options);
  }
};

TEST_F(VoxgiBench, TinyBenchWritesEveryOutputAndTheReportAgreesWithResults) {
  const ProcessResult r = bench("out");
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stderr_has(r, {"voxgi: device: ", "2 of 2 configurations",
                             "reference for cornell / default / 64x64: not cached, rendering",
                             "[1/2] c000 ambient ambient.radiance=0.02", "[2/2] c001",
                             "voxgi: wrote out/results.json"}));
  for (const char* file :
       {"results.json", "results.csv", "report.md", "charts/heat-scale.svg",
        "charts/group0-error-vs-time.svg", "charts/group0-pass-times.svg", "images/c000.png",
        "images/c000-error.png", "images/c001.png", "images/c001-error.png"}) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / file)) << file;
  }
  const json results = read_json(dir_ / "out" / "results.json");
  ASSERT_EQ(results["results"].size(), 2u);
  EXPECT_EQ(results["configurations_total"], 2);
  EXPECT_TRUE(results["missing"].empty());
  const std::string report = read_text(dir_ / "out" / "report.md");
  const std::string csv = read_text(dir_ / "out" / "results.csv");
  for (const json& item : results["results"]) {
    const std::string id = item["id"];
    SCOPED_TRACE(id);
    EXPECT_EQ(item["reference_cache_hit"], false);
    EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / item["images"]["reference"].get<std::string>()));
    const json& full = item["metrics"]["full"];
    ASSERT_TRUE(full.is_object());
    EXPECT_GT(full["rel_mse"].get<double>(), 0.0) << "the reference differs from both";
    EXPECT_GT(full["ssim_luminance"].get<double>(), 0.0);
    EXPECT_LE(full["ssim_luminance"].get<double>(), 1.0);
    EXPECT_EQ(full["non_finite_pixels"], 0);
    EXPECT_EQ(full["compared_pixels"], 64 * 64);
    ASSERT_TRUE(item["metrics"]["indirect"].is_object()) << "both graphs have `indirect`";
    EXPECT_GT(item["gpu_ms"]["median"].get<double>(), 0.0) << "timestamps were read";
    EXPECT_LE(item["gpu_ms"]["p10"].get<double>(), item["gpu_ms"]["median"].get<double>());
    EXPECT_LE(item["gpu_ms"]["median"].get<double>(), item["gpu_ms"]["p90"].get<double>());
    EXPECT_FALSE(item["passes"].empty());

    // The report's table row for this configuration shows results.json's numbers.
    const size_t at = report.find("| " + id + " |");
    ASSERT_NE(at, std::string::npos) << report;
    const std::vector<std::string> cells =
        split_cells(report.substr(at, report.find('\n', at) - at));
    // id | technique | settings | GPU ms | p10–p90 | relMSE | RMSE | SSIM | FLIP | bias |
    // indirect | nf | GPU MiB
    ASSERT_EQ(cells.size(), 13u) << report.substr(at, 200);
    ASSERT_GT(item["gpu_memory_bytes"].get<uint64_t>(), 0u);
    EXPECT_TRUE(same_number(cells[12], item["gpu_memory_bytes"].get<double>() / (1 << 20)));
    EXPECT_EQ(cells[1], "ambient");
    EXPECT_NE(cells[2].find("ambient.radiance=" +
                            item["overrides"]["ambient.radiance"].get<std::string>()),
              std::string::npos);
    EXPECT_TRUE(same_number(cells[3], item["gpu_ms"]["median"]));
    const size_t dash = cells[4].find("–");
    ASSERT_NE(dash, std::string::npos);
    EXPECT_TRUE(same_number(cells[4].substr(0, dash), item["gpu_ms"]["p10"]));
    EXPECT_TRUE(
        same_number(cells[4].substr(dash + std::string("–").size()), item["gpu_ms"]["p90"]));
    EXPECT_TRUE(same_number(cells[5], full["rel_mse"]));
    EXPECT_TRUE(same_number(cells[6], full["rmse"]));
    EXPECT_TRUE(same_number(cells[7], full["ssim_luminance"]));
    EXPECT_TRUE(same_number(cells[8], full["hdr_flip"]));
    EXPECT_GT(full["hdr_flip"].get<double>(), 0.0);
    EXPECT_TRUE(same_number(cells[9], full["luminance_bias"]));
    EXPECT_TRUE(same_number(cells[10], item["metrics"]["indirect"]["rel_mse"]));
    EXPECT_EQ(cells[11], "0");
    EXPECT_TRUE(item["same_bounce"].is_null()) << "the default graph declares no bounces";
    EXPECT_NE(report.find("src=\"" + item["images"]["heat_map"].get<std::string>() + "\""),
              std::string::npos);
    std::ostringstream csv_row;
    csv_row << "\n" << item["index"].get<int>() << "," << id << ",";
    EXPECT_NE(csv.find(csv_row.str()), std::string::npos);
  }
  // A brighter ambient term is closer to the reference's brighter one.
  EXPECT_LT(results["results"][1]["metrics"]["full"]["rel_mse"].get<double>(),
            results["results"][0]["metrics"]["full"]["rel_mse"].get<double>());
}

TEST_F(VoxgiBench, ASecondRunHitsTheReferenceCache) {
  ASSERT_TRUE(exited_with(bench("first"), 0));
  const ProcessResult second = bench("second");
  ASSERT_TRUE(exited_with(second, 0));
  EXPECT_TRUE(stderr_has(second, {"reference for cornell / default / 64x64: cache hit"}));
  EXPECT_FALSE(contains(second.err, "not cached")) << second.describe();
  const json first = read_json(dir_ / "first" / "results.json");
  const json again = read_json(dir_ / "second" / "results.json");
  ASSERT_EQ(again["results"].size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again["results"][i]["reference_cache_hit"], true);
    EXPECT_EQ(again["results"][i]["reference_key"], first["results"][i]["reference_key"]);
    // The cache stores 32-bit floats: the comparison is the same as with the fresh reference.
    EXPECT_NEAR(again["results"][i]["metrics"]["full"]["rel_mse"].get<double>(),
                first["results"][i]["metrics"]["full"]["rel_mse"].get<double>(),
                1e-9 + 1e-6 * first["results"][i]["metrics"]["full"]["rel_mse"].get<double>());
  }
}

TEST_F(VoxgiBench, ShardsAndMergeEqualTheUnshardedRun) {
  ASSERT_TRUE(exited_with(bench("all"), 0));
  const ProcessResult one = bench("shard1", {"--shard", "1/2"});
  ASSERT_TRUE(exited_with(one, 0));
  EXPECT_TRUE(stderr_has(one, {"1 of 2 configurations (shard 1/2)"}));
  ASSERT_TRUE(exited_with(bench("shard2", {"--shard", "2/2"}), 0));
  const ProcessResult merge = voxgi({"bench", "merge", "merged", "shard2", "shard1"});
  ASSERT_TRUE(exited_with(merge, 0));
  EXPECT_TRUE(stderr_has(merge, {"2 of 2 configurations from 2 shard folder(s)"}));
  EXPECT_FALSE(contains(merge.err, "warning")) << merge.describe();

  const json all = read_json(dir_ / "all" / "results.json");
  const json merged = read_json(dir_ / "merged" / "results.json");
  auto configurations = [](const json& doc) {
    std::set<std::string> set;
    for (const json& item : doc["results"]) {
      set.insert(item["id"].get<std::string>() + " " + item["label"].get<std::string>() + " " +
                 item["overrides"].dump() + " " + item["reference_key"].get<std::string>());
    }
    return set;
  };
  EXPECT_EQ(configurations(merged), configurations(all));
  EXPECT_EQ(merged["configurations_total"], 2);
  EXPECT_TRUE(merged["missing"].empty());
  EXPECT_EQ(merged["shards"], json::array({"2/2", "1/2"}));
  EXPECT_EQ(merged["results"][0]["id"], "c000") << "merged results are in configuration order";
  for (const json& item : merged["results"]) {
    for (const char* image : {"image", "reference", "heat_map"}) {
      EXPECT_TRUE(fs::is_regular_file(dir_ / "merged" / item["images"][image].get<std::string>()))
          << image;
    }
  }
  EXPECT_TRUE(fs::is_regular_file(dir_ / "merged" / "report.md"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "merged" / "results.csv"));

  // A shard of another bench is refused.
  write_text(dir_ / "tiny.json", tiny_bench() + "// changed\n");
  ASSERT_TRUE(exited_with(bench("other", {"--shard", "1/2"}), 0));
  const ProcessResult mixed = voxgi({"bench", "merge", "mixed", "shard2", "other"});
  EXPECT_TRUE(exited_with(mixed, 1));
  EXPECT_TRUE(stderr_has(mixed, {"'other' comes from a different bench file"}));
}

// vct (one bounce) and dvs (K + 1 bounces) against the path tracer limited to as many bounces
// and diffuse-only materials, and against the full reference split as they split; then the same
// bench against that reference given as image files.
// "changes": "lights" measures frames in which a light moves: the LPV's change-driven passes
// run in every measured frame instead of skipping, the voxelization still skips, and the
// report says what was measured.
TEST_F(VoxgiBench, ChangedLightsRerunTheChangeDrivenPasses) {
  const auto run = [&](const std::string& name, const std::string& changes) {
    write_text(dir_ / (name + ".json"), R"({ "scenes": ["cornell"], "resolution": [32, 32],
      "warmup_frames": 1, "frames": 2, )" + changes +
                                            R"(
      "graphs": [{ "graph": "graphs/lpv.json", "set": { "voxel.resolution": 16,
                   "lpv.iterations": 4, "lpv.rsm_resolution": 32 } }],
      "reference": { "graph": "graphs/default.json", "frames": 1 } })");
    ProcessOptions options;
    options.timeout = std::chrono::milliseconds(120000);
    const ProcessResult r = voxgi(
        {"bench", name + ".json", "--out", name, "--reference-cache", "cache", "--validation"},
        options);
    EXPECT_TRUE(exited_with(r, 0));
    return read_json(dir_ / name / "results.json");
  };
  const auto skipped = [](const json& results, const std::string& pass) -> int {
    for (const json& p : results["results"][0]["passes"]) {
      if (p["pass"] == pass) return p["skipped_frames"].get<int>();
    }
    ADD_FAILURE() << "no pass " << pass;
    return -1;
  };
  const json moving = run("moving", R"("changes": "lights",)");
  EXPECT_EQ(moving["changes"], "lights");
  for (const char* pass : {"rsm", "inject", "downsample", "propagate", "merge"}) {
    EXPECT_EQ(skipped(moving, pass), 0) << pass;
  }
  EXPECT_EQ(skipped(moving, "voxelize"), 2);
  EXPECT_NE(read_text(dir_ / "moving" / "report.md").find("the lights change in each one"),
            std::string::npos);
  const json still = run("still", "");
  EXPECT_EQ(still["changes"], "none");
  EXPECT_EQ(skipped(still, "propagate"), 2);
}

TEST_F(VoxgiBench, GiGraphsAreComparedLikeWithLikeAndWithImageReferences) {
  if (!fs::exists(fs::path(VOXGI_SOURCE_DIR) / "graphs" / "reference.json")) {
    GTEST_SKIP() << "needs the reference path tracer graph";
  }
  const std::string graphs = R"(
  "scenes": ["cornell"], "resolution": [32, 32], "warmup_frames": 1, "frames": 2,
  "graphs": [
    { "graph": "graphs/vct.json", "set": { "voxel.resolution": 32, "voxel.levels": 1 } },
    { "graph": "graphs/dvs.json", "set": { "voxel.resolution": 32 },
      "sweep": { "dvs.bounces": [0, 1] } } ],)";
  write_text(dir_ / "gi.json", "{" + graphs + R"(
  "reference": { "graph": "graphs/reference.json", "frames": 4,
                 "set": { "path_tracer.deferred_layers": true,
                          "path_tracer.pixel_jitter": false } } })");
  ProcessOptions options;
  options.timeout = std::chrono::milliseconds(300000);
  const ProcessResult r = voxgi(
      {"bench", "gi.json", "--out", "gi", "--reference-cache", "cache", "--validation"}, options);
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stderr_has(r, {"same-bounce reference (path_tracer.lambert=true "
                             "path_tracer.max_depth=2 path_tracer.single_sided=true) for cornell / "
                             "default / 32x32: not cached",
                             "same-bounce reference (path_tracer.lambert=true "
                             "path_tracer.max_depth=3 path_tracer.single_sided=true) for cornell / "
                             "default / 32x32: not cached"}));
  const json results = read_json(dir_ / "gi" / "results.json");
  ASSERT_EQ(results["results"].size(), 3u);
  const std::string report = read_text(dir_ / "gi" / "report.md");
  const size_t table = report.find("### Indirect light, like with like");
  ASSERT_NE(table, std::string::npos) << report;
  const uint32_t bounces[] = {1, 1, 2};
  for (size_t i = 0; i < 3; ++i) {
    const json& item = results["results"][i];
    SCOPED_TRACE(item["label"].get<std::string>());
    const json& same = item["same_bounce"];
    ASSERT_TRUE(same.is_object());
    EXPECT_EQ(same["bounces"], bounces[i]);
    EXPECT_EQ(same["brdf"], "diffuse");
    EXPECT_EQ(same["reference_set"]["path_tracer.max_depth"], std::to_string(bounces[i] + 1));
    EXPECT_EQ(same["reference_set"]["path_tracer.lambert"], "true");
    EXPECT_EQ(same["reference_set"]["path_tracer.deferred_layers"], "true");
    EXPECT_EQ(same["reference_set"]["path_tracer.pixel_jitter"], "false");
    EXPECT_EQ(same["reference_set"]["path_tracer.single_sided"], "true")
        << "the shipped voxel graphs light single-sided materials on their front only";
    EXPECT_EQ(same["faces"], "front");
    // The bench's reference already splits as the techniques do: it is the full one.
    EXPECT_EQ(same["full_reference_key"], item["reference_key"]);
    EXPECT_EQ(same["full_indirect"], item["metrics"]["indirect"]);
    ASSERT_TRUE(same["indirect"].is_object());
    EXPECT_EQ(same["indirect"]["compared_pixels"], 32 * 32);
    // The same-bounce reference's own noise (4 frames: large, but finite and positive).
    ASSERT_TRUE(same["reference_noise_rel_mse"].is_number()) << same.dump();
    EXPECT_GT(same["reference_noise_rel_mse"].get<double>(), 0.0);
    EXPECT_TRUE(std::isfinite(same["reference_noise_rel_mse"].get<double>()));
    EXPECT_GT(same["indirect"]["hdr_flip"].get<double>(), 0.0);
    const double missing = same["missing_fraction"].get<double>();
    EXPECT_GT(missing, 0.0) << "further bounces and the full BRDF add light";
    EXPECT_LT(missing, 1.0);
    const size_t row = report.find("| " + item["id"].get<std::string>() + " |", table);
    ASSERT_NE(row, std::string::npos);
    const std::vector<std::string> cells =
        split_cells(report.substr(row, report.find('\n', row) - row));
    ASSERT_EQ(cells.size(), 12u);
    EXPECT_EQ(cells[3], std::to_string(bounces[i]) + ", diffuse, front faces");
    EXPECT_TRUE(same_number(cells[5], same["indirect"]["rel_mse"]));
    EXPECT_TRUE(same_number(cells[6], same["reference_noise_rel_mse"]));
    EXPECT_TRUE(same_number(cells[11], missing));
  }
  const json& c0 = results["results"][0]["same_bounce"];
  EXPECT_EQ(c0["reference_key"], results["results"][1]["same_bounce"]["reference_key"])
      << "vct and dvs with no voxel bounce share their one-bounce reference";
  EXPECT_NE(c0["reference_key"], results["results"][2]["same_bounce"]["reference_key"]);
  EXPECT_LT(results["results"][2]["same_bounce"]["missing_fraction"].get<double>(),
            c0["missing_fraction"].get<double>())
      << "a second bounce leaves less out";
  EXPECT_NE(read_text(dir_ / "gi" / "results.csv").find(",1,diffuse,"), std::string::npos);

  // The same reference as image files (as another renderer would give it).
  const fs::path entry = dir_ / "cache" / results["results"][0]["reference_key"].get<std::string>();
  fs::copy_file(entry / "linear.exr", dir_ / "full.exr");
  fs::copy_file(entry / "indirect.exr", dir_ / "indirect.exr");
  write_text(dir_ / "image.json", "{" + graphs + R"(
  "reference": { "image": "full.exr", "indirect": "indirect.exr",
                 "graph": "graphs/reference.json", "frames": 4 } })");
  const ProcessResult again =
      voxgi({"bench", "image.json", "--out", "image", "--reference-cache", "cache"}, options);
  ASSERT_TRUE(exited_with(again, 0));
  EXPECT_FALSE(contains(again.err, "not cached")) << "the same-bounce references are cached";
  const json from_image = read_json(dir_ / "image" / "results.json");
  EXPECT_EQ(from_image["reference"]["graph"], "full.exr");
  EXPECT_EQ(from_image["reference"]["frames"], 0);
  EXPECT_NE(read_text(dir_ / "image" / "report.md").find("- reference: image `full.exr`"),
            std::string::npos);
  for (size_t i = 0; i < 3; ++i) {
    const json& a = results["results"][i];
    const json& b = from_image["results"][i];
    EXPECT_NEAR(b["metrics"]["full"]["rel_mse"].get<double>(),
                a["metrics"]["full"]["rel_mse"].get<double>(), 1e-9);
    EXPECT_NEAR(b["same_bounce"]["missing_fraction"].get<double>(),
                a["same_bounce"]["missing_fraction"].get<double>(), 1e-9);
    EXPECT_EQ(b["same_bounce"]["full_reference_key"], b["reference_key"]);
    EXPECT_TRUE(fs::is_regular_file(dir_ / "image" / b["images"]["reference"].get<std::string>()));
  }
}

}  // namespace
}  // namespace voxgi::test
