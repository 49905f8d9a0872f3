// voxgi bench: measures graphs (GI techniques and their parameter sweeps) on scenes against a
// cached reference, and writes results.json, results.csv and a report. `bench merge`,
// `bench bvh` and `bench voxel-light` live in their own files.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <system_error>

#include <nlohmann/json.hpp>

#include "apps/voxgi/bench_progress.hpp"
#include "apps/voxgi/bench_reference.hpp"
#include "apps/voxgi/bench_results.hpp"
#include "apps/voxgi/bench_runner.hpp"
#include "apps/voxgi/bench_same_bounce.hpp"
#include "apps/voxgi/bench_spec.hpp"
#include "apps/voxgi/bench_subcommands.hpp"
#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/commands.hpp"
#include "apps/voxgi/report_markdown.hpp"
#include "engine/image/error_map.hpp"
#include "engine/image/metrics.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

}  // namespace

const char* const kBenchUsage =
    "usage: voxgi bench FILE.json [options]          measure the bench file's configurations\n"
    "       voxgi bench merge OUT_DIR SHARD_DIR...   join shard results into one report\n"
    "       voxgi bench bvh --scene S [--repeat N]   BVH build time and SAH cost of a scene\n"
    "       voxgi bench voxel-light --scene S        a voxel's injected light against its "
    "surfaces\n";

namespace {

Args bench_args() {
  return Args("voxgi bench",
              {{"out", true, false, "DIR", "output folder (default out/bench/<bench name>)"},
               {"shard", true, false, "i/n", "run only configurations k with k mod n = i - 1"},
               {"reference-cache", true, false, "DIR",
                "reference image cache (default $VOXGI_REFERENCE_CACHE or "
                "~/.cache/voxgi/references)"},
               {"check", false, false, "",
                "check the bench file and every configuration, list them, render nothing"},
               {"device", true, false, "INDEX|NAME", "Vulkan device"},
               {"validation", false, false, "",
                "enable the Vulkan validation layer; messages fail the run"},
               {"help", false, false, "", "show this help"}});
}

// A problem with one configuration, located at the bench file entry it comes from.
[[noreturn]] void fail_at(const graph::SourceLoc& loc, const std::string& field,
                          const std::string& message) {
  throw graph::GraphError(graph::Diagnostic{loc, "", field, message, ""});
}

std::string config_field(const BenchConfiguration& config) {
  return "graphs[" + std::to_string(config.graph) + "]";
}

void check_outputs(const graph::CompiledGraph& compiled, const std::string& file,
                   const graph::SourceLoc& loc, const std::string& field) {
  for (const char* name : {"display", "linear"}) {
    if (!compiled.outputs.count(name)) {
      fail_at(loc, field,
              "graph '" + file + "' has no '" + name +
                  "' output (every benchmarked graph has 'display', 'linear' and, for GI, "
                  "'indirect')");
    }
  }
}

struct ReferenceTarget {
  std::string key;
  std::string description;                 // JSON kept beside the cached images
  std::map<std::string, std::string> set;  // the reference graph's overrides
  std::string what;                        // "reference", "same-bounce reference (...)"
  bool image = false;                      // the bench's image-file reference
};

// The references one configuration is compared with.
struct ConfigReferences {
  ReferenceTarget full;
  std::optional<IndirectModel> model;  // what the graph declares its indirect light holds
  std::optional<ReferenceTarget> same_bounce;
  // The full reference with the technique's direct/indirect split (deferred_layers), or the
  // image reference: the bounces the technique leaves out are measured against it.
  std::optional<ReferenceTarget> full_like_split;
};

nlohmann::json reference_description(const BenchSpec& spec, const BenchScene& scene,
                                     const std::string& camera, uint32_t width, uint32_t height,
                                     const std::map<std::string, std::string>& set) {
  return {{"scene", scene.label},
          {"camera", camera},
          {"width", width},
          {"height", height},
          {"graph", spec.reference.file_as_written},
          {"frames", spec.reference.frames},
          {"set", set}};
}

// "max_depth=2 deferred_layers=true lambert=true": what a same-bounce reference changes.
std::string changed_settings(const std::map<std::string, std::string>& set,
                             const std::map<std::string, std::string>& base) {
  std::string text;
  for (const auto& [key, value] : set) {
    auto it = base.find(key);
    if (it != base.end() && it->second == value) continue;
    text += (text.empty() ? "" : " ") + key + "=" + value;
  }
  return text;
}

fs::path default_out_dir(const BenchSpec& spec) {
  return fs::path("out") / "bench" / spec.name;
}

std::string where_of(const BenchSpec& spec, const BenchConfiguration& config) {
  return spec.scenes[config.scene].label + " / " + config.camera + " / " +
         std::to_string(config.width) + "x" + std::to_string(config.height);
}

// One `voxgi bench FILE` run: checks every configuration, then measures them one by one.
class BenchRun {
 public:
  BenchRun(const BenchSpec& spec, ReferenceCache& cache, fs::path out_dir)
      : spec_(spec), cache_(cache), out_dir_(std::move(out_dir)) {}

  // Compiles every configuration and its reference for its scene before any device is opened,
  // so that a mistake in the bench file (an unknown parameter, a camera the scene lacks) costs
  // no rendering time; also computes the reference keys.
  void check(const std::vector<BenchConfiguration>& selected) {
    const fs::path shader_root = gpu::ShaderCompiler::default_shader_root();
    for (const BenchConfiguration& config : selected) {
      const BenchScene& bench_scene = spec_.scenes[config.scene];
      const BenchGraph& entry = spec_.graphs[config.graph];
      const std::string scene_field = "scenes[" + std::to_string(config.scene) + "]";
      scene::Scene* scene = nullptr;
      try {
        scene = &catalog_.scene(bench_scene.source);
      } catch (const std::exception& e) {
        fail_at(bench_scene.loc, scene_field, e.what());
      }
      scene::Camera camera;
      try {
        camera = camera_of(*scene, config);
      } catch (const std::exception& e) {
        fail_at(bench_scene.loc, scene_field + ".cameras", e.what());
      }
      std::optional<IndirectModel> model;
      try {
        const graph::GraphDesc& desc = catalog_.graph(entry.file);
        const graph::CompiledGraph compiled =
            catalog_.compile(desc, *scene, config.width, config.height, config.overrides);
        check_outputs(compiled, entry.file_as_written, entry.loc, config_field(config));
        model = indirect_model_of(desc, compiled.parameters, scene->features().as_map());
      } catch (const std::exception& e) {
        fail_at(entry.loc, config_field(config),
                "configuration " + config.id + " (" + config.label(spec_) + ") on '" +
                    bench_scene.label + "': " + e.what());
      }
      ConfigReferences& refs = references_of_[config.index];
      refs.model = model;
      if (spec_.reference.is_image()) {
        refs.full = image_reference_target(config);
      }
      if (model && spec_.reference.is_image()) refs.full_like_split = refs.full;
      if (!spec_.reference.has_graph()) continue;
      const graph::GraphDesc& reference_desc = catalog_.graph(spec_.reference.file);
      const auto target_for = [&](const std::map<std::string, std::string>& set,
                                  const std::string& what) {
        try {
          const graph::CompiledGraph compiled =
              catalog_.compile(reference_desc, *scene, config.width, config.height, set);
          check_outputs(compiled, spec_.reference.file_as_written, spec_.reference.loc,
                        "reference");
        } catch (const std::exception& e) {
          fail_at(spec_.reference.loc, "reference",
                  what + " on '" + bench_scene.label + "': " + std::string(e.what()));
        }
        BenchReference reference = spec_.reference;
        reference.set = set;
        return ReferenceTarget{reference_key(reference, reference_desc, bench_scene.source, *scene,
                                             camera, config.width, config.height, shader_root),
                               reference_description(spec_, bench_scene, config.camera,
                                                     config.width, config.height, set)
                                   .dump(2),
                               set, what, false};
      };
      if (!spec_.reference.is_image()) refs.full = target_for(spec_.reference.set, "reference");
      if (!model) continue;
      const std::string pass = path_tracer_pass_of(reference_desc);
      if (pass.empty()) {
        if (!warned_no_path_tracer_) {
          std::cerr << "voxgi: bench: note: no same-bounce references: the reference graph '"
                    << spec_.reference.file_as_written
                    << "' has no pass of type reference.path_tracer\n";
          warned_no_path_tracer_ = true;
        }
        continue;
      }
      const std::map<std::string, std::string> set =
          same_bounce_reference_set(spec_.reference.set, pass, *model);
      refs.same_bounce = target_for(
          set, "same-bounce reference (" + changed_settings(set, spec_.reference.set) + ")");
      if (!spec_.reference.is_image()) {
        std::map<std::string, std::string> full_set = spec_.reference.set;
        full_set[pass + ".deferred_layers"] = "true";
        full_set[pass + ".pixel_jitter"] = "false";  // as the same-bounce reference
        // The bench's own reference when it already splits that way.
        refs.full_like_split =
            full_set == spec_.reference.set
                ? refs.full
                : target_for(full_set, "reference split as deferred lighting + GI (" +
                                           changed_settings(full_set, spec_.reference.set) + ")");
      }
    }
  }

  const ConfigReferences& references_of(const BenchConfiguration& config) const {
    return references_of_.at(config.index);
  }

  ConfigResult measure(const BenchConfiguration& config, BenchRenderer& renderer,
                       BenchProgress& progress) {
    const auto start = Clock::now();
    const BenchGraph& entry = spec_.graphs[config.graph];
    progress.starting(config.id + " " + config.label(spec_));
    scene::Scene& scene = catalog_.scene(spec_.scenes[config.scene].source);
    const scene::Camera camera = camera_of(scene, config);
    const ConfigReferences& refs = references_of_.at(config.index);
    const ReferenceImages& reference =
        reference_for(config, refs.full, scene, camera, renderer, progress);
    const ReferenceImages* same_bounce =
        refs.same_bounce
            ? &reference_for(config, *refs.same_bounce, scene, camera, renderer, progress)
            : nullptr;
    const ReferenceImages* full_like_split =
        refs.full_like_split
            ? &reference_for(config, *refs.full_like_split, scene, camera, renderer, progress)
            : nullptr;

    const graph::CompiledGraph compiled =
        catalog_.compile(catalog_.graph(entry.file), scene, config.width, config.height,
                         config.overrides, &renderer.context());
    const runtime::FrameChanges changes{false, spec_.changes != "none",
                                        spec_.changes == "geometry"};
    RenderRun run = renderer.render(compiled, catalog_.registry(), scene, camera,
                                    spec_.warmup_frames, spec_.frames, {}, changes);

    ConfigResult r;
    r.index = config.index;
    r.id = config.id;
    r.label = config.label(spec_);
    r.technique = entry.label;
    r.graph = entry.file_as_written;
    r.scene = spec_.scenes[config.scene].label;
    r.camera = config.camera;
    r.width = config.width;
    r.height = config.height;
    r.overrides = config.overrides;
    r.swept = config.swept;
    r.warmup_frames = spec_.warmup_frames;
    r.frames = spec_.frames;
    r.times = summarize_frames(run.measured);
    r.gpu_memory_bytes = compiled.total_bytes;
    r.gpu_memory_unshared_bytes = compiled.total_bytes_unshared;
    r.full = image::compare_images(run.outputs.at("linear"), reference.linear);
    if (run.outputs.count("indirect") && reference.indirect) {
      r.indirect = image::compare_images(run.outputs.at("indirect"), *reference.indirect);
    }
    r.reference_key = reference.key;
    r.reference_cache_hit = reference.cache_hit;
    if (refs.model) {
      r.same_bounce = same_bounce_result(*refs.model, run, reference, full_like_split, same_bounce);
      // The bench's reference already split alike: the comparison is the one made above.
      if (full_like_split == &reference) r.same_bounce->full_indirect = r.indirect;
      if (refs.same_bounce) r.same_bounce->reference_set = refs.same_bounce->set;
    }
    write_images(r, run, reference);
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return r;
  }

 private:
  static scene::Camera camera_of(const scene::Scene& scene, const BenchConfiguration& config) {
    return choose_camera(scene, config.camera == "default" ? "" : config.camera);
  }

  // The like-with-like part of a result: the technique's indirect against the same-bounce
  // reference, and what the full reference's indirect has beyond that one's.
  // `full` is the full reference split alike; when it is `reference` itself, the caller
  // already compared with it.
  static SameBounceResult same_bounce_result(const IndirectModel& model, const RenderRun& run,
                                             const ReferenceImages& reference,
                                             const ReferenceImages* full,
                                             const ReferenceImages* same_bounce) {
    SameBounceResult s;
    s.bounces = model.bounces;
    s.brdf = model.brdf();
    s.faces = model.front_faces_only ? "front" : "both";
    const image::ImageRGBA32F* indirect =
        run.outputs.count("indirect") ? &run.outputs.at("indirect") : nullptr;
    if (full) s.full_reference_key = full->key;
    if (full && full != &reference && indirect && full->indirect) {
      s.full_indirect = image::compare_images(*indirect, *full->indirect);
    }
    if (!same_bounce) return s;
    s.reference_key = same_bounce->key;
    s.reference_cache_hit = same_bounce->cache_hit;
    if (!same_bounce->indirect) return s;
    if (indirect) s.indirect = image::compare_images(*indirect, *same_bounce->indirect);
    if (same_bounce->indirect_variance) {
      s.reference_noise_rel_mse =
          image::noise_rel_mse(*same_bounce->indirect, *same_bounce->indirect_variance);
    }
    if (full && full->indirect) {
      s.missing_fraction = missing_indirect_fraction(image::mean_luminance(*full->indirect),
                                                     image::mean_luminance(*same_bounce->indirect));
    }
    return s;
  }

  // The image reference of the bench file, read (and checked against every configuration's
  // resolution) before anything is rendered.
  ReferenceTarget image_reference_target(const BenchConfiguration& config) {
    const BenchReference& ref = spec_.reference;
    if (!image_reference_) image_reference_ = read_reference_images(ref);
    if (image_reference_->linear.width != config.width ||
        image_reference_->linear.height != config.height) {
      fail_at(ref.image.loc, "reference.image",
              "'" + ref.image.file_as_written + "' is " + size_text(image_reference_->linear) +
                  " but configuration " + config.id + " renders " + std::to_string(config.width) +
                  "x" + std::to_string(config.height));
    }
    return ReferenceTarget{image_reference_->key, {}, {}, "reference image", true};
  }

  static std::string size_text(const image::ImageRGBA32F& picture) {
    return std::to_string(picture.width) + "x" + std::to_string(picture.height);
  }

  // The image reference; else from this run's references, else the cache, else rendered now
  // and stored in the cache.
  const ReferenceImages& reference_for(const BenchConfiguration& config,
                                       const ReferenceTarget& target, const scene::Scene& scene,
                                       const scene::Camera& camera, BenchRenderer& renderer,
                                       BenchProgress& progress) {
    if (target.image) {
      if (image_reference_->display_png.empty()) {
        image_reference_->display_png =
            out_dir_ / "images" / ("reference-image-" + target.key + ".png");
        image::write_png(image_reference_->display_png, display_picture(image_reference_->linear));
      }
      return *image_reference_;
    }
    if (auto known = references_.find(target.key); known != references_.end()) {
      return known->second;
    }
    const std::string where = where_of(spec_, config);
    const std::string entry = (cache_.dir() / target.key).string();
    if (std::optional<ReferenceImages> cached = cache_.find(target.key)) {
      progress.note("voxgi: bench: " + target.what + " for " + where + ": cache hit (" + entry +
                    ")");
      return references_.emplace(target.key, std::move(*cached)).first->second;
    }
    const uint32_t frames = spec_.reference.frames;
    progress.note("voxgi: bench: " + target.what + " for " + where + ": not cached, rendering " +
                  std::to_string(frames) + " frames of " + spec_.reference.file_as_written);
    const auto start = Clock::now();
    const graph::CompiledGraph compiled =
        catalog_.compile(catalog_.graph(spec_.reference.file), scene, config.width, config.height,
                         target.set, &renderer.context());
    const RenderRun run = renderer.render(
        compiled, catalog_.registry(), scene, camera, 0, frames, [&](uint32_t done) {
          progress.step(target.what + " for " + where + ": frame " + std::to_string(done) + "/" +
                        std::to_string(frames));
        });
    ReferenceImages stored = cache_.store(target.key, run.outputs, target.description);
    progress.note(
        "voxgi: bench: " + target.what + " rendered in " +
        BenchProgress::duration_text(std::chrono::duration<double>(Clock::now() - start).count()) +
        ", cached as " + entry);
    return references_.emplace(target.key, std::move(stored)).first->second;
  }

  // The display image, the error heat map and a copy of the reference's display image.
  void write_images(ConfigResult& r, const RenderRun& run, const ReferenceImages& reference) {
    r.image_png = "images/" + r.id + ".png";
    r.heat_map_png = "images/" + r.id + "-error.png";
    r.reference_png = "images/reference-" + reference.key + ".png";
    image::write_png(out_dir_ / r.image_png, run.outputs.at("display"));
    image::write_png(out_dir_ / r.heat_map_png,
                     image::relative_error_heat_map(run.outputs.at("linear"), reference.linear));
    std::error_code ec;
    fs::copy_file(reference.display_png, out_dir_ / r.reference_png,
                  fs::copy_options::overwrite_existing, ec);
    if (ec) {
      throw std::runtime_error("cannot copy the reference image '" +
                               reference.display_png.string() + "' to '" +
                               (out_dir_ / r.reference_png).string() + "': " + ec.message());
    }
  }

  const BenchSpec& spec_;
  ReferenceCache& cache_;
  fs::path out_dir_;
  BenchCatalog catalog_;
  std::map<size_t, ConfigReferences> references_of_;   // configuration index → its references
  std::map<std::string, ReferenceImages> references_;  // by key, for this run
  std::optional<ReferenceImages> image_reference_;     // the bench file's "image"
  bool warned_no_path_tracer_ = false;
};

std::string summary_of(const ConfigResult& r, const std::string& where) {
  std::string text = r.id + " " + r.label + " on " + where + ": " +
                     report_number(r.times.gpu_total_ms.median) + " ms GPU (p10-p90 " +
                     report_number(r.times.gpu_total_ms.p10) + "-" +
                     report_number(r.times.gpu_total_ms.p90) + ")";
  if (r.full) text += ", relMSE " + report_number(r.full->rel_mse);
  if (r.indirect) text += ", indirect relMSE " + report_number(r.indirect->rel_mse);
  if (r.same_bounce && r.same_bounce->indirect) {
    text += " (same-bounce " + report_number(r.same_bounce->indirect->rel_mse) + ")";
  }
  return text;
}

int run_bench(const std::vector<std::string>& argv) {
  Args args = bench_args();
  args.parse(argv);
  if (args.flag("help")) {
    std::cout << kBenchUsage << args.help();
    return 0;
  }
  // A mistyped subcommand reads as a missing bench file; say what was probably meant.
  std::error_code missing;
  if (!args.positional().empty() &&
      !fs::exists(runtime::resolve_graph_path(args.positional()[0]), missing)) {
    if (const std::string close =
            closest_match(args.positional()[0], {"merge", "bvh", "voxel-light"});
        !close.empty()) {
      throw UsageError("voxgi bench: no bench file '" + args.positional()[0] +
                       "' (did you mean 'voxgi bench " + close + "'?)");
    }
  }
  if (args.positional().size() != 1) {
    throw UsageError(args.positional().empty()
                         ? "voxgi bench: expected a bench file (e.g. graphs/bench.json)"
                         : "voxgi bench: unexpected argument '" + args.positional()[1] + "'");
  }
  const std::optional<Shard> shard =
      args.value("shard") ? std::optional<Shard>(parse_shard(*args.value("shard"))) : std::nullopt;
  const fs::path bench_file = runtime::resolve_graph_path(args.positional()[0]);
  const BenchSpec spec = load_bench_file(bench_file, runtime::repo_dir());
  const std::vector<BenchConfiguration> all = expand_configurations(spec);
  const std::vector<BenchConfiguration> selected = shard ? select_shard(all, *shard) : all;
  const fs::path out_dir = args.value("out") ? fs::path(*args.value("out")) : default_out_dir(spec);
  ReferenceCache cache(args.value("reference-cache") ? fs::path(*args.value("reference-cache"))
                                                     : default_reference_cache_dir());
  if (!args.flag("check")) {
    std::error_code ec;
    fs::create_directories(out_dir / "images", ec);
    if (ec) {
      throw std::runtime_error("--out: cannot create folder '" + out_dir.string() +
                               "': " + ec.message());
    }
  }
  BenchRun run(spec, cache, out_dir);
  run.check(selected);
  if (args.flag("check")) {
    std::cout << spec.file.filename().string() << ": " << selected.size() << " of " << all.size()
              << " configurations" << (shard ? " (shard " + shard->text() + ")" : std::string())
              << "\n";
    for (const BenchConfiguration& config : selected) {
      const ConfigReferences& refs = run.references_of(config);
      const auto listed = [&](const ReferenceTarget& target) {
        return target.key + (!target.image && cache.has_entry(target.key) ? ", cached" : "");
      };
      std::cout << "  " << config.id << "  " << config.label(spec) << "  on "
                << where_of(spec, config) << "  (" << refs.full.what << " " << listed(refs.full)
                << ")";
      if (refs.model) {
        std::cout << "  indirect: " << refs.model->bounces << " bounce"
                  << (refs.model->bounces == 1 ? "" : "s") << ", " << refs.model->terms();
        if (refs.same_bounce) {
          std::cout << "; " << refs.same_bounce->what << " " << listed(*refs.same_bounce);
        }
      }
      std::cout << "\n";
    }
    return 0;
  }

  gpu::ContextOptions context_options;
  context_options.device = args.value_or("device", "");
  const char* env_validation = std::getenv("VOXGI_VALIDATION");
  context_options.validation =
      args.flag("validation") || (env_validation && std::string(env_validation) == "1");
  BenchRenderer renderer(context_options);
  std::cerr << "voxgi: device: " << renderer.context().device_summary() << "\n";
  std::cerr << "voxgi: bench '" << spec.name << "': " << selected.size() << " of " << all.size()
            << " configurations" << (shard ? " (shard " + shard->text() + ")" : std::string())
            << ", reference cache " << cache.dir().string() << "\n";

  BenchResults results;
  results.name = spec.name;
  results.bench_file = args.positional()[0];  // as given: no machine paths in reports
  results.bench_hash = spec.content_hash;
  results.device = renderer.context().device_summary();
  // An image reference is recorded by its file, with 0 frames.
  results.reference_graph = spec.reference.is_image() ? spec.reference.image.file_as_written
                                                      : spec.reference.file_as_written;
  results.reference_frames = spec.reference.is_image() ? 0 : spec.reference.frames;
  results.changes = spec.changes;
  results.configurations_total = all.size();
  if (shard) results.shards.push_back(shard->text());

  BenchProgress progress(std::cerr, selected.size(), ::isatty(STDERR_FILENO) == 1);
  for (const BenchConfiguration& config : selected) {
    results.results.push_back(run.measure(config, renderer, progress));
    progress.finished(summary_of(results.results.back(), where_of(spec, config)));
  }
  progress.done();

  write_results(out_dir, results);
  write_report(out_dir, results);
  std::cerr << "voxgi: wrote " << (out_dir / "results.json").string() << ", "
            << (out_dir / "results.csv").string() << ", " << (out_dir / "report.md").string()
            << "\n";
  if (context_options.validation && renderer.context().validation_message_count() > 0) {
    std::cerr << "voxgi: error: the validation layer reported "
              << renderer.context().validation_message_count() << " message(s)\n";
    return 1;
  }
  return 0;
}

}  // namespace

int bench_command(const std::vector<std::string>& args) {
  if (!args.empty() && args[0] == "merge") {
    return bench_merge_command(std::vector<std::string>(args.begin() + 1, args.end()));
  }
  if (!args.empty() && args[0] == "bvh") {
    return bench_bvh_command(std::vector<std::string>(args.begin() + 1, args.end()));
  }
  if (!args.empty() && args[0] == "voxel-light") {
    return bench_voxel_light_command(std::vector<std::string>(args.begin() + 1, args.end()));
  }
  return run_bench(args);
}

}  // namespace voxgi::cli
