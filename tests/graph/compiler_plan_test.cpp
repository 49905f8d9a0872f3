// Culling, ordering, barriers and resource sharing of compiled graphs.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/graph/dump.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::compile_text;
using test::make_registry;

CompiledGraph compile_graph(const std::string& resources, const std::string& passes,
                            CompileOptions options = {}) {
  static const Registry registry = make_registry();
  return compile_text(test::graph_text(resources, passes), registry, options);
}

std::vector<std::string> schedule(const CompiledGraph& g) {
  std::vector<std::string> names;
  for (const CompiledPass& p : g.passes) names.push_back(p.name);
  return names;
}

const Barrier* find_barrier(const CompiledGraph& g, const std::vector<Barrier>& list,
                            const std::string& resource, uint32_t mip = 0) {
  const int r = g.find_resource(resource);
  for (const Barrier& b : list) {
    if (b.resource == r && mip >= b.base_mip && mip < b.base_mip + b.mip_count) return &b;
  }
  return nullptr;
}

const std::string kClear =
    R"({ "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },)";
const std::string kShade =
    R"({ "name": "shade", "type": "test.shade", "in": { "src": "hdr" }, "out": { "color": "ldr" } },)";

TEST(CompilerCulling, WhenFalseCullsWithReason) {
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 0}};
  const CompiledGraph g = compile_graph(
      R"("spec": { "type": "image2d", "format": "rgba16f", "size": 8 },)", kClear + R"(
    { "name": "specular", "type": "test.blur", "when": "scene.has_glossy", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "spec" }, "out": { "color": "ldr" } })",
      options);
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"clear", "shade"}));
  ASSERT_NE(g.find_culled("specular"), nullptr);
  EXPECT_EQ(g.find_culled("specular")->reason, "when 'scene.has_glossy' is false for this scene");
  // The optional input whose only writer was culled is unbound.
  EXPECT_EQ(g.find_pass("shade")->binding("extra")->resource, -1);
  EXPECT_EQ(g.resources[static_cast<size_t>(g.find_resource("spec"))].physical, -1);

  options.scene_features = {{"scene.has_glossy", 1}};
  const CompiledGraph with = compile_graph(
      R"("spec": { "type": "image2d", "format": "rgba16f", "size": 8 },)", kClear + R"(
    { "name": "specular", "type": "test.blur", "when": "scene.has_glossy", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "spec" }, "out": { "color": "ldr" } })",
      options);
  EXPECT_EQ(schedule(with), (std::vector<std::string>{"clear", "specular", "shade"}));
  EXPECT_TRUE(with.culled.empty());
}

// A pass parameter may follow the condition that adds another pass (vct.cone_trace's
// specular_layer follows the specular pass's scene.has_glossy).
TEST(CompilerCulling, PassParametersReadSceneFeatures) {
  const std::string passes =
      R"({ "name": "clear", "type": "test.clear", "params": { "enabled": "scene.has_glossy" }, "out": { "color": "hdr" } },)" +
      kShade;
  for (double glossy : {0.0, 1.0}) {
    CompileOptions options;
    options.scene_features = {{"scene.has_glossy", glossy}};
    const CompiledGraph g = compile_graph("", passes, options);
    EXPECT_DOUBLE_EQ(g.find_pass("clear")->params.at("enabled").number, glossy);
  }
}

const std::string kDeviceChoice = kClear + R"(
    { "name": "traced", "type": "test.blur", "when": "device.ray_query && scene.has_glossy", "in": { "src": "hdr" }, "out": { "dst": "spec" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "spec" }, "out": { "color": "ldr" } })";
const std::string kSpec = R"("spec": { "type": "image2d", "format": "rgba16f", "size": 8 },)";

TEST(CompilerCulling, WhenReadsDeviceFeatures) {
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 1}};
  options.device_features = {{"device.ray_query", 1}, {"device.shader_int64", 1}};
  options.device_name = "test gpu";
  const CompiledGraph with = compile_graph(kSpec, kDeviceChoice, options);
  EXPECT_EQ(schedule(with), (std::vector<std::string>{"clear", "traced", "shade"}));
  EXPECT_TRUE(with.device_queried);
  EXPECT_EQ(with.device_name, "test gpu");
  EXPECT_DOUBLE_EQ(with.device_features.at("device.ray_query"), 1.0);
  // Names the options leave out read as absent.
  EXPECT_DOUBLE_EQ(with.device_features.at("device.ray_tracing_pipeline"), 0.0);
  ASSERT_EQ(with.device_conditions.size(), 1u);
  EXPECT_EQ(with.device_conditions[0].pass, "traced");
  EXPECT_EQ(with.device_conditions[0].features, (std::vector<std::string>{"device.ray_query"}));
  EXPECT_TRUE(with.device_conditions[0].value);

  options.device_features = {{"device.ray_query", 0}};
  const CompiledGraph without = compile_graph(kSpec, kDeviceChoice, options);
  EXPECT_EQ(schedule(without), (std::vector<std::string>{"clear", "shade"}));
  EXPECT_EQ(without.find_culled("traced")->reason,
            "when 'device.ray_query && scene.has_glossy' is false for this scene and device "
            "'test gpu'");
  ASSERT_EQ(without.device_conditions.size(), 1u);
  EXPECT_FALSE(without.device_conditions[0].value);
}

TEST(CompilerCulling, WithoutADeviceEveryDeviceFeatureIsAbsent) {
  CompileOptions options;
  options.scene_features = {{"scene.has_glossy", 1}};
  const CompiledGraph g = compile_graph(kSpec, kDeviceChoice, options);
  EXPECT_FALSE(g.device_queried);
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"clear", "shade"}));
  EXPECT_EQ(g.find_culled("traced")->reason,
            "when 'device.ray_query && scene.has_glossy' is false for this scene (compiled "
            "without a device: device features read as absent)");
  for (const auto& [name, value] : g.device_features) EXPECT_DOUBLE_EQ(value, 0.0) << name;
  EXPECT_TRUE(g.device_features.count("device.conservative_rasterization"));
  // A condition that does not read the device says nothing about it.
  EXPECT_TRUE(compile_graph(kSpec, kClear + kShade, options).device_conditions.empty());
}

TEST(CompilerCulling, UnreachablePassesAreCulled) {
  const CompiledGraph g = compile_graph(
      R"("debug": { "type": "image2d", "format": "rgba16f", "size": 8 },)", kClear + kShade + R"(
    { "name": "debug_view", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "debug" } })");
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"clear", "shade"}));
  ASSERT_EQ(g.culled.size(), 1u);
  EXPECT_EQ(g.culled[0].name, "debug_view");
  EXPECT_EQ(g.culled[0].reason, "no output depends on it");
}

TEST(CompilerCulling, CullingPropagatesThroughRequiredInputs) {
  CompileOptions options;
  options.overrides = {{"use_gi", "false"}};
  const Registry registry = make_registry();
  const CompiledGraph g = compile_text(R"({
  "parameters": { "use_gi": true },
  "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "gi": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "gi_filtered": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 } },
  "passes": [
    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
    { "name": "gi", "type": "test.blur", "when": "${use_gi}", "in": { "src": "hdr" }, "out": { "dst": "gi" } },
    { "name": "filter", "type": "test.blur", "in": { "src": "gi" }, "out": { "dst": "gi_filtered" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "gi_filtered" }, "out": { "color": "ldr" } } ],
  "outputs": { "display": "ldr" } })",
                                       registry, options);
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"clear", "shade"}));
  ASSERT_EQ(g.culled.size(), 2u);
  EXPECT_EQ(g.find_culled("gi")->reason, "when '${use_gi}' is false for this scene");
  EXPECT_EQ(g.find_culled("filter")->reason, "input 'src' is only written by culled pass 'gi'");
  EXPECT_FALSE(g.find_pass("shade")->binding("extra")->resource >= 0);
}

TEST(CompilerOrdering, DependenciesDecideNotFileOrder) {
  // Listed backwards: readers before writers. The schedule follows the data.
  const std::string resources = R"("half": { "type": "image2d", "format": "rgba16f", "size": 4 },)";
  const std::string shade =
      R"({ "name": "shade", "type": "test.shade", "in": { "src": "half" }, "out": { "color": "ldr" } },)";
  const std::string blur =
      R"({ "name": "blur", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "half" } },)";
  const CompiledGraph backwards = compile_graph(resources, shade + blur + kClear);
  EXPECT_EQ(schedule(backwards), (std::vector<std::string>{"clear", "blur", "shade"}));
  const CompiledGraph forwards = compile_graph(resources, kClear + blur + shade);
  EXPECT_EQ(schedule(forwards), schedule(backwards));
  EXPECT_EQ(forwards.passes[2].depends_on, (std::vector<size_t>{1}));
}

TEST(CompilerOrdering, IndependentPassesKeepFileOrderAndResultsAreStable) {
  const std::string resources = R"("a": { "type": "image2d", "format": "rgba16f", "size": 4 },
    "b": { "type": "image2d", "format": "rgba16f", "size": 4 },)";
  const std::string pa =
      R"({ "name": "pa", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "a" } },)";
  const std::string pb =
      R"({ "name": "pb", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "b" } },)";
  const std::string shade =
      R"({ "name": "shade", "type": "test.shade", "in": { "src": "a", "extra": "b" }, "out": { "color": "ldr" } },)";
  const CompiledGraph first = compile_graph(resources, kClear + pa + pb + shade);
  EXPECT_EQ(schedule(first), (std::vector<std::string>{"clear", "pa", "pb", "shade"}));
  for (int run = 0; run < 5; ++run) {
    EXPECT_EQ(schedule(compile_graph(resources, kClear + pa + pb + shade)), schedule(first));
  }
  // Moving the dependent passes around in the file does not change where they run.
  EXPECT_EQ(schedule(compile_graph(resources, shade + pa + kClear + pb)),
            (std::vector<std::string>{"clear", "pa", "pb", "shade"}));
}

TEST(CompilerOrdering, LaterWritersFollowEarlierReaders) {
  // shade samples hdr, then "overwrite" clears hdr again for the next use: write after read.
  const CompiledGraph g = compile_graph(
      R"("copy": { "type": "image2d", "format": "rgba16f", "size": 8 },)",
      kClear + kShade + R"({ "name": "overwrite", "type": "test.clear", "out": { "color": "hdr" } },
      { "name": "keep", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "copy" } },
      { "name": "shade2", "type": "test.shade", "in": { "src": "hdr", "extra": "copy" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(schedule(g),
            (std::vector<std::string>{"clear", "shade", "overwrite", "keep", "shade2"}));
  const CompiledPass* overwrite = g.find_pass("overwrite");
  EXPECT_NE(std::find(overwrite->depends_on.begin(), overwrite->depends_on.end(), 1u),
            overwrite->depends_on.end());
}

TEST(CompilerBarriers, ColorAttachmentToSampled) {
  const CompiledGraph g = compile_graph("", kClear + kShade);
  const Barrier* first = find_barrier(g, g.passes[0].barriers, "hdr");
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->old_layout, VK_IMAGE_LAYOUT_UNDEFINED);  // transient: contents discarded
  EXPECT_EQ(first->new_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  const Barrier* b = find_barrier(g, g.passes[1].barriers, "hdr");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->old_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(b->new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(b->src_stages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  EXPECT_EQ(b->src_access, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  EXPECT_EQ(b->dst_stages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(b->dst_access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  // The output goes to TRANSFER_SRC when the frame ends.
  const Barrier* end = find_barrier(g, g.frame_end, "ldr");
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->old_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(end->new_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  // Usage is the union of every access, plus sampled/transfer for viewers and read-back.
  const CompiledResource& hdr = g.resources[static_cast<size_t>(g.find_resource("hdr"))];
  EXPECT_EQ(hdr.image_usage, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  const CompiledResource& ldr = g.resources[static_cast<size_t>(g.find_resource("ldr"))];
  EXPECT_TRUE(ldr.image_usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

TEST(CompilerBarriers, StorageWriteToSampledAndReadAfterReadNeedsNone) {
  const CompiledGraph g = compile_graph(
      R"("half": { "type": "image2d", "format": "rgba16f", "size": 4 },
         "ldr2": { "type": "image2d", "format": "rgba8", "size": 8 },)",
      kClear +
          R"({ "name": "blur", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "half" } },
      { "name": "shade", "type": "test.shade", "in": { "src": "half" }, "out": { "color": "ldr" } },
      { "name": "shade2", "type": "test.shade", "in": { "src": "half", "extra": "ldr2" }, "out": { "color": "ldr" } },
      { "name": "make_ldr2", "type": "test.clear", "out": { "color": "ldr2" } })");
  EXPECT_EQ(schedule(g),
            (std::vector<std::string>{"clear", "blur", "shade", "make_ldr2", "shade2"}));
  const Barrier* b = find_barrier(g, g.find_pass("shade")->barriers, "half");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->old_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(b->new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(b->src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // shade2 samples half in the same stage and layout as shade: no barrier.
  EXPECT_EQ(find_barrier(g, g.find_pass("shade2")->barriers, "half"), nullptr);
  // But it writes ldr after shade wrote it: a write-after-write barrier.
  const Barrier* waw = find_barrier(g, g.find_pass("shade2")->barriers, "ldr");
  ASSERT_NE(waw, nullptr);
  EXPECT_EQ(waw->old_layout, waw->new_layout);
  EXPECT_EQ(waw->src_access, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

TEST(CompilerBarriers, PerMipBarriersForSingleMipSlots) {
  const CompiledGraph g = compile_graph(
      R"("vox": { "type": "image3d", "format": "rgba16f", "size": 8, "mips": "full" },)",
      kClear +
          R"({ "name": "mip0", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "vox@0" } },
      { "name": "mip1", "type": "test.mip", "in": { "src": "vox@0" }, "out": { "dst": "vox@1" } },
      { "name": "mip2", "type": "test.mip", "in": { "src": "vox@1" }, "out": { "dst": "vox@2" } },
      { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "vox" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"clear", "mip0", "mip1", "mip2", "shade"}));
  const std::vector<Barrier>& mip1 = g.find_pass("mip1")->barriers;
  const Barrier* read0 = find_barrier(g, mip1, "vox", 0);
  ASSERT_NE(read0, nullptr);
  EXPECT_EQ(read0->base_mip, 0u);
  EXPECT_EQ(read0->mip_count, 1u);
  EXPECT_EQ(read0->old_layout, VK_IMAGE_LAYOUT_GENERAL);  // storage write -> storage read
  EXPECT_EQ(read0->src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(read0->dst_access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  const Barrier* write1 = find_barrier(g, mip1, "vox", 1);
  ASSERT_NE(write1, nullptr);
  EXPECT_EQ(write1->base_mip, 1u);
  EXPECT_EQ(write1->old_layout, VK_IMAGE_LAYOUT_UNDEFINED);  // first use of mip 1
  EXPECT_EQ(find_barrier(g, mip1, "vox", 2), nullptr);       // mip 2 not touched yet
  // shade samples all 4 mips: 0..2 come from GENERAL, 3 was never written (discarded).
  const std::vector<Barrier>& shade = g.find_pass("shade")->barriers;
  const Barrier* written = find_barrier(g, shade, "vox", 0);
  ASSERT_NE(written, nullptr);
  EXPECT_EQ(written->base_mip, 0u);
  EXPECT_EQ(written->mip_count, 3u);
  EXPECT_EQ(written->old_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(written->new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  const Barrier* untouched = find_barrier(g, shade, "vox", 3);
  ASSERT_NE(untouched, nullptr);
  EXPECT_EQ(untouched->old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
}

TEST(CompilerBarriers, PersistentResourcesTransitionAtFrameStart) {
  const CompiledGraph g = compile_graph(
      R"("history": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },)",
      kClear +
          R"({ "name": "accumulate", "type": "test.accumulate", "in": { "src": "hdr" }, "out": { "acc": "history" } },
      { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": "history" }, "out": { "color": "ldr" } })");
  const CompiledResource& history = g.resources[static_cast<size_t>(g.find_resource("history"))];
  EXPECT_TRUE(history.carries_contents);
  ASSERT_EQ(history.end_state.size(), 1u);
  EXPECT_EQ(history.end_state[0].layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  const Barrier* start = find_barrier(g, g.frame_start, "history");
  ASSERT_NE(start, nullptr);
  EXPECT_EQ(start->old_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);  // kept contents
  EXPECT_EQ(start->new_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(start->src_stages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(find_barrier(g, g.find_pass("accumulate")->barriers, "history"), nullptr);
}

// Indirect arguments written by a compute pass reach the dispatch through the draw-indirect
// stage; the buffer gets the indirect usage on top of storage.
TEST(CompilerBarriers, ComputeWrittenIndirectArguments) {
  const CompiledGraph g = compile_graph(
      R"("args": { "type": "buffer", "size": 64 },
         "a": { "type": "image2d", "format": "rgba16f", "size": 8 },
         "b": { "type": "image2d", "format": "rgba16f", "size": 8 },
         "c": { "type": "image2d", "format": "rgba16f", "size": 8 },)",
      R"({ "name": "fill", "type": "test.fill", "out": { "buf": "args" } },
      { "name": "first", "type": "test.indirect_dispatch", "in": { "args": "args" }, "out": { "dst": "a" } },
      { "name": "second", "type": "test.indirect_dispatch", "in": { "args": "args" }, "out": { "dst": "b" } },
      { "name": "third", "type": "test.indirect_dispatch", "in": { "args": "args", "data": "args" }, "out": { "dst": "c" } },
      { "name": "shade", "type": "test.shade", "in": { "src": "a", "extra": "b" }, "out": { "color": "hdr" } },
      { "name": "shade2", "type": "test.shade", "in": { "src": "c", "extra": "hdr" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(schedule(g),
            (std::vector<std::string>{"fill", "first", "second", "third", "shade", "shade2"}));
  const Barrier* b = find_barrier(g, g.find_pass("first")->barriers, "args");
  ASSERT_NE(b, nullptr);
  EXPECT_TRUE(b->is_buffer);
  EXPECT_EQ(b->src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b->dst_stages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
  EXPECT_EQ(b->dst_access, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  // Already visible to indirect reads: the second reader needs no barrier.
  EXPECT_EQ(find_barrier(g, g.find_pass("second")->barriers, "args"), nullptr);
  // A shader reading the same arguments as storage needs the write made visible to it too.
  const Barrier* storage = find_barrier(g, g.find_pass("third")->barriers, "args");
  ASSERT_NE(storage, nullptr);
  EXPECT_EQ(storage->src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_TRUE(storage->dst_access & VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  EXPECT_TRUE(storage->dst_stages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  const CompiledResource& args = g.resources[static_cast<size_t>(g.find_resource("args"))];
  EXPECT_TRUE(args.buffer_usage & VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  EXPECT_TRUE(args.buffer_usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  EXPECT_EQ(access_name(Access::IndirectRead), "indirect");
}

// Indirect arguments come from buffers and are only read: other declarations are refused.
TEST(CompilerBarriers, IndirectAccessIsForBufferInputsOnly) {
  Registry r;
  PassTypeInfo image_args;
  image_args.type = "bad.image_args";
  image_args.inputs = {test::slot("args", test::kImage2D, Access::IndirectRead, kStageCompute)};
  EXPECT_THROW(r.add(image_args, [] { return nullptr; }), std::invalid_argument);
  PassTypeInfo output_args;
  output_args.type = "bad.output_args";
  output_args.outputs = {test::slot("args", test::kBuffer, Access::IndirectRead, kStageCompute)};
  EXPECT_THROW(r.add(output_args, [] { return nullptr; }), std::invalid_argument);
}

TEST(CompilerBarriers, FullBarriersMode) {
  CompileOptions options;
  options.full_barriers = true;
  const CompiledGraph g = compile_graph("", kClear + kShade, options);
  EXPECT_TRUE(g.full_barriers);
  for (const CompiledPass& p : g.passes) {
    ASSERT_FALSE(p.barriers.empty());
    EXPECT_TRUE(p.barriers[0].is_global);
    EXPECT_EQ(p.barriers[0].src_stages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    EXPECT_EQ(p.barriers[0].dst_access, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    for (size_t i = 1; i < p.barriers.size(); ++i) {
      EXPECT_NE(p.barriers[i].old_layout, p.barriers[i].new_layout);  // only transitions remain
      EXPECT_EQ(p.barriers[i].src_stages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
  }
  const Barrier* b = find_barrier(g, g.passes[1].barriers, "hdr");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

const std::string kChain =
    R"({ "name": "b1", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "t1" } },
    { "name": "b2", "type": "test.blur", "in": { "src": "t1" }, "out": { "dst": "t2" } },
    { "name": "b3", "type": "test.blur", "in": { "src": "t2" }, "out": { "dst": "t3" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "t3" }, "out": { "color": "ldr" } })";

std::string chain_resources(bool t3_persistent) {
  return std::string(R"("t1": { "type": "image2d", "format": "rgba16f", "size": 16 },
    "t2": { "type": "image2d", "format": "rgba16f", "size": 16 },
    "t3": { "type": "image2d", "format": "rgba16f", "size": 16, "persistent": )") +
         (t3_persistent ? "true" : "false") + " },";
}

TEST(CompilerResources, DisjointTransientsShareOverlappingDoNot) {
  const CompiledGraph g = compile_graph(chain_resources(false), kClear + kChain);
  auto physical = [&](const char* name) {
    return g.resources[static_cast<size_t>(g.find_resource(name))].physical;
  };
  const CompiledResource& t1 = g.resources[static_cast<size_t>(g.find_resource("t1"))];
  EXPECT_EQ(t1.first_pass, 1);
  EXPECT_EQ(t1.last_pass, 2);
  EXPECT_EQ(physical("t1"), physical("t3"));  // lives [1,2] and [3,4]
  EXPECT_NE(physical("t1"), physical("t2"));  // [1,2] and [2,3] overlap
  EXPECT_NE(physical("t2"), physical("t3"));
  EXPECT_EQ(t1.bytes, 16u * 16u * 8u);
  // t3 lives in t1's allocation; hdr (8^2 rgba16f, 512 bytes, passes 0..1) takes turns with t2
  // in one block of memory.
  EXPECT_EQ(g.total_bytes_unshared - g.total_bytes, t1.bytes + 8u * 8u * 8u);
  // The second sharer's first use waits for the first sharer's last read.
  const Barrier* b = find_barrier(g, g.find_pass("b3")->barriers, "t3");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(b->src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);

  CompileOptions no_alias;
  no_alias.alias_transients = false;
  const CompiledGraph separate = compile_graph(chain_resources(false), kClear + kChain, no_alias);
  EXPECT_EQ(separate.physical.size(), separate.resources.size());
  EXPECT_EQ(separate.total_bytes, separate.total_bytes_unshared);
}

// Different descriptions cannot share an allocation, but with disjoint lives they take turns in
// blocks of memory: hdr (8^2 rgba16f, passes 0..1) then t2 (16^2 rgba16f, 2..3), and t1 (16^2
// rgba16f, 1..2) then t3 (32^2 r8, 3..4), each joining the block it grows least. The newcomer's
// first barrier waits for the last read of the one before.
TEST(CompilerResources, DisjointTransientsOfOtherDescriptionsShareMemoryInTurn) {
  const std::string resources = R"("t1": { "type": "image2d", "format": "rgba16f", "size": 16 },
    "t2": { "type": "image2d", "format": "rgba16f", "size": 16 },
    "t3": { "type": "image2d", "format": "r8", "size": 32 },)";
  const CompiledGraph g = compile_graph(resources, kClear + kChain);
  const auto physical = [&](const char* name) -> const PhysicalResource& {
    return g.physical[static_cast<size_t>(
        g.resources[static_cast<size_t>(g.find_resource(name))].physical)];
  };
  EXPECT_NE(&physical("t1"), &physical("t3"));
  ASSERT_EQ(g.memory_blocks.size(), 2u) << explain(g);
  EXPECT_EQ(physical("hdr").memory_block, physical("t2").memory_block);
  EXPECT_EQ(physical("t1").memory_block, physical("t3").memory_block);
  EXPECT_NE(physical("t1").memory_block, physical("t2").memory_block);
  EXPECT_EQ(physical("ldr").memory_block, -1);  // an output
  for (const MemoryBlock& block : g.memory_blocks) EXPECT_EQ(block.bytes, 16u * 16u * 8u);
  EXPECT_EQ(g.total_bytes_unshared - g.total_bytes, 8u * 8u * 8u + 32u * 32u);
  const Barrier* b = find_barrier(g, g.find_pass("b3")->barriers, "t3");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
  // b2's read of t1 (and t3's own read by shade in the frame before).
  EXPECT_TRUE(b->src_stages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_NE(explain(g).find("block 0, "), std::string::npos) << explain(g);

  CompileOptions no_alias;
  no_alias.alias_transients = false;
  EXPECT_TRUE(compile_graph(resources, kClear + kChain, no_alias).memory_blocks.empty());
}

TEST(CompilerResources, PersistentResourcesNeverShare) {
  const CompiledGraph g = compile_graph(chain_resources(true), kClear + kChain);
  for (const PhysicalResource& p : g.physical) EXPECT_EQ(p.resources.size(), 1u);
}

TEST(CompilerResources, SizesMipsLayersAndClipmaps) {
  CompileOptions options;
  options.viewport_width = 100;
  options.viewport_height = 60;
  const Registry registry = make_registry();
  const CompiledGraph g = compile(parse_graph(R"({
  "parameters": { "res": 16 },
  "resources": {
    "half": { "type": "image2d", "format": "rgba16f", "size": "viewport/2", "mips": "full" },
    "shadow": { "type": "image2d", "format": "d32f", "size": "${res} * 2", "layers": "6 * 4" },
    "clip": { "type": "clipmap", "format": "rgba16f", "resolution": "${res}", "levels": 6 },
    "buf": { "type": "buffer", "size": 4096 },
    "rect": { "type": "image3d", "format": "r32ui", "size": [8, "viewport.height / 10", 2] },
    "ldr": { "type": "image2d", "format": "rgba8", "size": "viewport" } },
  "passes": [
    { "name": "depth", "type": "test.depth", "out": { "depth": "shadow" } },
    { "name": "fill", "type": "test.fill", "out": { "buf": "buf" } },
    { "name": "use", "type": "test.use_buffer", "in": { "buf": "buf" }, "out": { "dst": "clip" } },
    { "name": "blur", "type": "test.blur", "in": { "src": "shadow", "extra": "clip" }, "out": { "dst": "half" } },
    { "name": "r", "type": "test.blur", "in": { "src": "half" }, "out": { "dst": "rect" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "half", "extra": "rect" }, "out": { "color": "ldr" } } ],
  "outputs": { "display": "ldr" } })",
                                              "g.json"),
                                  registry, options);
  auto info = [&](const char* name) {
    return g.resources[static_cast<size_t>(g.find_resource(name))].info;
  };
  EXPECT_EQ(info("half").extent.width, 50u);
  EXPECT_EQ(info("half").extent.height, 30u);
  EXPECT_EQ(info("half").mip_levels, 6u);
  EXPECT_EQ(info("shadow").extent.width, 32u);
  EXPECT_EQ(info("shadow").array_layers, 24u);
  EXPECT_EQ(info("clip").extent.depth, 96u);
  EXPECT_EQ(info("clip").clipmap_levels, 6u);
  EXPECT_EQ(info("buf").buffer_size, 4096u);
  EXPECT_EQ(info("rect").extent.height, 6u);
  EXPECT_EQ(info("rect").extent.depth, 2u);
  EXPECT_EQ(g.resources[static_cast<size_t>(g.find_resource("shadow"))].bytes,
            32u * 32u * 4u * 24u);
  const CompiledResource& buf = g.resources[static_cast<size_t>(g.find_resource("buf"))];
  EXPECT_EQ(
      buf.buffer_usage & (VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  const Barrier* b = find_barrier(g, g.find_pass("use")->barriers, "buf");
  ASSERT_NE(b, nullptr);
  EXPECT_TRUE(b->is_buffer);
  EXPECT_EQ(b->src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b->dst_access, VK_ACCESS_2_UNIFORM_READ_BIT);
  // Depth images sampled in shaders use the depth read-only layout.
  const Barrier* depth = find_barrier(g, g.find_pass("blur")->barriers, "shadow");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->old_layout, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(depth->new_layout, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
}

// "x@previous": the previous frame's x, read without a dependency on x's writer (so a
// temporal loop is no cycle), yet keeping that writer alive; both live to the frame's end,
// where the copy is made after every pass.
TEST(CompilerHistory, PreviousFrameReadsNeedNoOrderAndKeepTheWriter) {
  const CompiledGraph g = compile_graph(
      R"("x": { "type": "image2d", "format": "rgba16f", "size": 8 },
         "y": { "type": "image2d", "format": "rgba16f", "size": 8 },)",
      R"({ "name": "use", "type": "test.blur", "in": { "src": "x@previous" }, "out": { "dst": "y" } },
         { "name": "make", "type": "test.blur", "in": { "src": "y" }, "out": { "dst": "x" } },
         { "name": "shade", "type": "test.shade", "in": { "src": "y" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(schedule(g), (std::vector<std::string>{"use", "make", "shade"}));
  EXPECT_TRUE(g.culled.empty()) << "make writes only what 'use' reads a frame later";
  const int x = g.find_resource("x");
  const int twin = g.find_resource("x@previous");
  ASSERT_GE(twin, 0);
  EXPECT_EQ(g.resources[static_cast<size_t>(twin)].history_of, x);
  EXPECT_EQ(g.resources[static_cast<size_t>(x)].history, twin);
  EXPECT_TRUE(g.resources[static_cast<size_t>(twin)].info.persistent);
  EXPECT_EQ(g.find_pass("use")->binding("src")->resource, twin);
  ASSERT_EQ(g.history_copies.size(), 1u);
  EXPECT_EQ(g.history_copies[0].from, x);
  EXPECT_EQ(g.history_copies[0].to, twin);
  const int end = static_cast<int>(g.passes.size());
  EXPECT_EQ(g.resources[static_cast<size_t>(x)].last_pass, end);
  EXPECT_EQ(g.resources[static_cast<size_t>(twin)].last_pass, end);
  // Before the copy: x from shader write to transfer source, the twin to transfer destination.
  const Barrier* from = find_barrier(g, g.history_barriers, "x");
  const Barrier* to = find_barrier(g, g.history_barriers, "x@previous");
  ASSERT_NE(from, nullptr);
  ASSERT_NE(to, nullptr);
  EXPECT_EQ(from->new_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_EQ(to->new_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  // The reader then finds the copy in the transfer destination layout of the frame before
  // (moved as the frame starts, like any carried resource).
  const Barrier* read = find_barrier(g, g.frame_start, "x@previous");
  ASSERT_NE(read, nullptr);
  EXPECT_EQ(read->old_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  EXPECT_EQ(read->src_stages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
}

// A temporal loop whose writer sizes the resource (pass-owned size) after the reader of the
// previous frame's version: the read is bound once the writer has sized it.
TEST(CompilerHistory, PreviousFrameOfAResourceItsLaterWriterSizes) {
  const CompiledGraph g = compile_graph(
      R"("vol": { "type": "clipmap", "persistent": true },
         "t": { "type": "image2d", "format": "rgba16f", "size": 8 },)",
      R"({ "name": "use", "type": "test.blur", "in": { "src": "vol@previous" }, "out": { "dst": "t" } },
         { "name": "make", "type": "test.sized", "params": { "resolution": 16, "levels": 3 },
           "in": {}, "out": { "volume": "vol" } },
         { "name": "shade", "type": "test.shade", "in": { "src": "t", "extra": "vol" },
           "out": { "color": "ldr" } })");
  const SlotBinding* src = g.find_pass("use")->binding("src");
  ASSERT_NE(src, nullptr);
  const CompiledResource& twin = g.resources[static_cast<size_t>(src->resource)];
  EXPECT_EQ(twin.info.name, "vol@previous");
  EXPECT_EQ(twin.info.clipmap_levels, 3u);
  EXPECT_EQ(twin.info.extent.width, 16u);
  EXPECT_EQ(g.history_copies.size(), 1u);
}

TEST(CompilerHistory, OnlyInputsReadThePreviousFrame) {
  static const Registry registry = make_registry();
  const std::string e = test::single_compile_error(
      test::graph_text(R"("x": { "type": "image2d", "format": "rgba16f", "size": 8 },)",
                       kClear + R"({ "name": "make", "type": "test.blur", "in": { "src": "hdr" },
                            "out": { "dst": "x@previous" } },
                          { "name": "shade", "type": "test.shade", "in": { "src": "x" },
                            "out": { "color": "ldr" } })"),
      registry);
  EXPECT_NE(e.find("pass 'make' field 'out.dst'"), std::string::npos) << e;
  EXPECT_NE(e.find("'x@previous' is the previous frame's version: a pass may read it, not "
                   "write it"),
            std::string::npos)
      << e;
  const std::string typo = test::single_compile_error(
      test::graph_text(
          "", kClear + R"({ "name": "shade", "type": "test.shade", "in": { "src": "hdr@prev" },
                               "out": { "color": "ldr" } })"),
      registry);
  EXPECT_NE(typo.find("or \"previous\" (the previous frame's version) after '@', found 'prev'"),
            std::string::npos)
      << typo;
}

}  // namespace
}  // namespace voxgi::graph
