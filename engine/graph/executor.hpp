#pragma once
// Runs a compiled graph: allocates its resources, creates its passes through the registry,
// and records, submits and times one frame per render().

#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/memory.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/frame.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_context_impl.hpp"
#include "engine/graph/resource_plan.hpp"

namespace voxgi::gpu {
class TimestampQueries;
}

namespace voxgi::graph {

class Executor {
 public:
  Executor(gpu::Context& context, gpu::ShaderCompiler& shaders, const Registry& registry);
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  // Allocates one image or buffer per physical resource (a clipmap is one 3D image), keeping
  // persistent resources of the previous build whose description is unchanged, creates the
  // passes and runs their setup(). The scene objects must outlive the executor's use of them.
  void build(const CompiledGraph& graph, const scene::Scene& scene, scene::GpuScene& gpu_scene);

  // What changed drives the passes' skip decisions; the first frame of a build treats
  // everything as changed whatever it says.
  struct FrameInput {
    CameraView camera;
    double time = 0.0;
    bool camera_changed = true;
    bool lights_changed = true;
    bool geometry_changed = true;
  };

  // Records one command buffer for the whole frame, submits it and waits for it. Throws when a
  // pass skips against the skip contract (its type does not declare may_skip, or it writes a
  // transient resource), naming the pass and the resource.
  void render(const FrameInput& input);

  struct PassTiming {
    std::string pass;
    std::string type;
    double gpu_ms = 0.0;  // 0 when the device has no timestamps
    double cpu_ms = 0.0;  // time spent recording in execute()
    std::string skipped;  // the pass's skip_reason(), empty when it ran
  };
  const std::vector<PassTiming>& timings() const { return timings_; }
  // GPU time of the whole last frame, from before its first barrier to after its last (0 when
  // the device has no timestamps). Minus the passes' own times it is what the frame spent
  // between passes: barriers, layout transitions and the timestamps themselves.
  double frame_gpu_ms() const { return frame_gpu_ms_; }
  // The graph's barriers the last render() recorded (the first frame's initialisation aside).
  const FrameBarriers& frame_barriers() const { return frame_barriers_; }

  // RGBA32F texels of an output after render(), converted from its format.
  std::vector<float> read_output(const std::string& output, uint32_t& width, uint32_t& height);

  // "pass.param" at run time, checked against the pass type (throws GraphError naming the
  // key). Returns true when applied live; false when the pass's setup() was re-run. Throws
  // ParamNeedsRecompile for a parameter that sizes the pass's outputs.
  bool set_param(const std::string& key, const std::string& value);

  // nullptr when the resource does not exist or no live pass uses it.
  gpu::Image* image(const std::string& resource);
  gpu::Buffer* buffer(const std::string& resource);
  const CompiledGraph& compiled() const { return graph_; }
  uint64_t frame_index() const { return frame_.index; }

 private:
  struct Physical {
    std::unique_ptr<gpu::Image> image;
    std::unique_ptr<gpu::Buffer> buffer;
    bool fresh = true;                        // created by this build: initialise first
    std::vector<VkImageLayout> kept_layouts;  // per mip, for a kept persistent image
  };
  struct LivePass {
    std::unique_ptr<Pass> pass;
    std::unique_ptr<PassContextImpl> impl;
  };

  void release();
  // Memory for each of the graph's memory blocks, bound to the allocations taking turns in it.
  void bind_memory_blocks();
  void record_initialisation(VkCommandBuffer cmd);
  void record_history_copies(VkCommandBuffer cmd);
  void record_barriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers);
  void fill_frame(const FrameInput& input);
  void run_setup(LivePass& live);
  // Each pass's skip reason for this frame (empty: it runs), asked in schedule order.
  std::vector<std::string> skip_reasons();

  gpu::Context& context_;
  gpu::ShaderCompiler& shaders_;
  const Registry& registry_;
  CompiledGraph graph_;
  const scene::Scene* scene_ = nullptr;
  scene::GpuScene* gpu_scene_ = nullptr;
  // Before physical_: aliased images and buffers are destroyed before the memory they use.
  std::vector<std::unique_ptr<gpu::SharedMemory>> shared_memory_;
  std::vector<Physical> physical_;
  std::vector<LivePass> passes_;
  // Write counts per graph resource (index as in graph_.resources); by name across rebuilds.
  std::vector<uint64_t> resource_versions_;
  std::map<std::string, uint64_t> versions_by_name_;
  std::unique_ptr<FrameSync> sync_;
  FrameBarriers frame_barriers_;
  std::unique_ptr<gpu::Buffer> uniforms_;
  std::unique_ptr<gpu::TimestampQueries> timestamps_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  FrameInfo frame_;
  bool first_frame_ = true;
  bool rendered_ = false;
  std::vector<PassTiming> timings_;
  double frame_gpu_ms_ = 0.0;
  glm::vec3 scene_min_{0.0f}, scene_max_{0.0f};
  float light_count_ = 0.0f;
};

}  // namespace voxgi::graph
