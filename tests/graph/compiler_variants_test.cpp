// Variants: named sets of overrides in one graph file, applied before the command line's own.
// A mistake in a variant is reported at its place in the file.
#include <gtest/gtest.h>

#include "engine/graph/dump.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::compile_text;

const Registry& registry() {
  return test::shared_registry();
}

// One graph parameter (the clear value) and two variants; `extra` adds variants (each ending in
// a comma).
std::string graph_with_variants(const std::string& extra = {}) {
  return R"({ "parameters": { "level": 0.25 },
  "variants": {)" +
         extra + R"(
    "bright": { "doc": "a brighter clear", "set": { "level": 0.75, "clear.mode": "slow" } },
    "counted": { "set": { "clear.count": 4, "clear.enabled": false } }
  },
  "resources": { "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
  "passes": [
    { "name": "clear", "type": "test.clear", "params": { "value": "${level}" },
      "out": { "color": "ldr" } }
  ],
  "outputs": { "display": "ldr" } })";
}

CompiledGraph compile_variant(const std::string& variant,
                              std::map<std::string, std::string> overrides = {}) {
  CompileOptions options;
  options.overrides = std::move(overrides);
  options.overrides[kVariantKey] = variant;
  return compile_text(graph_with_variants(), registry(), options);
}

const ParamValue& clear_param(const CompiledGraph& g, const std::string& name) {
  return g.passes.at(0).params.at(name);
}

TEST(CompilerVariants, FileAsWrittenListsItsVariants) {
  const CompiledGraph g = compile_text(graph_with_variants(), registry());
  EXPECT_TRUE(g.variant.empty());
  EXPECT_EQ(g.variants, (std::vector<std::string>{"bright", "counted"}));
  EXPECT_DOUBLE_EQ(clear_param(g, "value").number, 0.25);
  EXPECT_NE(explain(g).find("variant: none (the file as written); the file's variants: bright "
                            "counted"),
            std::string::npos)
      << explain(g);
  // An empty name is the file as written too (a bench sweep over variants may include it).
  EXPECT_DOUBLE_EQ(clear_param(compile_variant(""), "value").number, 0.25);
}

TEST(CompilerVariants, SettingsApplyToGraphAndPassParameters) {
  const CompiledGraph bright = compile_variant("bright");
  EXPECT_EQ(bright.variant, "bright");
  EXPECT_DOUBLE_EQ(bright.parameters.at("level"), 0.75);
  EXPECT_DOUBLE_EQ(clear_param(bright, "value").number, 0.75);
  EXPECT_EQ(clear_param(bright, "mode").text, "slow");
  EXPECT_NE(explain(bright).find("variant: bright"), std::string::npos);

  const CompiledGraph counted = compile_variant("counted");
  EXPECT_DOUBLE_EQ(clear_param(counted, "count").number, 4.0);
  EXPECT_DOUBLE_EQ(clear_param(counted, "enabled").number, 0.0);
  EXPECT_DOUBLE_EQ(clear_param(counted, "value").number, 0.25);  // untouched
}

TEST(CompilerVariants, CommandLineWins) {
  const CompiledGraph g = compile_variant("bright", {{"level", "0.5"}, {"clear.count", "2"}});
  EXPECT_DOUBLE_EQ(clear_param(g, "value").number, 0.5);
  EXPECT_EQ(clear_param(g, "mode").text, "slow");  // the variant's, not overridden
  EXPECT_DOUBLE_EQ(clear_param(g, "count").number, 2.0);
}

TEST(CompilerVariants, UnknownVariantNamesTheChoices) {
  CompileOptions options;
  options.overrides[kVariantKey] = "brigth";
  const std::string e = test::single_compile_error(graph_with_variants(), registry(), options);
  EXPECT_NE(e.find("unknown variant 'brigth' (the graph's variants: 'bright', 'counted')"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("bright"), std::string::npos) << e;
  EXPECT_NE(e.find("graphs/test.json"), std::string::npos) << e;
}

TEST(CompilerVariants, GraphWithoutVariants) {
  CompileOptions options;
  options.overrides[kVariantKey] = "half";
  const std::string e = test::single_compile_error(
      test::graph_text("",
                       R"({ "name": "clear", "type": "test.clear", "out": { "color": "ldr" } })"),
      registry(), options);
  EXPECT_NE(e.find("graph has no variants, so there is no variant 'half'"), std::string::npos) << e;
}

TEST(CompilerVariants, BadSettingIsReportedInTheFile) {
  const std::string text = graph_with_variants(R"(
    "typo": { "set": { "clear.valeu": 0.5 } },
    "range": { "set": { "clear.value": 7 } },)");
  CompileOptions options;
  options.overrides[kVariantKey] = "typo";
  std::string e = test::single_compile_error(text, registry(), options);
  EXPECT_NE(e.find("graphs/test.json:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'clear.valeu' of variant 'typo'"), std::string::npos) << e;
  EXPECT_NE(e.find("clear.value"), std::string::npos) << e;  // did you mean
  EXPECT_EQ(e.find("--set"), std::string::npos) << e;

  options.overrides[kVariantKey] = "range";
  e = test::single_compile_error(text, registry(), options);
  EXPECT_NE(e.find("graphs/test.json:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("clear.value"), std::string::npos) << e;
}

TEST(CompilerVariants, MalformedVariantsAreParseErrors) {
  const auto error = [](const std::string& variants) {
    try {
      parse_graph(graph_with_variants(variants), test::kTestFile);
    } catch (const GraphError& e) {
      EXPECT_EQ(e.diagnostics().size(), 1u) << e.what();
      return format(e.diagnostics().front());
    }
    ADD_FAILURE() << "parsed without errors: " << variants;
    return std::string();
  };
  EXPECT_NE(error(R"("a": { "doc": "no settings" },)").find("field 'variants.a.set'"),
            std::string::npos);
  EXPECT_NE(error(R"("a": { "set": { "variant": "bright" } },)")
                .find("a variant cannot select another variant"),
            std::string::npos);
  const std::string array = error(R"("a": { "set": { "clear.value": [1] } },)");
  EXPECT_NE(array.find("expected a number, string or boolean, found"), std::string::npos) << array;
  EXPECT_NE(error(R"("a": { "set": {}, "sett": {} },)").find("sett"), std::string::npos);
  EXPECT_NE(error(R"("a": 3,)").find("field 'variants.a'"), std::string::npos);
}

TEST(CompilerVariants, VariantIsAReservedParameterName) {
  const std::string e = test::single_compile_error(
      R"({ "parameters": { "variant": 1 },
           "resources": { "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
           "passes": [ { "name": "clear", "type": "test.clear", "out": { "color": "ldr" } } ],
           "outputs": { "display": "ldr" } })",
      registry());
  EXPECT_NE(e.find("'variant' is reserved"), std::string::npos) << e;
}

}  // namespace
}  // namespace voxgi::graph
