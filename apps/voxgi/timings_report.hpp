#pragma once
// Per-pass GPU and CPU times over several frames, reduced to medians after a warm-up.

#include <filesystem>
#include <string>
#include <vector>

#include "engine/graph/executor.hpp"

namespace voxgi::cli {

class TimingsReport {
 public:
  explicit TimingsReport(uint32_t warmup_frames) : warmup_frames_(warmup_frames) {}

  // `barriers`: the graph barriers the frame recorded (graph::barrier_count); `frame_gpu_ms`:
  // the whole frame's GPU time (Executor::frame_gpu_ms).
  void add_frame(const std::vector<graph::Executor::PassTiming>& frame, size_t barriers,
                 double frame_gpu_ms = 0.0);

  struct PassSummary {
    std::string pass, type;
    double gpu_ms_median = 0, gpu_ms_min = 0, gpu_ms_max = 0;
    double cpu_ms_median = 0;
    uint32_t frames = 0;   // measured (not skipped) frames after warm-up
    uint32_t skipped = 0;  // frames after warm-up the pass skipped
    std::string skip_reason;
  };
  std::vector<PassSummary> summary() const;

  // Writes JSON atomically (temp file + rename). Throws std::runtime_error naming the path.
  void write_json(const std::filesystem::path& path, const std::string& device,
                  const std::string& scene, const std::string& graph, uint32_t width,
                  uint32_t height) const;
  std::string table() const;

 private:
  uint32_t warmup_frames_;
  uint32_t frames_seen_ = 0;
  std::vector<std::vector<graph::Executor::PassTiming>> frames_;
  std::vector<graph::Executor::PassTiming> first_frame_;  // measured or not
  std::vector<size_t> barriers_per_frame_;                // every frame, warm-up included
  std::vector<double> frame_gpu_ms_;                      // measured frames
  std::vector<double> between_passes_gpu_ms_;             // frame minus its passes
};

}  // namespace voxgi::cli
