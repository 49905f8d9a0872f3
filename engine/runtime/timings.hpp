#pragma once
// Per-pass GPU and CPU times over a window of recent frames: medians for tables and files,
// totals per frame for history plots.

#include <cstddef>
#include <deque>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/graph/executor.hpp"

namespace voxgi::runtime {

// The value at fraction `p` (0..1) of `sorted` (ascending, not empty), interpolating linearly
// between the two nearest ranks: p = 0.5 is the median, 0.1 the 10th percentile.
double percentile(const std::vector<double>& sorted, double p);
// The median of `values` (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

struct PassTimingSummary {
  std::string pass, type;
  double gpu_ms_median = 0.0;
  double cpu_ms_median = 0.0;
  uint32_t frames = 0;      // frames in the window where the pass ran
  uint32_t skipped = 0;     // frames in the window where it skipped
  std::string skip_reason;  // the latest one
};

class TimingsHistory {
 public:
  // Keeps the last `window` frames.
  explicit TimingsHistory(size_t window = 120) : window_(window) {}

  void add_frame(const std::vector<graph::Executor::PassTiming>& frame, double frame_ms);
  void clear();

  size_t frames() const { return frames_.size(); }
  // Per pass, in the order of the latest frame.
  std::vector<PassTimingSummary> summary() const;
  // Sum of the passes' GPU times per frame, oldest first.
  std::vector<float> gpu_totals_ms() const;
  // Wall time per frame as given to add_frame, oldest first.
  std::vector<float> frame_ms() const;

  // A fixed-width text table: pass, type, GPU ms, CPU ms, skipped.
  std::string table() const;
  // JSON object {"frames": n, "passes": [{pass, type, gpu_ms, cpu_ms, frames, skipped, ...}]}.
  std::string json(const std::map<std::string, std::string>& about = {}) const;
  // Writes json() atomically. Throws std::runtime_error naming the path.
  void write_json(const std::filesystem::path& path,
                  const std::map<std::string, std::string>& about = {}) const;

 private:
  struct Frame {
    std::vector<graph::Executor::PassTiming> passes;
    double frame_ms = 0.0;
  };
  size_t window_;
  std::deque<Frame> frames_;
};

}  // namespace voxgi::runtime
