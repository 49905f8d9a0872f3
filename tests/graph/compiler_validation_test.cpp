// Each validation error of the compiler: the message names file:line:col, pass and field,
// suggests a fix where one is close, and is reported once.
#include <gtest/gtest.h>

#include <set>

#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::compile_text;
using test::make_registry;

std::vector<std::string> errors_of(const std::string& text, CompileOptions options = {}) {
  return test::compile_errors(text, make_registry(), options);
}

std::string single_error(const std::string& text, CompileOptions options = {}) {
  return test::single_compile_error(text, make_registry(), options);
}

// A valid graph: line 1 "{", extra resources from line 7, passes right after them (line 9
// when there are none), outputs last.
std::string graph(const std::string& passes, const std::string& extra_resources = "",
                  const std::string& outputs = R"("display": "ldr")") {
  return "{\n"
         "  \"parameters\": { \"res\": 16, \"on\": true },\n"
         "  \"resources\": {\n"
         "    \"hdr\": { \"type\": \"image2d\", \"format\": \"rgba16f\", \"size\": \"viewport\" "
         "},\n"
         "    \"half\": { \"type\": \"image2d\", \"format\": \"rgba16f\", \"size\": \"viewport/2\" "
         "},\n"
         "    \"ldr\": { \"type\": \"image2d\", \"format\": \"rgba8\", \"size\": \"viewport\" "
         "},\n" +
         extra_resources +
         "  },\n"
         "  \"passes\": [\n" +
         passes +
         "  ],\n"
         "  \"outputs\": { " +
         outputs + " }\n}\n";
}

const std::string kClear =
    R"(    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
)";
const std::string kShade =
    R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr" }, "out": { "color": "ldr" } },
)";

TEST(CompilerValidation, ValidGraphCompiles) {
  const Registry registry = make_registry();
  const CompiledGraph g = compile_text(graph(kClear + kShade), registry);
  ASSERT_EQ(g.passes.size(), 2u);
  EXPECT_EQ(g.passes[0].name, "clear");
  EXPECT_EQ(g.resources[1].info.extent.width, 32u);  // viewport/2 of 64x32
  EXPECT_EQ(g.resources[1].info.extent.height, 16u);
}

TEST(CompilerValidation, UnknownPassType) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
          R"(    { "name": "shade", "type": "test.shdae", "in": { "src": "hdr" }, "out": { "color": "ldr" } },
)")),
      "graphs/test.json:10:32: error: pass 'shade' field 'type': unknown pass type "
      "'test.shdae' (did you mean 'test.shade'?)");
}

TEST(CompilerValidation, UnknownSlotName) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
          R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extar": "hdr" }, "out": { "color": "ldr" } },
)")),
      "graphs/test.json:10:68: error: pass 'shade' field 'in.extar': unknown input slot "
      "'extar' of pass type 'test.shade' (it has 'src', 'extra') (did you mean 'extra'?)");
}

TEST(CompilerValidation, SlotInWrongSection) {
  const std::string e = single_error(graph(
      kClear +
      R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "color": "ldr" } },
)"));
  EXPECT_NE(e.find("pass 'shade' field 'in.color': 'color' is an output slot"), std::string::npos)
      << e;
}

TEST(CompilerValidation, MissingRequiredSlot) {
  EXPECT_EQ(
      single_error(graph(
          kClear + R"(    { "name": "shade", "type": "test.shade", "out": { "color": "ldr" } },
)")),
      "graphs/test.json:10:5: error: pass 'shade' field 'in.src': missing required input "
      "slot 'src'");
}

TEST(CompilerValidation, UnknownParameter) {
  EXPECT_EQ(
      single_error(graph(
          R"(    { "name": "clear", "type": "test.clear", "params": { "valeu": 0.2 }, "out": { "color": "hdr" } },
)" + kShade)),
      "graphs/test.json:9:58: error: pass 'clear' field 'params.valeu': unknown parameter "
      "'valeu' of pass type 'test.clear' (did you mean 'value'?)");
}

TEST(CompilerValidation, WrongParameterType) {
  const std::vector<std::string> errors = errors_of(graph(
      R"(    { "name": "clear", "type": "test.clear", "params": { "value": "abc", "count": 1.5, "enabled": 1, "mode": "fsat" }, "out": { "color": "hdr" } },
)" + kShade));
  ASSERT_EQ(errors.size(), 4u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0],
            "graphs/test.json:9:68: error: pass 'clear' field 'params.value': in expression "
            "\"abc\" at column 1: unknown name 'abc' (pass parameters may use numbers, scene "
            "features and ${graph parameters})");
  EXPECT_EQ(errors[1],
            "graphs/test.json:9:83: error: pass 'clear' field 'params.count': expected an "
            "integer, found 1.5");
  EXPECT_EQ(errors[2],
            "graphs/test.json:9:99: error: pass 'clear' field 'params.enabled': expected true "
            "or false, found a number");
  EXPECT_EQ(errors[3],
            "graphs/test.json:9:110: error: pass 'clear' field 'params.mode': expected one of "
            "fast, slow, found 'fsat' (did you mean 'fast'?)");
}

TEST(CompilerValidation, ParameterOutOfRange) {
  EXPECT_EQ(
      single_error(graph(
          R"(    { "name": "clear", "type": "test.clear", "params": { "count": 9 }, "out": { "color": "hdr" } },
)" + kShade)),
      "graphs/test.json:9:67: error: pass 'clear' field 'params.count': value 9 is out of "
      "range [1, 8]");
}

TEST(CompilerValidation, ParameterFromGraphParameterExpression) {
  const Registry registry = make_registry();
  const CompiledGraph g = compile_text(
      graph(
          R"(    { "name": "clear", "type": "test.clear", "params": { "count": "${res} / 4", "mode": "slow" }, "out": { "color": "hdr" } },
)" + kShade),
      registry);
  EXPECT_DOUBLE_EQ(g.passes[0].params.at("count").number, 4.0);
  EXPECT_EQ(g.passes[0].params.at("mode").text, "slow");
  EXPECT_DOUBLE_EQ(g.passes[0].params.at("mode").number, 1.0);
  EXPECT_DOUBLE_EQ(g.passes[0].params.at("value").number, 0.5);  // default
}

TEST(CompilerValidation, HugeExpressionIsRefusedWithAShortQuote) {
  std::string sum = "1";
  for (int i = 0; i < 20000; ++i) sum += "+1";
  const std::string e = single_error(
      graph(R"(    { "name": "clear", "type": "test.clear", "params": { "count": ")" + sum +
            R"(" }, "out": { "color": "hdr" } },
)" + kShade));
  EXPECT_NE(e.find("graphs/test.json:"), std::string::npos) << e;
  EXPECT_NE(e.find("field 'params.count'"), std::string::npos) << e;
  EXPECT_NE(e.find("expression too long: more than 4096 values and operators"), std::string::npos)
      << e;
  EXPECT_NE(e.find("\"...1+1"), std::string::npos) << e;
  EXPECT_LT(e.size(), 400u) << e;
}

TEST(CompilerValidation, UnknownResource) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
          R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdrr" }, "out": { "color": "ldr" } },
)")),
      "graphs/test.json:10:61: error: pass 'shade' field 'in.src': unknown resource 'hdrr' "
      "(did you mean 'hdr'?)");
}

TEST(CompilerValidation, ResourceKindNotAccepted) {
  const std::string e = single_error(
      graph(kClear + R"(    { "name": "fill", "type": "test.fill", "out": { "buf": "hdr" } },
)" + kShade));
  EXPECT_EQ(e,
            "graphs/test.json:10:60: error: pass 'fill' field 'out.buf': resource 'hdr' is a "
            "image2d, but the slot accepts buffer");
}

TEST(CompilerValidation, FormatNotAccepted) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
              R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr" }, "out": { "color": "mono" } },
)",
          R"(    "mono": { "type": "image2d", "format": "r32f", "size": 8 },
)",
          R"("display": "mono")")),
      "graphs/test.json:11:88: error: pass 'shade' field 'out.color': resource 'mono' has "
      "format r32f, but the slot accepts 'rgba8', 'rgba16f'");
}

TEST(CompilerValidation, ReadBeforeAnyWrite) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
          R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "half" }, "out": { "color": "ldr" } },
)")),
      "graphs/test.json:10:77: error: pass 'shade' field 'in.extra': resource 'half' is "
      "read before any write: no pass writes it (mark it \"persistent\": true if it carries "
      "data from earlier frames)");
}

TEST(CompilerValidation, PersistentMayBeReadBeforeAnyWrite) {
  const Registry registry = make_registry();
  const CompiledGraph g = compile_text(
      graph(
          kClear +
              R"(    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "history" }, "out": { "color": "ldr" } },
)",
          R"(    "history": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },
)"),
      registry);
  EXPECT_EQ(g.passes.size(), 2u);
}

TEST(CompilerValidation, MipOutOfRange) {
  EXPECT_EQ(
      single_error(graph(
          kClear +
              R"(    { "name": "mip", "type": "test.mip", "in": { "src": "vox@1" }, "out": { "dst": "vox@4" } },
)" + kShade,
          R"(    "vox": { "type": "image3d", "format": "rgba16f", "size": 8, "mips": "full" },
)")),
      "graphs/test.json:11:84: error: pass 'mip' field 'out.dst': mip 4 is out of range: "
      "resource 'vox' has 4 mip level(s) (0..3)");
}

TEST(CompilerValidation, DuplicatePassNames) {
  EXPECT_EQ(
      single_error(graph(
          kClear + R"(    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
)" + kShade)),
      "graphs/test.json:10:15: error: pass 'clear' field 'name': duplicate pass name (first "
      "defined at line 9)");
}

TEST(CompilerValidation, CycleNamesThePasses) {
  // a reads x (written later by b, so the frame's final x); b reads y written earlier by a.
  const std::string e =
      single_error(graph(
          R"(    { "name": "a", "type": "test.blur", "in": { "src": "x" }, "out": { "dst": "y" } },
    { "name": "b", "type": "test.blur", "in": { "src": "y" }, "out": { "dst": "x" } },
)" + kClear + kShade,
          R"(    "x": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "y": { "type": "image2d", "format": "rgba16f", "size": 8 },
)"));
  EXPECT_NE(e.find("dependency cycle between passes: "), std::string::npos) << e;
  EXPECT_NE(e.find("'a' -> 'b' -> 'a'"), std::string::npos) << e;
  EXPECT_EQ(e.rfind("graphs/test.json:11:5: error: pass 'a'", 0), 0u) << e;
}

TEST(CompilerValidation, UnknownOutputResource) {
  EXPECT_EQ(single_error(graph(kClear + kShade, "", R"("display": "lrd")")),
            "graphs/test.json:12:27: error: field 'outputs.display': unknown output resource "
            "'lrd' (did you mean 'ldr'?)");
}

TEST(CompilerValidation, BadResourceDeclarations) {
  const std::vector<std::string> errors = errors_of(
      graph(kClear + kShade, R"X(    "a": { "type": "image4d", "format": "rgba16f", "size": 8 },
    "b": { "type": "image2d", "format": "rgba61f", "size": 8 },
    "c": { "type": "image2d", "format": "rgba16f", "size": "viewport / (1 - 1)" },
    "d": { "type": "image2d", "format": "rgba16f", "size": "${rse}" },
    "e": { "type": "image2d", "format": "rgba16f", "size": [1, 2, 3] },
    "f": { "type": "image2d", "format": "rgba16f", "size": "0" },
    "g": { "type": "image3d", "format": "rgba16f", "size": 8, "mips": 5 },
    "h": { "type": "clipmap", "format": "rgba16f", "resolution": 8 },
)X"));
  ASSERT_EQ(errors.size(), 8u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0],
            "graphs/test.json:7:20: error: field 'resources.a.type': unknown resource type "
            "'image4d' (expected image2d, image3d, clipmap or buffer) (did you mean 'image2d'?)");
  EXPECT_EQ(errors[1],
            "graphs/test.json:8:41: error: field 'resources.b.format': unknown format 'rgba61f' "
            "(did you mean 'rgba16f'?)");
  EXPECT_EQ(errors[2],
            "graphs/test.json:9:70: error: field 'resources.c.size': in expression \"viewport / "
            "(1 - 1)\" at column 10: division by zero");
  EXPECT_EQ(errors[3],
            "graphs/test.json:10:61: error: field 'resources.d.size': in expression \"${rse}\" at "
            "column 1: unknown parameter '${rse}' (did you mean 'res'?)");
  EXPECT_NE(errors[4].find("field 'resources.e.size': a image2d size has 1 or 2 components"),
            std::string::npos);
  EXPECT_EQ(errors[5],
            "graphs/test.json:12:60: error: field 'resources.f.size': size '0' evaluates to 0, "
            "expected 1 to 16384");
  EXPECT_EQ(errors[6],
            "graphs/test.json:13:71: error: field 'resources.g.mips': mip count 5 exceeds the "
            "full chain of 4 levels for this size");
  EXPECT_EQ(errors[7],
            "graphs/test.json:14:5: error: field 'resources.h.levels': a clipmap needs both "
            "'resolution' and 'levels'");
}

TEST(CompilerValidation, UnknownSceneFeatureInWhen) {
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 1}, {"scene.has_emissive", 0}};
  EXPECT_EQ(
      single_error(
          graph(
              kClear +
              R"(    { "name": "shade", "type": "test.shade", "when": "${on} && scene.has_glosy", "in": { "src": "hdr" }, "out": { "color": "ldr" } },
)"),
          options),
      "graphs/test.json:10:64: error: pass 'shade' field 'when': in expression \"${on} && "
      "scene.has_glosy\" at column 10: unknown scene feature 'scene.has_glosy' (did you "
      "mean 'scene.has_glossy'?)");
}

TEST(CompilerValidation, UnknownDeviceFeatureInWhenListsTheKnownOnes) {
  const std::string error = single_error(graph(
      kClear +
      R"(    { "name": "shade", "type": "test.shade", "when": "device.ray_querry", "in": { "src": "hdr" }, "out": { "color": "ldr" } },
)"));
  EXPECT_EQ(error.rfind("graphs/test.json:10:55: error: pass 'shade' field 'when': in expression "
                        "\"device.ray_querry\" at column 1: unknown device feature "
                        "'device.ray_querry' (known: ",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("device.ray_query, device.ray_tracing_pipeline"), std::string::npos)
      << error;
  EXPECT_NE(error.find("(did you mean 'device.ray_query'?)"), std::string::npos) << error;
}

// Sizes must not depend on the device: `graph check` would see other sizes than a render.
TEST(CompilerValidation, SizesReadNoDeviceFeatures) {
  CompileOptions options;
  options.device_features = {{"device.ray_query", 1}};
  const std::string error = single_error(
      graph(
          kClear + kShade,
          R"("extra": { "type": "image2d", "format": "rgba8", "size": "8 * device.ray_query" },)"),
      options);
  EXPECT_NE(error.find("unknown name 'device.ray_query' (sizes may use viewport"),
            std::string::npos)
      << error;
}

TEST(CompilerValidation, SameMipInTwoLayoutsInOnePass) {
  const std::string e = single_error(graph(
      kClear +
      R"(    { "name": "blur", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "hdr" } },
)" + kShade));
  EXPECT_NE(e.find("pass 'blur' field 'out.dst': resource 'hdr' is also bound to slot 'src'"),
            std::string::npos)
      << e;
}

TEST(CompilerValidation, UnknownAndBadOverrides) {
  CompileOptions options;
  options.overrides = {
      {"clear.valeu", "0.1"}, {"clear.count", "many"}, {"res", "big"}, {"shade.mode", "x"}};
  const std::vector<std::string> errors = errors_of(graph(kClear + kShade), options);
  ASSERT_EQ(errors.size(), 4u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "--set res=big: error: field 'res': expected a number, found 'big'");
  EXPECT_EQ(errors[1],
            "--set clear.count=many: error: pass 'clear' field 'clear.count': expected an "
            "integer, found 'many'");
  EXPECT_EQ(errors[2],
            "--set clear.valeu=0.1: error: field 'clear.valeu': unknown --set key 'clear.valeu' "
            "(expected a graph parameter or 'pass.parameter') (did you mean 'clear.value'?)");
  EXPECT_EQ(errors[3],
            "--set shade.mode=x: error: field 'shade.mode': unknown --set key 'shade.mode' "
            "(expected a graph parameter or 'pass.parameter')");
}

TEST(CompilerValidation, GoodOverrides) {
  CompileOptions options;
  options.overrides = {{"clear.value", "0.25"},
                       {"clear.mode", "slow"},
                       {"res", "32"},
                       {"on", "false"},
                       {"clear.enabled", "off"}};
  const Registry registry = make_registry();
  const CompiledGraph g =
      compile_text(graph(kClear + kShade,
                         R"(    "r": { "type": "image2d", "format": "rgba16f", "size": "${res}" },
)"),
                   registry, options);
  const CompiledPass* clear = g.find_pass("clear");
  ASSERT_NE(clear, nullptr);
  EXPECT_DOUBLE_EQ(clear->params.at("value").number, 0.25);
  EXPECT_EQ(clear->params.at("mode").text, "slow");
  EXPECT_DOUBLE_EQ(clear->params.at("enabled").number, 0.0);
  EXPECT_DOUBLE_EQ(g.parameters.at("res"), 32.0);
  EXPECT_DOUBLE_EQ(g.parameters.at("on"), 0.0);
  EXPECT_EQ(g.resources[static_cast<size_t>(g.find_resource("r"))].info.extent.width, 32u);
}

TEST(CompilerValidation, OutputWithOnlyCulledWriters) {
  CompileOptions options;
  options.scene_features = {{"scene.has_sky", 0}};
  EXPECT_EQ(
      single_error(
          graph(
              kClear +
              R"(    { "name": "shade", "type": "test.shade", "when": "scene.has_sky", "in": { "src": "hdr" }, "out": { "color": "ldr" } },
)"),
          options),
      "graphs/test.json:12:27: error: field 'outputs.display': output resource 'ldr' has no "
      "writer left: every pass writing it was culled (pass 'shade': when 'scene.has_sky' "
      "is false for this scene)");
}

TEST(CompilerValidation, StructuralErrorsFromTheFile) {
  const std::vector<std::string> errors = errors_of(R"({
  "resources": { "a": { "type": "image2d", "fromat": "rgba8", "size": 4 } },
  "passes": [ { "name": "p", "tpye": "test.clear", "out": { "color": "a@x" } } ],
  "outputs": { "display": 3 }
})");
  ASSERT_EQ(errors.size(), 5u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0],
            "graphs/test.json:2:44: error: field 'resources.a.fromat': unknown field (did you "
            "mean 'format'?)");
  EXPECT_EQ(errors[1],
            "graphs/test.json:3:30: error: pass 'p' field 'tpye': unknown field (did you mean "
            "'type'?)");
  EXPECT_EQ(errors[2],
            "graphs/test.json:3:15: error: pass 'p' field 'type': missing field 'type' "
            "(\"family.pass\")");
  EXPECT_EQ(errors[3],
            "graphs/test.json:3:70: error: pass 'p' field 'out.color': expected a mip level "
            "number (\"name@2\") or \"previous\" (the previous frame's version) after '@', "
            "found 'x'");
  EXPECT_EQ(errors[4],
            "graphs/test.json:4:27: error: field 'outputs.display': expected a resource name "
            "string, found a number");
}

TEST(CompilerValidation, EveryProblemReportedOnce) {
  // Two passes with the same unknown type and a misspelt resource each: four distinct errors,
  // none repeated.
  const std::vector<std::string> errors = errors_of(
      graph(kClear + kShade + R"(    { "name": "x1", "type": "test.nope", "in": { "src": "hdr" } },
    { "name": "x2", "type": "test.nope", "in": { "src": "hdr" } },
    { "name": "x3", "type": "test.blur", "in": { "src": "hdrx" }, "out": { "dst": "half" } },
    { "name": "x4", "type": "test.blur", "in": { "src": "hdrx" }, "out": { "dst": "half" } },
)"));
  ASSERT_EQ(errors.size(), 4u) << ::testing::PrintToString(errors);
  std::set<std::string> unique(errors.begin(), errors.end());
  EXPECT_EQ(unique.size(), 4u);
}

TEST(CompilerValidation, MissingFileIsAGraphError) {
  try {
    load_graph_file("no/such/graph.json");
    FAIL();
  } catch (const GraphError& e) {
    EXPECT_STREQ(e.what(),
                 "no/such/graph.json: error: cannot open the graph file (expected a readable JSON "
                 "file)");
  }
}

}  // namespace
}  // namespace voxgi::graph
