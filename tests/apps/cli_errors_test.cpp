// `voxgi` runs that need no Vulkan device: bad input must end in one message that names the file
// and the field or option, with exit code 2 for a wrong command line and 1 for everything else.
// Each run fails before the device is opened ("voxgi: device:" is printed once it is).

#include <regex>

#include "tests/apps/voxgi_cli_fixture.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

constexpr int kUsageError = 2;
constexpr int kError = 1;

// A run that must not get as far as rendering.
::testing::AssertionResult failed_before_rendering(const ProcessResult& result) {
  if (contains(result.err, "voxgi: device:") || contains(result.err, "voxgi: wrote")) {
    return ::testing::AssertionFailure() << "expected no rendering\n" << result.describe();
  }
  return ::testing::AssertionSuccess();
}

// ---- scenes -------------------------------------------------------------------------------

TEST_F(VoxgiCli, MissingSceneFileIsNamed) {
  const ProcessResult r = render({"--scene", "missing.gltf", "--out", "out/image"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"voxgi: error: missing.gltf: file: does not exist"}));
  EXPECT_TRUE(failed_before_rendering(r));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "image.png"));
}

TEST_F(VoxgiCli, CorruptGltfIsNamedWithTheParseError) {
  write_text(dir_ / "corrupt.gltf", "{\n  \"asset\": { \"version\": \"2.0\" },\n  \"scenes\": [\n");
  const ProcessResult r = render({"--scene", "corrupt.gltf"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"corrupt.gltf: gltf: not a valid glTF 2.0 file", "parse error"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, TruncatedGlbIsNamedAsTruncated) {
  GltfWriter writer;
  writer.add_mesh_node(writer.triangle());
  const std::vector<uint8_t> bytes = writer.glb_bytes();
  writer.write_glb(dir_ / "whole.glb");
  // The complete file loads (graph check reads the scene without a device), so the failures
  // below come from the cut alone.
  const ProcessResult whole =
      voxgi({"graph", "check", "graphs/default.json", "--scene", "whole.glb"});
  EXPECT_TRUE(exited_with(whole, 0));

  for (const size_t keep : {bytes.size() / 2, size_t(8)}) {
    const std::string name = "cut-" + std::to_string(keep) + ".glb";
    std::ofstream(dir_ / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(keep));
    const ProcessResult r = render({"--scene", name});
    EXPECT_TRUE(exited_with(r, kError));
    EXPECT_TRUE(stderr_has(r, {name + ": glb: truncated"}));
    EXPECT_TRUE(failed_before_rendering(r));
  }
}

TEST_F(VoxgiCli, UnknownBuiltinSceneListsTheBuiltinScenes) {
  const ProcessResult r = render({"--scene", "cornel"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(
      r, {"builtin:cornel: name: unknown built-in scene", "cornell", "plane-point", "empty"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

// ---- graph files --------------------------------------------------------------------------

TEST_F(VoxgiCli, GraphSyntaxErrorHasFileLineAndColumn) {
  write_text(dir_ / "syntax.json", "{\n  \"name\": \"syntax\",\n  \"passes\": [ oops ]\n}\n");
  const ProcessResult r = render({"--graph", "syntax.json"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"syntax.json:3:15: error:"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, UnknownPassTypeSuggestsTheClosestType) {
  // The typo is in a copy of the foundation fragment next to the graph, which the graph's
  // include finds before the shipped one: the error names the fragment and the include.
  std::string fragment = foundation_fragment_text();
  const size_t at = fragment.find("\"common.gbuffer\"");
  ASSERT_NE(at, std::string::npos) << "graphs/common/foundation.json no longer uses common.gbuffer";
  fragment.replace(at, 16, "\"common.gbufer\"");
  std::filesystem::create_directories(dir_ / "common");
  write_text(dir_ / "common" / "foundation.json", fragment);
  const std::string graph = default_graph_text();
  write_text(dir_ / "typo.json", graph);

  const ProcessResult r = render({"--graph", "typo.json"});
  EXPECT_TRUE(exited_with(r, kError));
  const std::string location =
      "common/foundation.json:" + std::to_string(line_of(fragment, "common.gbufer")) + ":";
  EXPECT_TRUE(stderr_has(r, {location, "field 'type'", "unknown pass type 'common.gbufer'",
                             "did you mean 'common.gbuffer'?",
                             "\n  included from typo.json:" +
                                 std::to_string(line_of(graph, "common/foundation.json")) + ":"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, GraphCheckAcceptsTheDefaultGraph) {
  // A relative path that is not under the working directory resolves into the source tree.
  const ProcessResult r = voxgi({"graph", "check", "graphs/default.json"});
  EXPECT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(r, {"default.json: ok"}));
}

// Every variant a shipped graph names compiles; one is chosen by --variant, and explain says
// which variant and which pass sized the resources the graph leaves unsized.
TEST_F(VoxgiCli, GraphCheckCompilesEveryVariantAndExplainNamesTheChosenOne) {
  const ProcessResult check = voxgi({"graph", "check", "graphs/vct.json"});
  EXPECT_TRUE(exited_with(check, 0));
  EXPECT_TRUE(stdout_has(check, {"vct.json: ok", "variant 'dense': ok", "variant 'half': ok",
                                 "variant 'cones16': ok"}));
  const ProcessResult explain =
      voxgi({"graph", "explain", "graphs/vct.json", "--variant", "dense"});
  EXPECT_TRUE(exited_with(explain, 0));
  EXPECT_TRUE(stdout_has(explain, {"variant: dense", "sized by pass 'voxelize'",
                                   "sized by pass 'filter'", "sized by pass 'shadows'"}));
}

// dvs.json's one cone count reaches its voxel bounces and its final gather alike: more gather
// cones alone leave the voxel bounces' error where it is (docs/error-budget.md, twenty-eighth
// round).
TEST_F(VoxgiCli, DvsConesSetTheVoxelBouncesAndTheFinalGather) {
  const ProcessResult r = voxgi(
      {"graph", "explain", "graphs/dvs.json", "--set", "dvs.cones=9", "--set", "dvs.bounces=2"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(
      r, {"bounce1 (dvs.voxel_bounce)", "bounce2 (dvs.voxel_bounce)", "gather (vct.cone_trace)"}));
  const std::string any = "param diffuse_cones = ";
  const std::string nine = any + "9\n";
  size_t count = 0;
  for (size_t at = r.out.find(any); at != std::string::npos; at = r.out.find(any, at + 1)) {
    EXPECT_EQ(r.out.compare(at, nine.size(), nine), 0) << r.out.substr(at, 40);
    ++count;
  }
  EXPECT_EQ(count, 3u) << r.out;  // two voxel bounces and the final gather
}

TEST_F(VoxgiCli, UnknownVariantListsTheGraphsVariants) {
  const ProcessResult r = render({"--graph", "graphs/vct.json", "--variant", "hlaf"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"vct.json", "unknown variant 'hlaf'", "'dense', 'half', 'cones16'",
                             "did you mean 'half'?"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, GraphCheckRejectsABrokenCopyNamingIt) {
  const std::string text = default_graph_text();
  write_text(dir_ / "broken.json", text.substr(0, text.size() / 2));
  const ProcessResult r = voxgi({"graph", "check", "broken.json"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(broken\.json:\d+:\d+: error: )")))
      << r.describe();
}

// "file:line:col" of the first `part` at or after `anchor` in `text`.
std::string location_of(const std::string& file, const std::string& text, const std::string& anchor,
                        const std::string& part) {
  const size_t at = text.find(part, text.find(anchor));
  if (at == std::string::npos) return file + ": '" + part + "' not found";
  const size_t line_start = text.rfind('\n', at) + 1;  // npos + 1 = 0 on the first line
  const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  return file + ":" + std::to_string(line) + ":" + std::to_string(at - line_start + 1);
}

// A `when` on a device feature: misspelt, it is located and the known names listed; without
// --device every feature reads as absent and `graph explain` says which conditions that decided.
TEST_F(VoxgiCli, GraphCheckReadsDeviceFeaturesOnlyFromANamedDevice) {
  // The conditions are edited in a copy of the foundation fragment next to the graph.
  std::string text = foundation_fragment_text();
  const std::string lights = "\"when\": \"scene.has_lights\"";
  ASSERT_NE(text.find(lights), std::string::npos) << "graphs/common/foundation.json changed";
  std::filesystem::create_directories(dir_ / "common");
  write_text(dir_ / "graph.json", default_graph_text());
  std::string misspelt = text;
  misspelt.replace(misspelt.find(lights), lights.size(), "\"when\": \"device.ray_querry\"");
  write_text(dir_ / "common" / "foundation.json", misspelt);
  const ProcessResult bad = voxgi({"graph", "check", "graph.json"});
  EXPECT_TRUE(exited_with(bad, kError));
  EXPECT_TRUE(stderr_has(
      bad, {location_of("common/foundation.json", misspelt, "\"when\"", "device.ray_querry") +
                ": error: pass 'shadows' field 'when'",
            "unknown device feature 'device.ray_querry' (known: ", "device.ray_query, ",
            "did you mean 'device.ray_query'?"}));

  text.replace(text.find(lights), lights.size(),
               "\"when\": \"scene.has_lights && device.timestamps\"");
  write_text(dir_ / "common" / "foundation.json", text);
  const ProcessResult none = voxgi({"graph", "explain", "graph.json"});
  EXPECT_TRUE(exited_with(none, 0));
  EXPECT_TRUE(stdout_has(
      none, {"device features (no device: every feature reads as absent; --device D queries one)",
             "  shadows: when 'scene.has_lights && device.timestamps' is false (reads "
             "device.timestamps): pass culled",
             "(compiled without a device: device features read as absent)"}));
  if (voxgi({"devices"}).exit_code != 0) return;  // no Vulkan device to name here
  const ProcessResult with = voxgi({"graph", "explain", "graph.json", "--device", "0"});
  EXPECT_TRUE(exited_with(with, 0));
  EXPECT_TRUE(stdout_has(with, {"device features (of '"}));
}

std::string vct_graph_text() {
  return read_text(std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "vct.json");
}

std::string shipped_text(const std::string& relative) {
  return read_text(std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / relative);
}

// Every `"persistent": true` of a declaration that starts with `prefix` removed.
std::string without_persistent(std::string text, const std::string& prefix) {
  const std::string persistent = ", \"persistent\": true";
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    const size_t end = text.find(" }", at);  // "${...}" inside the declaration has no space
    const size_t flag = text.find(persistent, at);
    if (flag < end) text.erase(flag, persistent.size());
  }
  return text;
}

// graphs/vct.json with the vct.* volumes transient (the radiance in the graph, the filtered
// volumes in a copy of their fragment next to it): injection and filtering may skip frames,
// which would leave them undefined, so the graph is refused before any frame.
TEST_F(VoxgiCli, GraphCheckRefusesTransientOutputsOfPassesThatMaySkip) {
  const std::string text = without_persistent(vct_graph_text(), "\"vct.");
  const std::string volumes =
      without_persistent(shipped_text("vct/directional_volumes.json"), "\"{{volumes}}.");
  ASSERT_NE(volumes, shipped_text("vct/directional_volumes.json"));
  write_text(dir_ / "transient.json", text);
  std::filesystem::create_directories(dir_ / "vct");
  write_text(dir_ / "vct" / "directional_volumes.json", volumes);
  const std::string filter = shipped_text("vct/filter.json");
  const ProcessResult r = voxgi({"graph", "check", "transient.json"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(
      r, {location_of("transient.json", text, "\"name\": \"inject\"", "\"vct.radiance\"") +
              ": error: pass 'inject' field 'out.radiance': pass type 'vct.inject' may skip",
          "resource 'vct.radiance' (line " + std::to_string(line_of(text, "\"vct.radiance\":")) +
              ") is transient",
          "mark it \"persistent\": true",
          location_of(
              (std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "vct" / "filter.json").string(),
              filter, "\"out\"", "\"{{volumes}}.pos_x\"") +
              ": error: pass 'filter' field 'out.pos_x'",
          "resource 'vct.pos_x' (vct/directional_volumes.json:" +
              std::to_string(line_of(volumes, "\"{{volumes}}.pos_x\":")) + ":"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

// Sizes beyond what any device allows, and memory beyond a stated budget, are refused by
// `graph check` with one located error per cause, naming the limit.
TEST_F(VoxgiCli, GraphCheckRefusesOversizedGraphsAndChecksAMemoryBudget) {
  const ProcessResult huge = voxgi({"graph", "check", "graphs/vct.json", "--set",
                                    "voxel.resolution=512", "--set", "voxel.levels=6"});
  EXPECT_TRUE(exited_with(huge, kError));
  EXPECT_TRUE(stderr_has(huge, {"field 'resources.voxel.albedo': pass 'voxelize' derives a "
                                "clipmap of 6 levels of 512^3 (at most 16 levels and 2048"}));
  // The volumes sized from the voxel volumes do not repeat the cause.
  EXPECT_EQ(huge.err.find("resources.vct.radiance"), std::string::npos) << huge.err;

  const std::vector<std::string> big = {
      "graph", "check",          "graphs/vct.json", "--set", "voxel.resolution=256",
      "--set", "voxel.levels=6", "--memory-budget"};
  std::vector<std::string> small_budget = big;
  small_budget.push_back("8GiB");
  const ProcessResult over = voxgi(small_budget);
  EXPECT_TRUE(exited_with(over, kError));
  EXPECT_TRUE(stderr_has(over, {"error: field 'resources.voxel.scratch': the graph needs",
                                "more than the device's 8.00 GiB", "voxel.scratch 3.25 GiB"}));
  std::vector<std::string> large_budget = big;
  large_budget.push_back("16GiB");
  EXPECT_TRUE(exited_with(voxgi(large_budget), 0));
  std::vector<std::string> bad_size = big;
  bad_size.push_back("8GB");
  const ProcessResult bad = voxgi(bad_size);
  EXPECT_TRUE(exited_with(bad, kUsageError));
  EXPECT_TRUE(stderr_has(bad, {"--memory-budget: expected a size such as 8GiB"}));
}

// Half-resolution cone tracing needs its scratch image: found by `graph check`, not at render.
TEST_F(VoxgiCli, GraphCheckRefusesHalfResolutionWithoutHalfRes) {
  // A copy of the gather fragment without the scratch binding, next to the graph.
  std::string gather = shipped_text("vct/gather.json");
  const std::string scratch = ",\n               \"half_res\": \"gi.half\"";
  ASSERT_NE(gather.find(scratch), std::string::npos) << "graphs/vct/gather.json changed";
  gather.erase(gather.find(scratch), scratch.size());
  std::filesystem::create_directories(dir_ / "vct");
  write_text(dir_ / "vct" / "gather.json", gather);
  std::string text = vct_graph_text();
  const std::string full = "\"resolution\": \"full\"";
  ASSERT_NE(text.find(full), std::string::npos) << "graphs/vct.json changed";
  text.replace(text.find(full), full.size(), "\"resolution\": \"half\"");
  write_text(dir_ / "half.json", text);
  const ProcessResult r = voxgi({"graph", "check", "half.json"});
  EXPECT_TRUE(exited_with(r, kError));
  // The parameter's value comes from the include's "with", where the error points.
  EXPECT_TRUE(stderr_has(
      r, {location_of("vct/gather.json", gather, "\"name\": \"{{name}}\"", "\"{{resolution}}\"") +
              ": error: pass 'cone_trace' field 'params.resolution': 'half' needs the output slot "
              "'half_res' bound",
          "included from half.json:"}));
  // The same through --set, located there.
  write_text(dir_ / "no-scratch.json", vct_graph_text());
  const ProcessResult over =
      voxgi({"graph", "check", "no-scratch.json", "--set", "cone_trace.resolution=half"});
  EXPECT_TRUE(exited_with(over, kError));
  EXPECT_TRUE(stderr_has(over, {"--set cone_trace.resolution=half: error: pass 'cone_trace' "
                                "field 'params.resolution': 'half' needs"}));
}

// The front-light graphs compile; a filter given one facing volume of the two is refused by
// `graph check`, naming the pass and the slot.
TEST_F(VoxgiCli, GraphCheckRefusesHalfTheFrontLightMode) {
  for (const char* graph : {"vct_front_light.json", "dvs_front_light.json"}) {
    write_text(dir_ / graph, shipped_text(graph));
    const ProcessResult ok = voxgi({"graph", "check", graph});
    EXPECT_TRUE(exited_with(ok, 0)) << graph << ": " << ok.describe();
  }
  std::string text = shipped_text("vct_front_light.json");
  const std::string both = "\"facing_pos\": \"vct.facing_pos\", \"facing_neg\": \"vct.facing_neg\"";
  ASSERT_NE(text.find(both), std::string::npos) << "graphs/vct_front_light.json changed";
  text.replace(text.find(both), both.size(), "\"facing_pos\": \"vct.facing_pos\"");
  write_text(dir_ / "half-front.json", text);
  const ProcessResult r = voxgi({"graph", "check", "half-front.json"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"pass 'filter'", "facing_neg",
                             "the front-light mode needs both facing_pos and facing_neg bound"}))
      << r.describe();
}

// ---- --set --------------------------------------------------------------------------------

// --set keys are checked against the graph, in the compiler, so they fail like a graph error.
TEST_F(VoxgiCli, UnknownSetKeyIsNamedWithASuggestion) {
  const ProcessResult r = render({"--set", "lighting.pcf_radios=2"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(
      stderr_has(r, {"--set lighting.pcf_radios=2", "unknown --set key 'lighting.pcf_radios'",
                     "did you mean 'lighting.pcf_radius'?"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, OutOfRangeSetValueNamesPassFieldAndRange) {
  const ProcessResult r = render({"--set", "lighting.pcf_radius=99"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"--set lighting.pcf_radius=99", "pass 'lighting'",
                             "field 'lighting.pcf_radius'", "value 99 is out of range ["}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, SetWithoutEqualsIsAUsageError) {
  const ProcessResult r = render({"--set", "lighting.pcf_radius"});
  EXPECT_TRUE(exited_with(r, kUsageError));
  EXPECT_TRUE(stderr_has(r, {"--set 'lighting.pcf_radius'", "expected KEY=VALUE", "usage:"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

// ---- options ------------------------------------------------------------------------------

TEST_F(VoxgiCli, UnknownOptionSuggestsTheClosestOption) {
  const ProcessResult r = voxgi({"render", "--widht", "64"});
  EXPECT_TRUE(exited_with(r, kUsageError));
  EXPECT_TRUE(stderr_has(r, {"voxgi render: unknown option '--widht'", "did you mean '--width'?"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

TEST_F(VoxgiCli, BadWidthIsAUsageError) {
  for (const std::string width : {"abc", "0", "64px", "99999"}) {
    const ProcessResult r = voxgi({"render", "--width", width, "--height", "64"});
    EXPECT_TRUE(exited_with(r, kUsageError));
    EXPECT_TRUE(
        stderr_has(r, {"option '--width'", "expected an integer in [1, ", "'" + width + "'"}));
    EXPECT_TRUE(failed_before_rendering(r));
  }
}

TEST_F(VoxgiCli, UnknownCommandSuggestsTheClosestCommand) {
  const ProcessResult r = voxgi({"rendr"});
  EXPECT_TRUE(exited_with(r, kUsageError));
  EXPECT_TRUE(stderr_has(r, {"unknown command 'rendr'", "did you mean 'render'?"}));
}

// ---- output paths -------------------------------------------------------------------------

TEST_F(VoxgiCli, OutputBelowARegularFileFailsBeforeRendering) {
  write_text(dir_ / "blocker", "a file where a folder is needed\n");
  const ProcessResult r = render({"--out", "blocker/sub/image"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"--out", "blocker/sub"}));
  EXPECT_TRUE(failed_before_rendering(r));
  EXPECT_EQ(read_text(dir_ / "blocker"), "a file where a folder is needed\n");
}

TEST_F(VoxgiCli, TimingsBelowARegularFileFailsBeforeRendering) {
  write_text(dir_ / "blocker", "");
  const ProcessResult r = render({"--out", "out/image", "--timings", "blocker/t.json"});
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"--timings", "blocker"}));
  EXPECT_TRUE(failed_before_rendering(r));
}

// ---- no Vulkan driver ---------------------------------------------------------------------

TEST_F(VoxgiCli, NoVulkanDriverSaysHowToInstallOne) {
  // Both variables: older loaders read VK_ICD_FILENAMES, newer ones VK_DRIVER_FILES.
  ProcessOptions options;
  const std::string nowhere = (dir_ / "no-such-driver.json").string();
  options.env["VK_ICD_FILENAMES"] = nowhere;
  options.env["VK_DRIVER_FILES"] = nowhere;
  options.env["VK_ADD_DRIVER_FILES"] = std::nullopt;

  const ProcessResult r = render({"--out", "out/image"}, options);
  EXPECT_TRUE(exited_with(r, kError));
  EXPECT_TRUE(stderr_has(r, {"voxgi: error:", "no Vulkan", "install mesa-vulkan-drivers"}));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "image.png"));

  const ProcessResult devices = voxgi({"devices"}, options);
  EXPECT_TRUE(exited_with(devices, kError));
  EXPECT_TRUE(contains(devices.out + devices.err, "install mesa-vulkan-drivers"))
      << devices.describe();
}

// ---- passes and graph explain -------------------------------------------------------------

TEST_F(VoxgiCli, PassesListsTheCommonFamily) {
  const ProcessResult r = voxgi({"passes"});
  EXPECT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(r, {"common.gbuffer", "common.shadow_maps", "common.deferred_lighting",
                             "common.display_transform", "pcf_radius (int"}));
}

TEST_F(VoxgiCli, PassesMarkdownPrintsTables) {
  const ProcessResult r = voxgi({"passes", "--markdown"});
  EXPECT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stdout_has(
      r, {"### `common.gbuffer`", "| parameter | type | default | range | live | description |",
          "|---|---|---|---|---|---|", "| `pcf_radius` | int |"}));
}

TEST_F(VoxgiCli, GraphExplainPrintsTheSchedule) {
  const ProcessResult r = voxgi({"graph", "explain", "graphs/default.json", "--scene", "cornell"});
  EXPECT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(
      stdout_has(r, {"scene: builtin:cornell", "schedule (", "1. gbuffer (common.gbuffer)",
                     "writes ", "barrier ", "culled (", "outputs:", "display -> ", "resources:"}));
}

TEST_F(VoxgiCli, GraphExplainShowsShadowsCulledForTheSharedCornellBox) {
  const std::filesystem::path scene =
      std::filesystem::path(VOXGI_SHARED_DIR) / "scenes" / "cornell-box" / "cornell-box.gltf";
  if (!std::filesystem::exists(scene)) {
    GTEST_SKIP() << "shared scene not found: " << scene.string();
  }
  // Its only light is an emissive quad: no punctual lights, so no shadow maps.
  const ProcessResult r =
      voxgi({"graph", "explain", "graphs/default.json", "--scene", scene.string()});
  EXPECT_TRUE(exited_with(r, 0));
  const size_t culled_at = std::min(r.out.find("culled ("), r.out.size());
  const std::string schedule = r.out.substr(0, culled_at), culled = r.out.substr(culled_at);
  EXPECT_FALSE(contains(schedule, ". shadows (")) << r.describe();
  EXPECT_TRUE(contains(culled, "shadows (common.shadow_maps): when 'scene.has_lights' is false"))
      << r.describe();
  EXPECT_TRUE(stdout_has(r, {"cornell-box.gltf"}));
}

}  // namespace
}  // namespace voxgi::test
