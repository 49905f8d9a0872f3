// Two variants as one graph: what they share (same pass, same parameters, shared inputs) is
// kept once, the rest of B runs renamed "b/...", and the merged graph compiles.
#include <gtest/gtest.h>

#include "engine/graph/ab_merge.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::compile_text;

const Registry& registry() {
  return test::shared_registry();
}

// c1 -> hdr -> blur -> t1 -> final -> ldr, with c2 -> h2 read by final too; a persistent
// accumulation fed by t1.
const char* kGraph = R"({ "parameters": { "v1": 0.25, "v2": 0.5 },
  "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "h2": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "t1": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "acc": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
  "passes": [
    { "name": "c1", "type": "test.clear", "params": { "value": "${v1}" }, "out": { "color": "hdr" } },
    { "name": "c2", "type": "test.clear", "params": { "value": "${v2}" }, "out": { "color": "h2" } },
    { "name": "blur", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "t1" } },
    { "name": "accumulate", "type": "test.accumulate", "in": { "src": "t1" }, "out": { "acc": "acc" } },
    { "name": "final", "type": "test.shade", "in": { "src": "acc", "extra": "h2" },
      "out": { "color": "ldr" } } ],
  "outputs": { "display": "ldr" } })";

CompileOptions options_with(std::map<std::string, std::string> overrides = {}) {
  CompileOptions options;
  options.viewport_width = 64;
  options.viewport_height = 32;
  options.overrides = std::move(overrides);
  return options;
}

CompiledGraph compile_with(std::map<std::string, std::string> overrides) {
  return compile(parse_graph(kGraph, "graphs/ab.json"), registry(), options_with(overrides));
}

const CompiledPass& pass(const CompiledGraph& g, const std::string& name) {
  const CompiledPass* p = g.find_pass(name);
  EXPECT_NE(p, nullptr) << name;
  return *p;
}

std::string bound(const CompiledGraph& g, const std::string& name, const std::string& slot) {
  const SlotBinding* b = pass(g, name).binding(slot);
  if (!b || b->resource < 0) return "-";
  return g.resources[static_cast<size_t>(b->resource)].info.name;
}

TEST(AbMerge, SharedPassesRunOnceTheRestRenamed) {
  const CompiledGraph a = compile_with({});
  const CompiledGraph b = compile_with({{"v2", "0.75"}});
  const AbMerge merge = merge_for_ab(a, b);
  // c2 differs, so final (which reads h2) differs; the chain through blur and the persistent
  // accumulation does not.
  EXPECT_EQ(merge.shared_passes, (std::vector<std::string>{"c1", "blur", "accumulate"}));
  EXPECT_EQ(merge.b_passes, (std::vector<std::string>{"b/c2", "b/final"}));
  const CompiledGraph merged = compile(merge.desc, registry(), options_with());
  EXPECT_EQ(merged.passes.size(), 7u);
  EXPECT_TRUE(merged.culled.empty());
  EXPECT_EQ(bound(merged, "b/final", "src"), "acc");  // A's, shared
  EXPECT_EQ(bound(merged, "b/final", "extra"), "b/h2");
  EXPECT_EQ(bound(merged, "b/final", "color"), "b/ldr");
  EXPECT_DOUBLE_EQ(pass(merged, "b/c2").params.at("value").number, 0.75);
  EXPECT_DOUBLE_EQ(pass(merged, "c2").params.at("value").number, 0.5);
  ASSERT_EQ(merged.outputs.size(), 2u);
  EXPECT_EQ(merged.resources[static_cast<size_t>(merged.outputs.at("display"))].info.name, "ldr");
  EXPECT_EQ(merged.resources[static_cast<size_t>(merged.outputs.at("b/display"))].info.name,
            "b/ldr");
}

TEST(AbMerge, ADifferenceUpstreamSharesNothingDownstream) {
  const AbMerge merge = merge_for_ab(compile_with({}), compile_with({{"v1", "0.3"}}));
  EXPECT_EQ(merge.shared_passes, (std::vector<std::string>{"c2"}));
  EXPECT_EQ(merge.b_passes,
            (std::vector<std::string>{"b/c1", "b/blur", "b/accumulate", "b/final"}));
  const CompiledGraph merged = compile(merge.desc, registry(), options_with());
  EXPECT_EQ(bound(merged, "b/accumulate", "acc"), "b/acc");  // persistent state kept apart
  EXPECT_EQ(bound(merged, "b/final", "extra"), "h2");
}

TEST(AbMerge, IdenticalGraphsShareEverything) {
  const CompiledGraph a = compile_with({});
  const AbMerge merge = merge_for_ab(a, a);
  EXPECT_EQ(merge.shared_passes.size(), a.passes.size());
  EXPECT_TRUE(merge.b_passes.empty());
  const CompiledGraph merged = compile(merge.desc, registry(), options_with());
  EXPECT_EQ(merged.outputs.at("display"), merged.outputs.at("b/display"));
}

}  // namespace
}  // namespace voxgi::graph
