// The executor on a real device: two compute passes through a buffer and an image, a
// persistent image, live and non-live parameter changes, and a pass that skips itself.
// The fixture fails on any validation or synchronisation-validation message.
#include <gtest/gtest.h>

#include <memory>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/dump.hpp"
#include "engine/graph/executor.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::param;
using test::slot;

int g_compose_setups = 0;
uint64_t g_values_version_seen = 0;   // resource_version("values") at compose's last execute
uint64_t g_history_version_seen = 0;  // resource_version("history") likewise

std::unique_ptr<gpu::ComputePipeline> make_pipeline(PassContext& ctx, const char* shader,
                                                    std::vector<gpu::Binding> bindings,
                                                    uint32_t push_size) {
  gpu::PipelineLayoutDesc layout;
  layout.bindings = std::move(bindings);
  layout.push_constant_size = push_size;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  return std::make_unique<gpu::ComputePipeline>(ctx.gpu(), ctx.shaders().compile({shader}), layout,
                                                ctx.pass_name());
}

class FillPass : public Pass {
 public:
  void setup(PassContext& ctx) override {
    pipeline_ =
        make_pipeline(ctx, "fill_buffer.comp",
                      {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}}, 8);
  }
  void execute(PassContext& ctx) override {
    const BoundResource& buf = ctx.resource("buf");
    struct {
      float value;
      uint32_t count;
    } push{static_cast<float>(ctx.number("value")),
           static_cast<uint32_t>(buf.info->buffer_size / sizeof(float))};
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_buffer(0, *buf.buffer)
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(ctx.cmd(), push);
    vkCmdDispatch(ctx.cmd(), gpu::ComputePipeline::groups(push.count, 64), 1, 1);
  }

 private:
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

// Adds 1 on the first frame after a build, then reports itself skipped.
class AccumulatePass : public Pass {
 public:
  void setup(PassContext& ctx) override {
    pipeline_ =
        make_pipeline(ctx, "accumulate.comp",
                      {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}}, 0);
  }
  std::string skip_reason(const PassContext& ctx) const override {
    return ctx.frame().first_frame ? std::string() : "nothing changed";
  }
  void execute(PassContext& ctx) override {
    const BoundResource& acc = ctx.resource("acc");
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_image(0, acc.view, acc.layout)
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    vkCmdDispatch(ctx.cmd(), gpu::ComputePipeline::groups(acc.info->extent.width, 8),
                  gpu::ComputePipeline::groups(acc.info->extent.height, 8), 1);
  }

 private:
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

class ComposePass : public Pass {
 public:
  void setup(PassContext& ctx) override {
    ++g_compose_setups;
    scale_at_setup_ = static_cast<float>(ctx.number("scale"));
    pipeline_ = make_pipeline(ctx, "compose.comp",
                              {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                               {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                               {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                               {3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}},
                              4);
  }
  void execute(PassContext& ctx) override {
    g_values_version_seen = ctx.resource_version("values");
    g_history_version_seen = ctx.resource_version("history");
    const BoundResource& values = ctx.resource("values");
    const BoundResource& history = ctx.resource("history");
    const BoundResource& dst = ctx.resource("dst");
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_buffer(0, *values.buffer)
        .storage_image(1, history.view, history.layout)
        .storage_image(2, dst.view, dst.layout)
        .uniform_buffer(3, *ctx.frame().uniform_buffer)
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    // "scale" is not live: the value baked in at setup() is the one used.
    pipeline_->push_constants(ctx.cmd(), scale_at_setup_);
    vkCmdDispatch(ctx.cmd(), gpu::ComputePipeline::groups(dst.info->extent.width, 8),
                  gpu::ComputePipeline::groups(dst.info->extent.height, 8), 1);
  }

 private:
  float scale_at_setup_ = 1.0f;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

// dst = previous + 1: bound to "counter@previous" and "counter", it counts frames.
class IncrementPass : public Pass {
 public:
  void setup(PassContext& ctx) override {
    pipeline_ = make_pipeline(ctx, "increment.comp",
                              {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                               {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}},
                              0);
  }
  void execute(PassContext& ctx) override {
    const BoundResource& previous = ctx.resource("previous");
    const BoundResource& dst = ctx.resource("dst");
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_image(0, previous.view, previous.layout)
        .storage_image(1, dst.view, dst.layout)
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    vkCmdDispatch(ctx.cmd(), gpu::ComputePipeline::groups(dst.info->extent.width, 8),
                  gpu::ComputePipeline::groups(dst.info->extent.height, 8), 1);
  }

 private:
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

Registry make_exec_registry(bool accumulate_may_skip = true) {
  Registry r;
  constexpr ResourceKinds buffer = test::kBuffer;
  constexpr ResourceKinds image = test::kImage2D;
  PassTypeInfo fill;
  fill.type = "exec.fill";
  fill.outputs = {slot("buf", buffer, Access::StorageWrite, kStageCompute)};
  fill.params = {param("value", ParamType::Float, 1.0, -100.0, 100.0)};
  r.add(fill, [] { return std::make_unique<FillPass>(); });
  PassTypeInfo acc;
  acc.type = "exec.accumulate";
  acc.outputs = {slot("acc", image, Access::StorageReadWrite, kStageCompute)};
  acc.may_skip = accumulate_may_skip;
  r.add(acc, [] { return std::make_unique<AccumulatePass>(); });
  PassTypeInfo compose;
  compose.type = "exec.compose";
  compose.inputs = {slot("values", buffer, Access::StorageRead, kStageCompute),
                    slot("history", image, Access::StorageRead, kStageCompute)};
  compose.outputs = {slot("dst", image, Access::StorageWrite, kStageCompute, false,
                          {VK_FORMAT_R32G32B32A32_SFLOAT})};
  ParamSpec scale = param("scale", ParamType::Float, 1.0, 0.0, 10.0);
  scale.live = false;
  compose.params = {scale};
  compose.validate = [](PassCheck& check) {
    if (check.number("scale") == 0.0) check.param_error("scale", "0 would zero the result");
  };
  r.add(compose, [] { return std::make_unique<ComposePass>(); });
  PassTypeInfo increment;
  increment.type = "exec.increment";
  increment.inputs = {slot("previous", image, Access::StorageRead, kStageCompute)};
  increment.outputs = {slot("dst", image, Access::StorageWrite, kStageCompute, false,
                            {VK_FORMAT_R32G32B32A32_SFLOAT})};
  r.add(increment, [] { return std::make_unique<IncrementPass>(); });
  return r;
}

constexpr uint32_t kSize = 8;

const char* kGraph = R"({
  "name": "exec",
  "resources": {
    "values": { "type": "buffer", "size": 256 },
    "history": { "type": "image2d", "format": "rgba32f", "size": 8, "persistent": true },
    "result": { "type": "image2d", "format": "rgba32f", "size": 8 } },
  "passes": [
    { "name": "compose", "type": "exec.compose", "params": { "scale": 2 },
      "in": { "values": "values", "history": "history" }, "out": { "dst": "result" } },
    { "name": "fill", "type": "exec.fill", "params": { "value": 3 }, "out": { "buf": "values" } },
    { "name": "accumulate", "type": "exec.accumulate", "out": { "acc": "history" } } ],
  "outputs": { "linear": "result" } })";

class ExecutorTest : public voxgi::test::GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    shaders_ = std::make_unique<gpu::ShaderCompiler>(
        std::vector<std::filesystem::path>{
            std::filesystem::path(VOXGI_SOURCE_DIR) / "tests/graph/shaders",
            std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders"},
        "");
    gpu_scene_ = std::make_unique<scene::GpuScene>(context(), scene_);
    registry_ = make_exec_registry();
  }
  void TearDown() override {
    executor_.reset();
    gpu_scene_.reset();
    GpuTest::TearDown();
  }

  Executor& build(CompileOptions options = {}) { return build(compile_exec_graph(options)); }

  CompiledGraph compile_exec_graph(CompileOptions options = {}) {
    options.viewport_width = kSize;
    options.viewport_height = kSize;
    return compile(parse_graph(kGraph, "exec.json"), registry_, options);
  }

  Executor& build(const CompiledGraph& graph) {
    if (!executor_) executor_ = std::make_unique<Executor>(context(), *shaders_, registry_);
    executor_->build(graph, scene_, *gpu_scene_);
    return *executor_;
  }

  // Barriers of the executor's last frame on `resource`.
  size_t barriers_on(Executor& executor, const std::string& resource) {
    const int r = executor.compiled().find_resource(resource);
    const FrameBarriers& frame = executor.frame_barriers();
    size_t count = 0;
    auto scan = [&](const std::vector<Barrier>& list) {
      for (const Barrier& b : list) count += b.resource == r ? 1 : 0;
    };
    scan(frame.frame_start);
    for (const std::vector<Barrier>& pass : frame.passes) scan(pass);
    scan(frame.frame_end);
    return count;
  }

  // The message of the exception render() throws, or "" when it throws none.
  std::string render_error(Executor& executor) {
    try {
      executor.render({});
    } catch (const std::exception& e) {
      return e.what();
    }
    return {};
  }

  // Red channel of texel i of the output.
  std::vector<float> render_and_read(Executor& executor, std::vector<float>* all = nullptr) {
    executor.render({});
    uint32_t w = 0, h = 0;
    std::vector<float> rgba = executor.read_output("linear", w, h);
    EXPECT_EQ(w, kSize);
    EXPECT_EQ(h, kSize);
    if (all) *all = rgba;
    return rgba;
  }

  scene::Scene scene_;
  std::unique_ptr<gpu::ShaderCompiler> shaders_;
  std::unique_ptr<scene::GpuScene> gpu_scene_;
  Registry registry_;
  std::unique_ptr<Executor> executor_;
};

TEST_F(ExecutorTest, DeviceConditionsMustBeDecidedForTheDevice) {
  std::string text = kGraph;
  const std::string accumulate = R"("name": "accumulate", )";
  text.replace(text.find(accumulate), accumulate.size(),
               accumulate + R"("when": "device.shader_int64 || !device.shader_int64", )");
  CompileOptions options;
  options.viewport_width = kSize;
  options.viewport_height = kSize;
  const CompiledGraph without = compile(parse_graph(text, "exec.json"), registry_, options);
  try {
    build(without);
    FAIL() << "built a graph whose device conditions were decided without a device";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the `when` of pass 'accumulate' reads device features, "
                                         "but the graph was compiled without a device"),
              std::string::npos)
        << e.what();
  }

  use_device(options, context());
  const CompiledGraph with = compile(parse_graph(text, "exec.json"), registry_, options);
  EXPECT_EQ(with.device_name, context().device_name());
  EXPECT_EQ(with.device_features, gpu::device_feature_values(context().features()));
  Executor& executor = build(with);
  EXPECT_EQ(render_error(executor), "");
}

TEST_F(ExecutorTest, RunsComputePassesInDependencyOrder) {
  Executor& executor = build();
  ASSERT_EQ(executor.compiled().passes.size(), 3u);
  // compose is listed first but reads what fill writes.
  EXPECT_EQ(executor.compiled().passes[0].name, "fill");
  EXPECT_EQ(executor.compiled().passes[1].name, "compose");
  EXPECT_EQ(executor.compiled().passes[2].name, "accumulate");
  const std::vector<float> rgba = render_and_read(executor);
  for (uint32_t i = 0; i < kSize * kSize; ++i) {
    ASSERT_FLOAT_EQ(rgba[i * 4 + 0], (3.0f + static_cast<float>(i)) * 2.0f) << i;
    // compose reads history before accumulate writes it: the previous frame's, zero at first.
    ASSERT_FLOAT_EQ(rgba[i * 4 + 1], 0.0f) << i;
    ASSERT_FLOAT_EQ(rgba[i * 4 + 2], 0.0f) << i;  // frame index 0
  }
  const auto& timings = executor.timings();
  ASSERT_EQ(timings.size(), 3u);
  for (const auto& t : timings) {
    EXPECT_TRUE(t.skipped.empty()) << t.pass;
    EXPECT_GE(t.gpu_ms, 0.0);
    EXPECT_GE(t.cpu_ms, 0.0);
  }
  ASSERT_NE(executor.image("history"), nullptr);
  ASSERT_NE(executor.buffer("values"), nullptr);
  EXPECT_EQ(executor.image("nope"), nullptr);
}

TEST_F(ExecutorTest, SkippedPassIsReportedAndPersistentContentsStay) {
  Executor& executor = build();
  render_and_read(executor);
  const std::vector<float> second = render_and_read(executor);
  const auto& timings = executor.timings();
  ASSERT_EQ(timings[2].pass, "accumulate");
  EXPECT_EQ(timings[2].skipped, "nothing changed");
  EXPECT_FLOAT_EQ(second[1], 1.0f);  // the first frame's accumulation
  EXPECT_FLOAT_EQ(second[2], 1.0f);  // frame index 1
  const std::vector<float> third = render_and_read(executor);
  EXPECT_FLOAT_EQ(third[1], 1.0f);  // skipped, so not accumulated again
  EXPECT_EQ(executor.frame_index(), 3u);
}

// A skipped pass gets no barriers, and neither does what it would have written: the frame after
// accumulate's last run still makes that write visible to compose, the next touches history not
// at all. Synchronisation validation checks both.
TEST_F(ExecutorTest, SkippedPassRecordsNoBarrierForWhatItWouldWrite) {
  Executor& executor = build();
  render_and_read(executor);
  const size_t every_pass = barrier_count(executor.frame_barriers());
  EXPECT_EQ(every_pass, barrier_count(FrameSync(executor.compiled()).all_passes_frame()));
  render_and_read(executor);
  EXPECT_EQ(barriers_on(executor, "history"), 1u);
  const std::vector<float> third = render_and_read(executor);
  EXPECT_EQ(barriers_on(executor, "history"), 0u);
  EXPECT_LT(barrier_count(executor.frame_barriers()), every_pass);
  EXPECT_FLOAT_EQ(third[1], 1.0f);  // still the first frame's accumulation
}

TEST_F(ExecutorTest, RefusesASkipItsTypeDoesNotDeclare) {
  registry_ = make_exec_registry(/*accumulate_may_skip=*/false);
  Executor& executor = build();
  render_and_read(executor);
  const std::string error = render_error(executor);
  EXPECT_NE(error.find("pass 'accumulate' (exec.accumulate) reported a skip (\"nothing "
                       "changed\"), but its type does not declare may_skip"),
            std::string::npos)
      << error;
}

TEST_F(ExecutorTest, RefusesASkipThatLeavesATransientUndefined) {
  // The compiler rejects such a graph; one put together otherwise still meets the executor.
  CompiledGraph graph = compile_exec_graph();
  const int history = graph.find_resource("history");
  graph.resources[static_cast<size_t>(history)].info.persistent = false;
  for (CompiledPass& pass : graph.passes) {
    for (SlotBinding& b : pass.bindings) {
      if (b.resource == history) b.info.persistent = false;
    }
  }
  Executor& executor = build(graph);
  render_and_read(executor);  // the first frame runs every pass
  const std::string error = render_error(executor);
  EXPECT_NE(error.find("pass 'accumulate' (exec.accumulate) reported a skip"), std::string::npos)
      << error;
  EXPECT_NE(error.find("writes the transient resource 'history' (slot 'acc')"), std::string::npos)
      << error;
  // Nothing of the refused frame was recorded: the next one with no skip renders cleanly.
  EXPECT_NO_THROW(build());
  render_and_read(*executor_);
}

TEST_F(ExecutorTest, ResourceVersionsCountExecutedWritersOnly) {
  Executor& executor = build();
  render_and_read(executor);
  EXPECT_EQ(g_values_version_seen, 1u);   // fill ran before compose
  EXPECT_EQ(g_history_version_seen, 0u);  // accumulate runs after compose
  render_and_read(executor);
  EXPECT_EQ(g_values_version_seen, 2u);
  EXPECT_EQ(g_history_version_seen, 1u);
  render_and_read(executor);
  EXPECT_EQ(g_values_version_seen, 3u);
  EXPECT_EQ(g_history_version_seen, 1u);  // accumulate skipped on frame 2
}

TEST_F(ExecutorTest, LiveAndNonLiveParameterChanges) {
  Executor& executor = build();
  render_and_read(executor);
  EXPECT_TRUE(executor.set_param("fill.value", "10"));
  std::vector<float> rgba = render_and_read(executor);
  EXPECT_FLOAT_EQ(rgba[0], 20.0f);
  EXPECT_FLOAT_EQ(rgba[4], 22.0f);

  const int setups = g_compose_setups;
  EXPECT_FALSE(executor.set_param("compose.scale", "0.5"));
  EXPECT_EQ(g_compose_setups, setups + 1);
  rgba = render_and_read(executor);
  EXPECT_FLOAT_EQ(rgba[0], 5.0f);

  EXPECT_THROW(executor.set_param("compose.scale", "11"), GraphError);
  // The type's validate hook sees every change; a refused value is not kept.
  try {
    executor.set_param("compose.scale", "0");
    ADD_FAILURE() << "scale 0 was accepted";
  } catch (const GraphError& e) {
    EXPECT_EQ(std::string(e.what()),
              "error: pass 'compose' field 'params.scale': 0 would zero the result");
  }
  EXPECT_DOUBLE_EQ(executor.compiled().find_pass("compose")->params.at("scale").number, 0.5);
  EXPECT_THROW(executor.set_param("fill.valeu", "1"), GraphError);
  try {
    executor.set_param("fill.valeu", "1");
  } catch (const GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'fill.value'"), std::string::npos)
        << e.what();
  }
}

TEST_F(ExecutorTest, RebuildKeepsPersistentContentsAndFullBarriersAreClean) {
  Executor& executor = build();
  render_and_read(executor);
  CompileOptions options;
  options.full_barriers = true;
  build(options);  // same description: history is kept (a new one would read 0)
  std::vector<float> rgba = render_and_read(executor);
  EXPECT_FLOAT_EQ(rgba[1], 1.0f);
  EXPECT_FLOAT_EQ(rgba[2], 0.0f);  // frame index restarts after a build
  rgba = render_and_read(executor);
  EXPECT_FLOAT_EQ(rgba[1], 2.0f);  // accumulate ran again on the first frame of the build
  EXPECT_FLOAT_EQ(rgba[0], 6.0f);
}

// A transient buffer and a later transient image of another description take turns in one
// block of memory; the image's first barrier waits for the buffer's last read (synchronisation
// validation would report the hazard), and what flows through the chain arrives intact.
TEST_F(ExecutorTest, TransientsOfDifferentDescriptionsShareMemoryInTurn) {
  const char* graph = R"({
  "resources": {
    "history": { "type": "image2d", "format": "rgba32f", "size": 8, "persistent": true },
    "a": { "type": "buffer", "size": 256 },
    "b": { "type": "buffer", "size": 256, "persistent": true },
    "m1": { "type": "image2d", "format": "rgba32f", "size": 8 },
    "m2": { "type": "image2d", "format": "rgba32f", "size": 8 },
    "result": { "type": "image2d", "format": "rgba32f", "size": 8 } },
  "passes": [
    { "name": "accumulate", "type": "exec.accumulate", "out": { "acc": "history" } },
    { "name": "fill_a", "type": "exec.fill", "params": { "value": 3 }, "out": { "buf": "a" } },
    { "name": "c1", "type": "exec.compose", "in": { "values": "a", "history": "history" },
      "out": { "dst": "m1" } },
    { "name": "fill_b", "type": "exec.fill", "params": { "value": 5 }, "out": { "buf": "b" } },
    { "name": "c2", "type": "exec.compose", "in": { "values": "b", "history": "m1" },
      "out": { "dst": "m2" } },
    { "name": "c3", "type": "exec.compose", "params": { "scale": 2 },
      "in": { "values": "b", "history": "m2" }, "out": { "dst": "result" } } ],
  "outputs": { "linear": "result" } })";
  CompileOptions options;
  options.viewport_width = options.viewport_height = kSize;
  const CompiledGraph compiled = compile(parse_graph(graph, "alias.json"), registry_, options);
  const auto physical = [&](const char* name) {
    return compiled.physical[static_cast<size_t>(
        compiled.resources[static_cast<size_t>(compiled.find_resource(name))].physical)];
  };
  ASSERT_EQ(compiled.memory_blocks.size(), 1u) << explain(compiled);
  EXPECT_GE(physical("a").memory_block, 0);
  EXPECT_EQ(physical("a").memory_block, physical("m2").memory_block);
  EXPECT_EQ(physical("m1").memory_block, -1);  // alive while a is
  EXPECT_LT(compiled.total_bytes, compiled.total_bytes_unshared);

  Executor& executor = build(compiled);
  for (int frame = 0; frame < 3; ++frame) {
    const std::vector<float> rgba = render_and_read(executor);
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
      ASSERT_FLOAT_EQ(rgba[i * 4 + 0], (5.0f + static_cast<float>(i)) * 2.0f) << i;
      // history (1 after the first frame's accumulate) went through m1 and m2.
      ASSERT_FLOAT_EQ(rgba[i * 4 + 1], 1.0f) << frame << " " << i;
    }
  }
}

// Frame history: "counter@previous" is what "counter" held when the previous frame ended
// (zeros on a new executor's first frame), so a pass reading it and writing counter counts
// frames, whether counter itself is transient or persistent. A rebuild keeps the copy (it is
// persistent), so counting goes on across it.
TEST_F(ExecutorTest, PreviousFrameBindingCountsFrames) {
  for (const char* persistent : {"false", "true"}) {
    const std::string graph = std::string(R"({
    "resources": {
      "counter": { "type": "image2d", "format": "rgba32f", "size": 8, "persistent": )") +
                              persistent + R"( },
      "result": { "type": "image2d", "format": "rgba32f", "size": 8 } },
    "passes": [
      { "name": "count", "type": "exec.increment", "in": { "previous": "counter@previous" },
        "out": { "dst": "counter" } },
      { "name": "show", "type": "exec.increment", "in": { "previous": "counter" },
        "out": { "dst": "result" } } ],
    "outputs": { "linear": "result" } })";
    CompileOptions options;
    options.viewport_width = options.viewport_height = kSize;
    const CompiledGraph compiled = compile(parse_graph(graph, "history.json"), registry_, options);
    ASSERT_EQ(compiled.history_copies.size(), 1u);
    const int twin = compiled.find_resource("counter@previous");
    ASSERT_GE(twin, 0);
    EXPECT_TRUE(compiled.resources[static_cast<size_t>(twin)].info.persistent);
    EXPECT_NE(explain(compiled).find("copy counter -> counter@previous"), std::string::npos)
        << explain(compiled);
    executor_.reset();
    Executor& executor = build(compiled);
    for (int frame = 1; frame <= 4; ++frame) {
      const std::vector<float> rgba = render_and_read(executor);
      // show adds one to the counter it reads: frame + 1.
      ASSERT_FLOAT_EQ(rgba[0], static_cast<float>(frame + 1)) << persistent << " " << frame;
      ASSERT_FLOAT_EQ(rgba[4 * (kSize * kSize - 1) + 3], static_cast<float>(frame + 1));
    }
    build(compiled);
    EXPECT_FLOAT_EQ(render_and_read(executor)[0], 6.0f) << persistent;
  }
}

}  // namespace
}  // namespace voxgi::graph
