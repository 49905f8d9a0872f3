#include "engine/runtime/timings.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace voxgi::runtime {

double percentile(const std::vector<double>& sorted, double p) {
  const double at = p * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(at));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  const double f = at - static_cast<double>(below);
  if (f == 0.0) return sorted[below];
  return sorted[below] * (1.0 - f) + sorted[above] * f;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return percentile(values, 0.5);
}

void TimingsHistory::add_frame(const std::vector<graph::Executor::PassTiming>& frame,
                               double frame_ms) {
  frames_.push_back({frame, frame_ms});
  while (frames_.size() > window_) frames_.pop_front();
}

void TimingsHistory::clear() {
  frames_.clear();
}

std::vector<PassTimingSummary> TimingsHistory::summary() const {
  std::vector<PassTimingSummary> result;
  if (frames_.empty()) return result;
  for (const graph::Executor::PassTiming& latest : frames_.back().passes) {
    PassTimingSummary s;
    s.pass = latest.pass;
    s.type = latest.type;
    std::vector<double> gpu, cpu;
    for (const Frame& frame : frames_) {
      for (const graph::Executor::PassTiming& t : frame.passes) {
        if (t.pass != latest.pass) continue;
        if (!t.skipped.empty()) {
          ++s.skipped;
          s.skip_reason = t.skipped;
        } else {
          gpu.push_back(t.gpu_ms);
          cpu.push_back(t.cpu_ms);
          ++s.frames;
        }
      }
    }
    s.gpu_ms_median = median(gpu);
    s.cpu_ms_median = median(cpu);
    result.push_back(std::move(s));
  }
  return result;
}

std::vector<float> TimingsHistory::gpu_totals_ms() const {
  std::vector<float> totals;
  for (const Frame& frame : frames_) {
    double sum = 0.0;
    for (const auto& t : frame.passes) sum += t.gpu_ms;
    totals.push_back(static_cast<float>(sum));
  }
  return totals;
}

std::vector<float> TimingsHistory::frame_ms() const {
  std::vector<float> values;
  for (const Frame& frame : frames_) values.push_back(static_cast<float>(frame.frame_ms));
  return values;
}

std::string TimingsHistory::table() const {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-20s %-28s %9s %9s %8s\n", "pass", "type", "GPU ms", "CPU ms",
                "skipped");
  out << line;
  double gpu_total = 0.0, cpu_total = 0.0;
  for (const PassTimingSummary& s : summary()) {
    std::snprintf(line, sizeof line, "%-20s %-28s %9.3f %9.3f %8u\n", s.pass.c_str(),
                  s.type.c_str(), s.gpu_ms_median, s.cpu_ms_median, s.skipped);
    out << line;
    gpu_total += s.gpu_ms_median;
    cpu_total += s.cpu_ms_median;
  }
  std::snprintf(line, sizeof line, "%-20s %-28s %9.3f %9.3f\n", "total", "", gpu_total, cpu_total);
  out << line;
  return out.str();
}

std::string TimingsHistory::json(const std::map<std::string, std::string>& about) const {
  nlohmann::json root = nlohmann::json::object();
  for (const auto& [key, value] : about) root[key] = value;
  root["frames"] = frames_.size();
  nlohmann::json passes = nlohmann::json::array();
  for (const PassTimingSummary& s : summary()) {
    nlohmann::json p;
    p["pass"] = s.pass;
    p["type"] = s.type;
    p["gpu_ms"] = s.gpu_ms_median;
    p["cpu_ms"] = s.cpu_ms_median;
    p["frames"] = s.frames;
    p["skipped"] = s.skipped;
    if (!s.skip_reason.empty()) p["skip_reason"] = s.skip_reason;
    passes.push_back(p);
  }
  root["passes"] = passes;
  return root.dump(2) + "\n";
}

void TimingsHistory::write_json(const std::filesystem::path& path,
                                const std::map<std::string, std::string>& about) const {
  const std::filesystem::path temp = path.string() + ".tmp";
  {
    std::ofstream out(temp);
    if (!out) throw std::runtime_error(path.string() + ": cannot write the timings file");
    out << json(about);
    if (!out) throw std::runtime_error(path.string() + ": writing the timings file failed");
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) throw std::runtime_error(path.string() + ": " + ec.message());
}

}  // namespace voxgi::runtime
