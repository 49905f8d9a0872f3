// The compile-time side of the pass contract: a pass that may skip writes only persistent
// resources, and a transient's first use writes it.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::kBuffer;
using test::kImages;
using test::slot;

// test.* types plus skip.voxels: may skip; writes "volume", optional scratch buffer "scratch".
Registry make_contract_registry() {
  Registry r = test::make_registry();
  PassTypeInfo voxels;
  voxels.type = "skip.voxels";
  voxels.outputs = {slot("volume", kImages, Access::StorageWrite, kStageCompute),
                    slot("scratch", kBuffer, Access::StorageReadWrite, kStageCompute, true)};
  voxels.outputs[1].scratch = true;
  voxels.may_skip = true;
  r.add(voxels, [] { return std::make_unique<test::DeclarationOnlyPass>(); });

  return r;
}

const Registry& registry() {
  static const Registry r = make_contract_registry();
  return r;
}

// "graphs/test.json:line:col" of the first `needle` after `after` in `text`.
std::string where(const std::string& text, const std::string& needle,
                  const std::string& after = {}) {
  const size_t at = text.find(needle, after.empty() ? 0 : text.find(after));
  EXPECT_NE(at, std::string::npos) << needle;
  const size_t line_start = text.rfind('\n', at);
  const size_t line = static_cast<size_t>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
  const size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return std::string(test::kTestFile) + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string single_error(const std::string& text, CompileOptions options = {}) {
  return test::single_compile_error(text, registry(), options);
}

// A graph whose pass "voxels" (skip.voxels) writes `volume`, read by "shade" into the output.
std::string voxel_graph(const std::string& volume_persistence) {
  return test::graph_text(
      R"(
    "volume": { "type": "image2d", "format": "rgba16f", "size": 8)" +
          volume_persistence + R"( },
    "scratch": { "type": "buffer", "size": 64 },)",
      R"(
    { "name": "voxels", "type": "skip.voxels", "out": { "volume": "volume", "scratch": "scratch" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "volume" }, "out": { "color": "ldr" } })");
}

// The 1-based line of the first `part` of `text`.
std::string line_of(const std::string& text, const std::string& part) {
  return std::to_string(
      std::count(text.begin(), text.begin() + static_cast<long>(text.find(part)), '\n') + 1);
}

TEST(SkipContract, APassThatMaySkipCannotWriteATransient) {
  const std::string text = voxel_graph("");
  EXPECT_EQ(single_error(text), where(text, "\"volume\",", "\"out\"") +
                                    ": error: pass 'voxels' field 'out.volume': pass type "
                                    "'skip.voxels' may skip frames whose inputs did not change "
                                    "and keep what it wrote earlier, but resource 'volume' (line " +
                                    line_of(text, "\"volume\": {") +
                                    ") is transient, so it would be undefined then: mark it "
                                    "\"persistent\": true");
}

TEST(SkipContract, PersistentOutputsAndATransientScratchAreAccepted) {
  const CompiledGraph g = test::compile_text(voxel_graph(", \"persistent\": true"), registry());
  ASSERT_NE(g.find_pass("voxels"), nullptr);
  for (const SlotBinding& b : g.find_pass("voxels")->bindings) {
    EXPECT_FALSE(skip_leaves_undefined(b)) << b.slot;
  }
  // The scratch buffer's read-modify-write first use does not carry it across frames.
  EXPECT_FALSE(g.resources[static_cast<size_t>(g.find_resource("scratch"))].carries_contents);
}

TEST(SkipContract, ATransientsFirstUseMustWriteIt) {
  auto history_graph = [](const std::string& persistence) {
    return test::graph_text(
        R"(
    "history": { "type": "image2d", "format": "rgba16f", "size": 8)" +
            persistence + " },",
        R"(
    { "name": "accumulate", "type": "test.accumulate", "out": { "acc": "history" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "history" }, "out": { "color": "ldr" } })");
  };
  const std::string text = history_graph("");
  EXPECT_EQ(single_error(text), where(text, "\"history\" }", "\"acc\"") +
                                    ": error: pass 'accumulate' field 'out.acc': resource "
                                    "'history' is transient, so it holds nothing when the frame "
                                    "starts, but its first use here reads it (storage-read-write): "
                                    "let an earlier pass write it, or mark it \"persistent\": "
                                    "true to keep it across frames");
  // Persistent, the same graph carries the history from frame to frame.
  const CompiledGraph g = test::compile_text(history_graph(", \"persistent\": true"), registry());
  EXPECT_TRUE(g.resources[static_cast<size_t>(g.find_resource("history"))].carries_contents);
}

}  // namespace
}  // namespace voxgi::graph
