// The compile-time side of the pass contract: a pass that may skip writes only persistent
// resources, a transient's first use writes it, pass types' validate hooks report with file, line
// and column; and the barriers FrameSync plans for frames in which passes skip.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/graph/resource_plan.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::kBuffer;
using test::kImages;
using test::slot;

// test.* types plus:
//   skip.voxels  may skip; writes "volume", optional scratch buffer "scratch"
//   check.trace  "resolution" full|half needs "half_res" for half, of half the size of "result"
Registry make_contract_registry() {
  Registry r = test::make_registry();
  PassTypeInfo voxels;
  voxels.type = "skip.voxels";
  voxels.outputs = {slot("volume", kImages, Access::StorageWrite, kStageCompute),
                    slot("scratch", kBuffer, Access::StorageReadWrite, kStageCompute, true)};
  voxels.outputs[1].scratch = true;
  voxels.may_skip = true;
  r.add(voxels, [] { return std::make_unique<test::DeclarationOnlyPass>(); });

  PassTypeInfo trace;
  trace.type = "check.trace";
  trace.inputs = {slot("src", kImages, Access::Sampled, kStageCompute)};
  trace.outputs = {slot("result", kImages, Access::StorageWrite, kStageCompute),
                   slot("half_res", kImages, Access::StorageWrite, kStageCompute, true)};
  trace.params = {test::param("resolution", ParamType::Enum, 0, 0, 0, {"full", "half"})};
  trace.params[0].live = false;
  trace.validate = [](PassCheck& check) {
    if (check.choice("resolution") == "half" && !check.has("half_res")) {
      check.param_error("resolution", "'half' needs 'half_res' bound");
    }
    if (check.has("half_res") &&
        check.info("half_res").extent.width * 2 != check.info("result").extent.width) {
      check.slot_error("half_res", "must be half the size of 'result'");
    }
  };
  r.add(trace, [] { return std::make_unique<test::DeclarationOnlyPass>(); });
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

// "trace" (check.trace) from "hdr" into "result", with the given extra fields.
std::string trace_graph(const std::string& params, const std::string& half_res,
                        const std::string& when = {}) {
  return test::graph_text(R"(
    "result": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "half": { "type": "image2d", "format": "rgba16f", "size": 4 },
    "quarter": { "type": "image2d", "format": "rgba16f", "size": 2 },)",
                          R"(
    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
    { "name": "trace", "type": "check.trace")" +
                              when + params + R"(, "in": { "src": "hdr" },
      "out": { "result": "result")" +
                              half_res + R"( } },
    { "name": "shade", "type": "test.shade", "in": { "src": "result" }, "out": { "color": "ldr" } })");
}

TEST(ValidateHook, ReportsAtTheParameterInTheFile) {
  const std::string text = trace_graph(R"(, "params": { "resolution": "half" })", "");
  EXPECT_EQ(single_error(text), where(text, "\"half\" }", "\"resolution\"") +
                                    ": error: pass 'trace' field 'params.resolution': 'half' "
                                    "needs 'half_res' bound");
  // Bound, it compiles.
  test::compile_text(
      trace_graph(R"(, "params": { "resolution": "half" })", R"(, "half_res": "half")"),
      registry());
}

TEST(ValidateHook, ReportsAtTheSetOverride) {
  CompileOptions options;
  options.overrides = {{"trace.resolution", "half"}};
  EXPECT_EQ(single_error(trace_graph("", ""), options),
            "--set trace.resolution=half: error: pass 'trace' field 'params.resolution': 'half' "
            "needs 'half_res' bound");
}

TEST(ValidateHook, ReportsAtTheSlotBindingAndChecksCulledPasses) {
  const std::string text = trace_graph("", R"(, "half_res": "quarter")");
  EXPECT_EQ(single_error(text), where(text, "\"quarter\" }", "\"half_res\"") +
                                    ": error: pass 'trace' field 'out.half_res': must be half the "
                                    "size of 'result'");
  // A pass the scene culls is still a mistake in the file.
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 0}};
  const std::string culled = single_error(
      trace_graph("", R"(, "half_res": "quarter")", R"(, "when": "scene.has_glossy")"), options);
  EXPECT_NE(culled.find("must be half the size of 'result'"), std::string::npos) << culled;
}

TEST(ValidateHook, SkippedWhenThePassHasOtherErrors) {
  // An unknown resource is reported once; the hook does not add a second, derived error.
  const std::string error = single_error(
      trace_graph(R"(, "params": { "resolution": "half" })", R"(, "half_res": "hlaf")"));
  EXPECT_NE(error.find("unknown resource 'hlaf'"), std::string::npos) << error;
}

// ---- barriers of frames in which passes skip ------------------------------------------------

const Barrier* find_barrier(const CompiledGraph& g, const std::vector<Barrier>& list,
                            const std::string& resource) {
  const int r = g.find_resource(resource);
  for (const Barrier& b : list) {
    if (b.resource == r) return &b;
  }
  return nullptr;
}

// Every barrier of a frame touching `resource`.
std::vector<Barrier> barriers_on(const CompiledGraph& g, const FrameBarriers& frame,
                                 const std::string& resource) {
  std::vector<Barrier> found;
  const int r = g.find_resource(resource);
  auto scan = [&](const std::vector<Barrier>& list) {
    for (const Barrier& b : list) {
      if (b.resource == r) found.push_back(b);
    }
  };
  scan(frame.frame_start);
  for (const std::vector<Barrier>& pass : frame.passes) scan(pass);
  scan(frame.frame_end);
  return found;
}

bool same_barriers(const std::vector<Barrier>& a, const std::vector<Barrier>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].resource != b[i].resource || a[i].base_mip != b[i].base_mip ||
        a[i].mip_count != b[i].mip_count || a[i].old_layout != b[i].old_layout ||
        a[i].new_layout != b[i].new_layout || a[i].src_stages != b[i].src_stages ||
        a[i].dst_stages != b[i].dst_stages || a[i].src_access != b[i].src_access ||
        a[i].dst_access != b[i].dst_access) {
      return false;
    }
  }
  return true;
}

size_t pass_index(const CompiledGraph& g, const std::string& name) {
  for (size_t s = 0; s < g.passes.size(); ++s) {
    if (g.passes[s].name == name) return s;
  }
  ADD_FAILURE() << "no pass " << name;
  return 0;
}

TEST(FrameSync, AFrameOfAllPassesHasTheCompiledBarriers) {
  const CompiledGraph g = test::compile_text(voxel_graph(", \"persistent\": true"), registry());
  FrameSync sync(g);
  const std::vector<bool> none(g.passes.size(), false);
  for (int frame = 0; frame < 3; ++frame) {
    const FrameBarriers planned = sync.plan(none);
    EXPECT_TRUE(same_barriers(planned.frame_start, g.frame_start));
    EXPECT_TRUE(same_barriers(planned.frame_end, g.frame_end));
    for (size_t s = 0; s < g.passes.size(); ++s) {
      EXPECT_TRUE(same_barriers(planned.passes[s], g.passes[s].barriers)) << g.passes[s].name;
    }
  }
}

TEST(FrameSync, WhatASkippedPassWouldWriteGetsNoBarrier) {
  const CompiledGraph g = test::compile_text(voxel_graph(", \"persistent\": true"), registry());
  // Every frame of all passes moves the volume to GENERAL for the write and back to
  // SHADER_READ_ONLY for the reader.
  ASSERT_NE(find_barrier(g, g.frame_start, "volume"), nullptr);
  ASSERT_NE(find_barrier(g, g.find_pass("shade")->barriers, "volume"), nullptr);
  FrameSync sync(g);
  std::vector<bool> skipped(g.passes.size(), false);
  skipped[pass_index(g, "voxels")] = true;
  for (int frame = 0; frame < 2; ++frame) {
    const FrameBarriers planned = sync.plan(skipped);
    // The reader finds the volume where the last frame left it, written long before.
    EXPECT_TRUE(barriers_on(g, planned, "volume").empty()) << "frame " << frame;
    EXPECT_TRUE(barriers_on(g, planned, "scratch").empty()) << "frame " << frame;
    EXPECT_TRUE(planned.passes[pass_index(g, "voxels")].empty());
    EXPECT_LT(barrier_count(planned), barrier_count(sync.all_passes_frame()));
  }
  // When it runs again, the frame is the compiled one.
  const FrameBarriers again = sync.plan(std::vector<bool>(g.passes.size(), false));
  EXPECT_TRUE(same_barriers(again.frame_start, g.frame_start));
  EXPECT_TRUE(same_barriers(again.passes[pass_index(g, "shade")], g.find_pass("shade")->barriers));
}

TEST(FrameSync, AFrameInWhichAPassSkipsEndsWhereEveryFrameEnds) {
  // "history" is sampled before "accumulate" writes it in GENERAL, where every frame leaves it.
  // When accumulate skips, the reader's transition is undone at the frame's end.
  const CompiledGraph g = test::compile_text(test::graph_text(R"(
    "history": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },)",
                                                              R"(
    { "name": "shade", "type": "test.shade", "in": { "src": "history" }, "out": { "color": "ldr" } },
    { "name": "accumulate", "type": "skip.voxels", "out": { "volume": "history" } })"),
                                             registry());
  const CompiledResource& history = g.resources[static_cast<size_t>(g.find_resource("history"))];
  ASSERT_EQ(history.end_state.at(0).layout, VK_IMAGE_LAYOUT_GENERAL);
  FrameSync sync(g);
  std::vector<bool> skipped(g.passes.size(), false);
  skipped[pass_index(g, "accumulate")] = true;
  const FrameBarriers first = sync.plan(skipped);
  const std::vector<Barrier> on_history = barriers_on(g, first, "history");
  ASSERT_EQ(on_history.size(), 2u);
  EXPECT_EQ(on_history[0].old_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(on_history[0].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  // The frame still ends where every frame ends, for rebuilds and read-backs.
  EXPECT_EQ(on_history[1].new_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_NE(find_barrier(g, first.frame_end, "history"), nullptr);
  EXPECT_EQ(sync.state(static_cast<size_t>(history.physical), 0).layout, VK_IMAGE_LAYOUT_GENERAL);
}

}  // namespace
}  // namespace voxgi::graph
