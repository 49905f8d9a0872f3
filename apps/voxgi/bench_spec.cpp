#include "apps/voxgi/bench_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

#include "apps/voxgi/bench_hash.hpp"
#include "apps/voxgi/cli_args.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/input_file.hpp"
#include "engine/graph/json.hpp"
#include "engine/scene/builtin_scenes.hpp"

namespace voxgi::cli {
namespace {

namespace fs = std::filesystem;
using graph::json::Value;

// Reads one bench file, collecting every problem instead of stopping at the first.
class BenchParser {
 public:
  BenchParser(fs::path file, fs::path repo_dir)
      : file_(std::move(file)), repo_dir_(std::move(repo_dir)) {}

  BenchSpec parse(const std::string& text) {
    BenchSpec spec;
    spec.file = file_;
    spec.content_hash = Hasher().add(text).hex();
    const Value root = graph::json::parse(text, file_.string());
    if (!root.is_object()) {
      error(root.loc(), "", "a bench file is a JSON object");
      diagnostics_.throw_if_any();
    }
    check_keys(root, "",
               {"name", "doc", "scenes", "resolution", "warmup_frames", "frames", "changes",
                "graphs", "reference"});
    spec.name = file_.stem().string();
    if (const Value* name = root.find("name")) spec.name = string_of(*name, "name");

    const Value* scenes = required(root, "scenes");
    if (scenes && expect_nonempty_array(*scenes, "scenes")) {
      for (size_t i = 0; i < scenes->items().size(); ++i) {
        parse_scene(scenes->items()[i], "scenes[" + std::to_string(i) + "]", spec);
      }
    }

    if (const Value* resolution = root.find("resolution")) {
      parse_resolutions(*resolution, spec);
    } else {
      spec.resolutions = {{1280, 720}};
    }
    if (const Value* warmup = root.find("warmup_frames")) {
      spec.warmup_frames = integer_of(*warmup, "warmup_frames", 0, 1000);
    }
    if (const Value* frames = root.find("frames")) {
      spec.frames = integer_of(*frames, "frames", 1, 100000);
    }
    if (const Value* changes = root.find("changes")) {
      const std::string written = string_of(*changes, "changes");
      if (written == "none" || written == "lights" || written == "geometry") {
        spec.changes = written;
      } else if (!written.empty()) {
        error(changes->loc(), "changes", "unknown value '" + written + "'",
              "one of \"none\", \"lights\", \"geometry\"");
      }
    }

    const Value* graphs = required(root, "graphs");
    if (graphs && expect_nonempty_array(*graphs, "graphs")) {
      std::set<std::string> labels;
      for (size_t i = 0; i < graphs->items().size(); ++i) {
        parse_graph(graphs->items()[i], "graphs[" + std::to_string(i) + "]", spec, labels);
      }
    }

    if (const Value* reference = required(root, "reference")) parse_reference(*reference, spec);
    if (graphs) check_configuration_count(*graphs, spec);
    diagnostics_.throw_if_any();
    return spec;
  }

  // Refuses, before anything runs, a bench whose sweeps multiply into more configurations
  // than any run could finish (a stray value list, a sweep pasted twice).
  void check_configuration_count(const Value& graphs, const BenchSpec& spec) {
    const auto saturating_product = [](uint64_t a, uint64_t b) {
      return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
    };
    uint64_t views = 0;
    for (const BenchScene& scene : spec.scenes) views += scene.cameras.size();
    views = saturating_product(views, spec.resolutions.size());
    uint64_t total = 0;
    for (const BenchGraph& entry : spec.graphs) {
      uint64_t per_view = 1;
      for (const BenchSweep& sweep : entry.sweeps) {
        per_view = saturating_product(per_view, sweep.values.size());
      }
      const uint64_t count = saturating_product(per_view, views);
      total = total > UINT64_MAX - count ? UINT64_MAX : total + count;
    }
    if (total > kMaxBenchConfigurations) {
      error(graphs.loc(), "graphs",
            "the scenes, cameras, resolutions and sweeps make " +
                (total == UINT64_MAX ? std::string("more than 2^64") : std::to_string(total)) +
                " configurations, more than " + std::to_string(kMaxBenchConfigurations) +
                " in one bench; shorten the sweeps or split the bench file");
    }
  }

 private:
  void error(const graph::SourceLoc& loc, const std::string& field, const std::string& message,
             const std::string& hint = {}) {
    diagnostics_.error(loc, "", field, message, hint);
  }

  const Value* required(const Value& object, const std::string& key) {
    const Value* value = object.find(key);
    if (!value) error(object.loc(), key, "missing (required)");
    return value;
  }

  void check_keys(const Value& object, const std::string& where,
                  const std::vector<std::string>& known) {
    for (const graph::json::Member& member : object.members()) {
      if (std::find(known.begin(), known.end(), member.key) != known.end()) continue;
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      error(member.key_loc, where.empty() ? member.key : where + "." + member.key,
            "unknown field (expected one of: " + list + ")",
            graph::did_you_mean(member.key, known));
    }
  }

  bool expect_nonempty_array(const Value& value, const std::string& field) {
    if (!value.is_array()) {
      error(value.loc(), field,
            std::string("expected an array, found ") + graph::json::kind_name(value.kind()));
      return false;
    }
    if (value.items().empty()) {
      error(value.loc(), field, "must not be empty");
      return false;
    }
    return true;
  }

  std::string string_of(const Value& value, const std::string& field) {
    if (value.is_string() && !value.as_string().empty()) return value.as_string();
    error(value.loc(), field,
          std::string("expected a non-empty string, found ") +
              (value.is_string() ? "an empty string" : graph::json::kind_name(value.kind())));
    return {};
  }

  uint32_t integer_of(const Value& value, const std::string& field, uint32_t min, uint32_t max) {
    if (value.is_number()) {
      const double n = value.as_number();
      if (n == std::floor(n) && n >= min && n <= max) return static_cast<uint32_t>(n);
    }
    std::string found = value.is_number() ? "" : graph::json::kind_name(value.kind());
    if (value.is_number()) {
      char number[64];
      std::snprintf(number, sizeof number, "%g", value.as_number());
      found = number;
    }
    error(value.loc(), field,
          "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
              "], found " + found);
    return min;
  }

  // A parameter value as `--set` takes it: numbers without trailing zeros, bools as true/false.
  std::string setting_of(const Value& value, const std::string& field) {
    if (value.is_string()) return value.as_string();
    if (value.is_bool()) return value.as_bool() ? "true" : "false";
    if (value.is_number()) {
      const double n = value.as_number();
      char text[64];
      if (n == std::floor(n) && std::fabs(n) < 1e15) {
        std::snprintf(text, sizeof text, "%.0f", n);
      } else {
        std::snprintf(text, sizeof text, "%.9g", n);
      }
      return text;
    }
    error(value.loc(), field,
          std::string("expected a number, bool or string, found ") +
              graph::json::kind_name(value.kind()));
    return {};
  }

  // Relative to the bench file's folder first, then to the source tree. The error_code forms:
  // a name the system cannot look up (too long, say) is a file that is not there.
  fs::path resolve(const std::string& written) const {
    const fs::path path(written);
    if (path.is_absolute()) return path;
    std::error_code ec;
    const fs::path beside = file_.parent_path() / path;
    if (fs::exists(beside, ec)) return beside.lexically_normal();
    const fs::path in_repo = repo_dir_ / path;
    if (fs::exists(in_repo, ec)) return in_repo.lexically_normal();
    return beside.lexically_normal();
  }

  std::string existing_file(const Value& value, const std::string& field) {
    const std::string written = string_of(value, field);
    if (written.empty()) return {};
    const fs::path path = resolve(written);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      error(
          value.loc(), field,
          "file '" + written + "' not found (looked beside the bench file and in the source tree)");
      return {};
    }
    return path.string();
  }

  void parse_scene(const Value& value, const std::string& field, BenchSpec& spec) {
    BenchScene scene;
    scene.loc = value.loc();
    const Value* source = &value;
    if (value.is_object()) {
      check_keys(value, field, {"scene", "cameras"});
      source = required(value, "scene");
      if (const Value* cameras = value.find("cameras")) {
        if (expect_nonempty_array(*cameras, field + ".cameras")) {
          for (size_t i = 0; i < cameras->items().size(); ++i) {
            scene.cameras.push_back(
                string_of(cameras->items()[i], field + ".cameras[" + std::to_string(i) + "]"));
          }
        }
      }
    } else if (!value.is_string()) {
      error(value.loc(), field,
            std::string("expected a scene name or path, or an object {\"scene\", \"cameras\"}, "
                        "found ") +
                graph::json::kind_name(value.kind()));
      return;
    }
    if (!source) return;
    const std::string source_field = value.is_object() ? field + ".scene" : field;
    scene.label = string_of(*source, source_field);
    if (scene.label.empty()) return;
    const std::string ext = fs::path(scene.label).extension().string();
    if (ext == ".gltf" || ext == ".glb") {
      scene.source = existing_file(*source, source_field);
      scene.label = fs::path(scene.label).stem().string();  // short, for results and charts
    } else {
      const std::vector<std::string> names = scene::builtin_scene_names();
      if (std::find(names.begin(), names.end(), scene.label) == names.end()) {
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        error(source->loc(), source_field,
              "'" + scene.label + "' is neither a .gltf/.glb file nor a built-in scene (" + list +
                  ")",
              graph::did_you_mean(scene.label, names));
        return;
      }
      scene.source = scene.label;
    }
    if (scene.cameras.empty()) scene.cameras = {"default"};
    for (const BenchScene& earlier : spec.scenes) {
      if (earlier.source == scene.source) {
        error(value.loc(), field,
              "scene '" + scene.label + "' is listed twice (first at line " +
                  std::to_string(earlier.loc.line) +
                  "); list it once, with every camera in its \"cameras\"");
        return;
      }
    }
    std::set<std::string> cameras;
    for (const std::string& camera : scene.cameras) {
      if (!cameras.insert(camera).second) {
        error(value.loc(), field + ".cameras", "camera '" + camera + "' is listed twice");
        return;
      }
    }
    spec.scenes.push_back(std::move(scene));
  }

  std::pair<uint32_t, uint32_t> resolution_of(const Value& value, const std::string& field) {
    if (!value.is_array() || value.items().size() != 2) {
      error(value.loc(), field, "expected [width, height]");
      return {1, 1};
    }
    return {integer_of(value.items()[0], field + "[0]", 1, 16384),
            integer_of(value.items()[1], field + "[1]", 1, 16384)};
  }

  // [w, h] or a list of them.
  void parse_resolutions(const Value& value, BenchSpec& spec) {
    if (value.is_array() && !value.items().empty() && value.items()[0].is_array()) {
      for (size_t i = 0; i < value.items().size(); ++i) {
        spec.resolutions.push_back(
            resolution_of(value.items()[i], "resolution[" + std::to_string(i) + "]"));
      }
    } else {
      spec.resolutions.push_back(resolution_of(value, "resolution"));
    }
  }

  std::map<std::string, std::string> settings_of(const Value& value, const std::string& field) {
    std::map<std::string, std::string> result;
    if (!value.is_object()) {
      error(value.loc(), field,
            std::string("expected an object {\"pass.param\": value}, found ") +
                graph::json::kind_name(value.kind()));
      return result;
    }
    for (const graph::json::Member& member : value.members()) {
      result[member.key] = setting_of(member.value, field + "." + member.key);
    }
    return result;
  }

  void parse_graph(const Value& value, const std::string& field, BenchSpec& spec,
                   std::set<std::string>& labels) {
    BenchGraph entry;
    entry.loc = value.loc();
    const Value* file = &value;
    std::string file_field = field;
    if (value.is_object()) {
      check_keys(value, field, {"graph", "label", "set", "sweep"});
      file = required(value, "graph");
      file_field = field + ".graph";
      if (const Value* set = value.find("set")) entry.set = settings_of(*set, field + ".set");
      if (const Value* sweep = value.find("sweep")) {
        if (!sweep->is_object()) {
          error(sweep->loc(), field + ".sweep",
                std::string("expected an object {\"pass.param\": [values]}, found ") +
                    graph::json::kind_name(sweep->kind()));
        } else {
          for (const graph::json::Member& member : sweep->members()) {
            const std::string sweep_field = field + ".sweep." + member.key;
            BenchSweep s;
            s.key = member.key;
            s.loc = member.key_loc;
            if (expect_nonempty_array(member.value, sweep_field)) {
              for (size_t i = 0; i < member.value.items().size(); ++i) {
                s.values.push_back(setting_of(member.value.items()[i],
                                              sweep_field + "[" + std::to_string(i) + "]"));
              }
            }
            if (entry.set.count(s.key)) {
              error(member.key_loc, sweep_field, "is both set and swept; keep one");
            }
            entry.sweeps.push_back(std::move(s));
          }
        }
      }
    } else if (!value.is_string()) {
      error(value.loc(), field,
            std::string("expected a graph path, or an object {\"graph\", \"label\", \"set\", "
                        "\"sweep\"}, found ") +
                graph::json::kind_name(value.kind()));
      return;
    }
    if (!file) return;
    entry.file_as_written = string_of(*file, file_field);
    if (entry.file_as_written.empty()) return;
    entry.file = existing_file(*file, file_field);
    entry.label = fs::path(entry.file_as_written).stem().string();
    if (value.is_object()) {
      if (const Value* label = value.find("label"))
        entry.label = string_of(*label, field + ".label");
    }
    if (!labels.insert(entry.label).second) {
      error(value.loc(), value.is_object() && value.find("label") ? field + ".label" : field,
            "label '" + entry.label + "' is used twice; give each graph entry its own \"label\"");
    }
    spec.graphs.push_back(std::move(entry));
  }

  void parse_reference(const Value& value, BenchSpec& spec) {
    BenchReference& ref = spec.reference;
    ref.loc = value.loc();
    if (!value.is_object()) {
      error(value.loc(), "reference",
            std::string("expected an object {\"graph\", \"frames\", \"set\"} or {\"image\", "
                        "\"indirect\"}, found ") +
                graph::json::kind_name(value.kind()));
      return;
    }
    check_keys(value, "reference", {"graph", "frames", "set", "image", "indirect"});
    const Value* image = value.find("image");
    if (image) parse_reference_image(*image, "reference.image", ref.image);
    if (const Value* indirect = value.find("indirect")) {
      parse_reference_image(*indirect, "reference.indirect", ref.indirect);
      if (!image) {
        error(indirect->loc(), "reference.indirect",
              "an indirect image needs the full one beside it in \"image\"");
      }
    }
    if (const Value* file = value.find("graph")) {
      ref.file_as_written = string_of(*file, "reference.graph");
      if (!ref.file_as_written.empty()) ref.file = existing_file(*file, "reference.graph");
    } else if (!image) {
      error(value.loc(), "reference.graph",
            "missing (required unless the reference is an image file: \"image\")");
    }
    if (const Value* frames = value.find("frames")) {
      ref.frames = integer_of(*frames, "reference.frames", 1, 1000000);
    } else if (value.find("graph")) {
      error(value.loc(), "reference.frames", "missing (required)");
    }
    if (const Value* set = value.find("set")) ref.set = settings_of(*set, "reference.set");
    if (image) {
      size_t views = 0;
      for (const BenchScene& scene : spec.scenes) views += scene.cameras.size();
      if (views > 1 || spec.resolutions.size() > 1) {
        error(image->loc(), "reference.image",
              "an image reference shows one scene, camera and resolution, but the bench has " +
                  std::to_string(views) + " views and " + std::to_string(spec.resolutions.size()) +
                  " resolutions");
      }
    }
  }

  // A linear OpenEXR image beside the bench file (or in the source tree).
  void parse_reference_image(const Value& value, const std::string& field,
                             BenchReferenceImage& image) {
    image.loc = value.loc();
    image.file_as_written = string_of(value, field);
    if (image.file_as_written.empty()) return;
    if (fs::path(image.file_as_written).extension() != ".exr") {
      error(value.loc(), field,
            "'" + image.file_as_written +
                "': expected a linear OpenEXR image (.exr), the same resolution as the bench");
      return;
    }
    image.file = existing_file(value, field);
  }

  fs::path file_;
  fs::path repo_dir_;
  graph::DiagnosticList diagnostics_;
};

}  // namespace

std::string BenchConfiguration::label(const BenchSpec& spec) const {
  std::string text = spec.graphs[graph].label;
  for (const auto& [key, value] : swept) {
    // A sweep over variants may include the file as written ("").
    text += " " + key + "=" + (key == graph::kVariantKey && value.empty() ? "none" : value);
  }
  return text;
}

BenchSpec parse_bench(const std::string& text, const std::filesystem::path& path,
                      const std::filesystem::path& repo_dir) {
  return BenchParser(path, repo_dir).parse(text);
}

BenchSpec load_bench_file(const std::filesystem::path& path,
                          const std::filesystem::path& repo_dir) {
  const std::string text = graph::read_input_file(path, "bench file");
  return parse_bench(text, path, repo_dir);
}

std::vector<BenchConfiguration> expand_configurations(const BenchSpec& spec) {
  std::vector<BenchConfiguration> result;
  for (size_t s = 0; s < spec.scenes.size(); ++s) {
    for (const std::string& camera : spec.scenes[s].cameras) {
      for (const auto& [width, height] : spec.resolutions) {
        for (size_t g = 0; g < spec.graphs.size(); ++g) {
          const BenchGraph& entry = spec.graphs[g];
          // Odometer over the sweeps: the last sweep varies fastest.
          std::vector<size_t> digit(entry.sweeps.size(), 0);
          while (true) {
            BenchConfiguration config;
            config.index = result.size();
            char id[32];
            std::snprintf(id, sizeof id, "c%03zu", config.index);
            config.id = id;
            config.scene = s;
            config.camera = camera;
            config.width = width;
            config.height = height;
            config.graph = g;
            config.overrides = entry.set;
            for (size_t k = 0; k < entry.sweeps.size(); ++k) {
              config.overrides[entry.sweeps[k].key] = entry.sweeps[k].values[digit[k]];
              config.swept[entry.sweeps[k].key] = entry.sweeps[k].values[digit[k]];
            }
            result.push_back(std::move(config));
            bool wrapped = true;
            for (size_t k = entry.sweeps.size(); k-- > 0;) {
              if (++digit[k] < entry.sweeps[k].values.size()) {
                wrapped = false;
                break;
              }
              digit[k] = 0;
            }
            if (wrapped) break;
          }
        }
      }
    }
  }
  return result;
}

Shard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  Shard shard;
  auto number = [](std::string_view part, uint32_t& out) {
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    return ec == std::errc() && ptr == part.data() + part.size();
  };
  if (slash == std::string::npos || !number(std::string_view(text).substr(0, slash), shard.index) ||
      !number(std::string_view(text).substr(slash + 1), shard.count) || shard.count == 0 ||
      shard.index == 0 || shard.index > shard.count) {
    throw UsageError("--shard '" + text + "': expected i/n with 1 <= i <= n, e.g. --shard 2/4");
  }
  return shard;
}

std::vector<BenchConfiguration> select_shard(const std::vector<BenchConfiguration>& all,
                                             const Shard& shard) {
  std::vector<BenchConfiguration> result;
  for (const BenchConfiguration& config : all) {
    if (config.index % shard.count == shard.index - 1) result.push_back(config);
  }
  return result;
}

}  // namespace voxgi::cli
