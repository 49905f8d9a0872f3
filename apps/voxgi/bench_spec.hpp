#pragma once
// Bench files: which scenes, cameras, resolutions, graphs and parameter sweeps `voxgi bench`
// measures, and the reference every image is compared with. A bench file is JSON with
// comments; every mistake is reported as "file:line:col: error: field 'f': ..." (GraphError).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::cli {

struct BenchScene {
  std::string label;                 // built-in name, or the file's stem
  std::string source;                // a built-in name or a resolved .gltf/.glb path
  std::vector<std::string> cameras;  // glTF camera names; "default": the scene's first camera
  graph::SourceLoc loc;
};

// One parameter swept over values; the sweeps of a graph entry form a cartesian product.
struct BenchSweep {
  std::string key;  // as for --set: "pass.param" or a graph parameter
  std::vector<std::string> values;
  graph::SourceLoc loc;
};

struct BenchGraph {
  std::string label;                       // the technique's name in results and charts
  std::filesystem::path file;              // resolved
  std::string file_as_written;             // for messages and results
  std::map<std::string, std::string> set;  // fixed overrides
  std::vector<BenchSweep> sweeps;
  graph::SourceLoc loc;
};

// A reference image given as a file (rendered by any offline renderer), relative to the bench
// file: "reference": {"image": "x.exr", "indirect": "y.exr"}.
struct BenchReferenceImage {
  std::filesystem::path file;  // resolved; empty when not given
  std::string file_as_written;
  graph::SourceLoc loc;
};

// The reference: rendered by a path tracer graph, or read from image files. With both, the
// images are the reference and the graph renders only the same-bounce references.
struct BenchReference {
  std::filesystem::path file;  // resolved graph file; empty for an image-only reference
  std::string file_as_written;
  uint32_t frames = 1;  // progressive: samples = frames × the graph's samples per frame
  std::map<std::string, std::string> set;
  graph::SourceLoc loc;
  BenchReferenceImage image;     // "image": the full linear image
  BenchReferenceImage indirect;  // "indirect": its indirect light (optional, with "image")

  bool has_graph() const { return !file_as_written.empty(); }
  bool is_image() const { return !image.file_as_written.empty(); }
};

struct BenchSpec {
  std::filesystem::path file;
  std::string name;
  std::string content_hash;  // of the bench file's bytes: shards of one bench share it
  std::vector<BenchScene> scenes;
  std::vector<std::pair<uint32_t, uint32_t>> resolutions;
  uint32_t warmup_frames = 2;
  uint32_t frames = 8;  // measured frames after the warm-up
  // What changes in every measured frame: "none" (a static view: change-driven passes skip),
  // "lights" (passes that depend on the lights run again, as when a light moves) or "geometry"
  // (everything that depends on the scene runs again).
  std::string changes = "none";
  std::vector<BenchGraph> graphs;
  BenchReference reference;
};

// One measured run: a scene, camera and resolution through a graph with its overrides.
struct BenchConfiguration {
  size_t index = 0;  // position in the full expansion (shards keep it)
  std::string id;    // "c007"
  size_t scene = 0;  // index into BenchSpec::scenes
  std::string camera;
  uint32_t width = 0;
  uint32_t height = 0;
  size_t graph = 0;                              // index into BenchSpec::graphs
  std::map<std::string, std::string> overrides;  // fixed `set` plus this point of the sweeps
  std::map<std::string, std::string> swept;      // only the swept keys, for labels

  // "vct voxel.resolution=64 vct.cones=4"
  std::string label(const BenchSpec& spec) const;
};

// Paths in a bench file are tried relative to the bench file's folder, then to `repo_dir`.
// Throws GraphError (every problem found, each with file:line:col and the field).
BenchSpec load_bench_file(const std::filesystem::path& path, const std::filesystem::path& repo_dir);
BenchSpec parse_bench(const std::string& text, const std::filesystem::path& path,
                      const std::filesystem::path& repo_dir);

// The most configurations one bench file may expand to; larger ones are refused when parsed.
inline constexpr uint64_t kMaxBenchConfigurations = 10000;

// Scenes × cameras × resolutions × graphs × the product of each graph's sweeps, in that order.
std::vector<BenchConfiguration> expand_configurations(const BenchSpec& spec);

// "--shard i/n" (1 ≤ i ≤ n): configuration k belongs to shard (k mod n) + 1.
struct Shard {
  uint32_t index = 1;
  uint32_t count = 1;
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
Shard parse_shard(const std::string& text);  // throws UsageError naming --shard
std::vector<BenchConfiguration> select_shard(const std::vector<BenchConfiguration>& all,
                                             const Shard& shard);

}  // namespace voxgi::cli
