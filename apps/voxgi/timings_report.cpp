#include "apps/voxgi/timings_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "engine/runtime/output_files.hpp"
#include "engine/runtime/timings.hpp"

namespace voxgi::cli {

using runtime::median;

void TimingsReport::add_frame(const std::vector<graph::Executor::PassTiming>& frame,
                              size_t barriers, double frame_gpu_ms) {
  barriers_per_frame_.push_back(barriers);
  if (frames_seen_ == 0) first_frame_ = frame;
  if (frames_seen_++ < warmup_frames_) return;
  frames_.push_back(frame);
  if (frame_gpu_ms > 0.0) {
    double passes = 0.0;
    for (const graph::Executor::PassTiming& t : frame) passes += t.gpu_ms;
    frame_gpu_ms_.push_back(frame_gpu_ms);
    between_passes_gpu_ms_.push_back(std::max(0.0, frame_gpu_ms - passes));
  }
}

std::vector<TimingsReport::PassSummary> TimingsReport::summary() const {
  std::vector<PassSummary> result;
  std::map<std::string, size_t> index;
  std::vector<std::vector<double>> gpu, cpu;
  for (const auto& frame : frames_) {
    for (const graph::Executor::PassTiming& t : frame) {
      auto [it, inserted] = index.try_emplace(t.pass, result.size());
      if (inserted) {
        result.push_back({t.pass, t.type});
        gpu.emplace_back();
        cpu.emplace_back();
      }
      PassSummary& s = result[it->second];
      if (!t.skipped.empty()) {
        ++s.skipped;
        s.skip_reason = t.skipped;
        continue;
      }
      ++s.frames;
      gpu[it->second].push_back(t.gpu_ms);
      cpu[it->second].push_back(t.cpu_ms);
    }
  }
  for (size_t i = 0; i < result.size(); ++i) {
    result[i].gpu_ms_median = median(gpu[i]);
    result[i].cpu_ms_median = median(cpu[i]);
    if (!gpu[i].empty()) {
      result[i].gpu_ms_min = *std::min_element(gpu[i].begin(), gpu[i].end());
      result[i].gpu_ms_max = *std::max_element(gpu[i].begin(), gpu[i].end());
    }
  }
  return result;
}

void TimingsReport::write_json(const std::filesystem::path& path, const std::string& device,
                               const std::string& scene, const std::string& graph, uint32_t width,
                               uint32_t height) const {
  nlohmann::json doc;
  doc["device"] = device;
  doc["scene"] = scene;
  doc["graph"] = graph;
  doc["width"] = width;
  doc["height"] = height;
  doc["warmup_frames"] = warmup_frames_;
  doc["measured_frames"] = frames_.size();
  doc["statistic"] = "median over measured frames; a skipped pass counts 0 ms in the total";
  double total_gpu = 0.0, total_cpu = 0.0;
  nlohmann::json passes = nlohmann::json::array();
  for (const PassSummary& s : summary()) {
    passes.push_back({{"pass", s.pass},
                      {"type", s.type},
                      {"gpu_ms", s.gpu_ms_median},
                      {"gpu_ms_min", s.gpu_ms_min},
                      {"gpu_ms_max", s.gpu_ms_max},
                      {"cpu_ms", s.cpu_ms_median},
                      {"frames", s.frames},
                      {"skipped_frames", s.skipped},
                      {"skip_reason", s.skip_reason}});
    total_gpu += s.gpu_ms_median;
    total_cpu += s.cpu_ms_median;
  }
  doc["passes"] = passes;
  // One-off work (static voxelization, pipeline compilation) shows only in the first frame.
  nlohmann::json first = nlohmann::json::array();
  for (const graph::Executor::PassTiming& t : first_frame_) {
    first.push_back({{"pass", t.pass}, {"gpu_ms", t.gpu_ms}, {"skip_reason", t.skipped}});
  }
  doc["first_frame"] = first;
  // Frames in which passes skip record fewer barriers: none for what they would have written.
  doc["barriers_per_frame"] = barriers_per_frame_;
  doc["total_gpu_ms"] = total_gpu;
  doc["total_cpu_ms"] = total_cpu;
  // The whole frame by its own timestamps, and what it spent between passes (barriers and
  // layout transitions), medians over the measured frames.
  doc["frame_gpu_ms"] = median(frame_gpu_ms_);
  doc["between_passes_gpu_ms"] = median(between_passes_gpu_ms_);

  runtime::write_file_atomically(path, doc.dump(2) + "\n");
}

std::string TimingsReport::table() const {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-18s %-28s %10s %10s  %s\n", "pass", "type", "gpu ms",
                "cpu ms", "note");
  out << line;
  for (const PassSummary& s : summary()) {
    std::string note =
        s.skipped ? "skipped " + std::to_string(s.skipped) + "x: " + s.skip_reason : "";
    std::snprintf(line, sizeof line, "%-18s %-28s %10.3f %10.3f  %s\n", s.pass.c_str(),
                  s.type.c_str(), s.gpu_ms_median, s.cpu_ms_median, note.c_str());
    out << line;
  }
  return out.str();
}

}  // namespace voxgi::cli
