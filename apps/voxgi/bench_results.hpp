#pragma once
// What `voxgi bench` measured: one record per configuration, written as results.json (the
// complete record, read back by `voxgi bench merge`) and results.csv (one flat row each).

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "engine/graph/executor.hpp"
#include "engine/image/metrics.hpp"
#include "engine/runtime/output_files.hpp"

namespace voxgi::cli {

// Distribution of a time over the measured frames.
struct Spread {
  double median = 0.0, min = 0.0, max = 0.0, p10 = 0.0, p90 = 0.0;
};
// Percentiles by linear interpolation between the sorted values; all 0 when empty.
Spread spread_of(std::vector<double> values);

struct PassTime {
  std::string pass, type;
  Spread gpu_ms;          // over the frames it ran
  double share_ms = 0.0;  // median over all measured frames, skipped ones counting 0
  uint32_t frames = 0;    // measured frames it ran
  uint32_t skipped = 0;   // measured frames it skipped
  std::string skip_reason;
};

struct FrameTimes {
  std::vector<PassTime> passes;  // in execution order
  Spread gpu_total_ms;           // per frame: sum over passes (skipped ones count 0)
  Spread cpu_total_ms;           // recording time per frame
};

// `frames` are the executor's timings of each measured frame (the warm-up left out).
FrameTimes summarize_frames(const std::vector<std::vector<graph::Executor::PassTiming>>& frames);

// The technique's `indirect` against the path tracer limited to the bounces and BRDF terms the
// graph declares (bench_same_bounce.hpp).
struct SameBounceResult {
  uint32_t bounces = 0;
  std::string brdf;            // "diffuse" or "full"
  std::string faces = "both";  // of single-sided materials: "front" or "both" (indirect.faces)
  std::map<std::string, std::string> reference_set;  // the reference graph's overrides
  std::string reference_key;
  bool reference_cache_hit = false;
  // Approximation error: the technique against what it models.
  std::optional<image::ImageMetrics> indirect;
  // The part of indirect->rel_mse that is the same-bounce reference's own noise (expected, from
  // its per-pixel variance; image::noise_rel_mse): the technique's error against the
  // converged reference is the difference. Absent where the reference has no variance.
  std::optional<double> reference_noise_rel_mse;
  // What a user sees: the technique against the full reference's indirect light, split as the
  // technique splits it (the bench's reference with deferred_layers, or its image).
  std::optional<image::ImageMetrics> full_indirect;
  std::string full_reference_key;
  // (full − same-bounce) / full mean luminance of the two references' `indirect`: what the
  // technique leaves out by design (further bounces, BRDF terms it does not model).
  std::optional<double> missing_fraction;
};

struct ConfigResult {
  size_t index = 0;
  std::string id;
  std::string label;      // technique plus the swept values
  std::string technique;  // the graph entry's label
  std::string graph;      // as written in the bench file
  std::string scene;      // as written
  std::string camera;
  uint32_t width = 0, height = 0;
  std::map<std::string, std::string> overrides;
  std::map<std::string, std::string> swept;
  uint32_t warmup_frames = 0, frames = 0;
  FrameTimes times;
  std::optional<image::ImageMetrics> full;      // linear against the reference's linear
  std::optional<image::ImageMetrics> indirect;  // when both graphs have an `indirect` output
  std::string reference_key;
  bool reference_cache_hit = false;
  // Like with like, for graphs that declare their indirect light ("indirect" in the graph file).
  std::optional<SameBounceResult> same_bounce;
  // Relative to the output folder.
  std::string image_png, reference_png, heat_map_png;
  double wall_seconds = 0.0;
  // Device memory of the graph's resources (compiled plan, transients shared), and without
  // any sharing; 0 in results written before it was recorded.
  uint64_t gpu_memory_bytes = 0;
  uint64_t gpu_memory_unshared_bytes = 0;
};

struct BenchResults {
  std::string name;
  std::string bench_file;
  std::string bench_hash;
  std::string device;
  std::string reference_graph;
  uint32_t reference_frames = 0;
  std::string changes = "none";       // BenchSpec::changes of the measured frames
  size_t configurations_total = 0;    // in the whole bench, every shard together
  std::vector<std::string> shards;    // "2/4" per shard merged in; empty for an unsharded run
  std::vector<ConfigResult> results;  // by index

  // Indices in [0, configurations_total) with no result.
  std::vector<size_t> missing() const;
};

nlohmann::json to_json(const BenchResults& results);
// Throws std::runtime_error naming `file` and the field when the JSON is not a results file.
BenchResults results_from_json(const nlohmann::json& doc, const std::string& file);
BenchResults read_results(const std::filesystem::path& results_json);
std::string results_csv(const BenchResults& results);

// Writes DIR/results.json and DIR/results.csv atomically.
void write_results(const std::filesystem::path& dir, const BenchResults& results);

using runtime::write_file_atomically;

}  // namespace voxgi::cli
