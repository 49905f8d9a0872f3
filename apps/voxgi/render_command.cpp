// voxgi render: headless rendering of a scene through a graph to PNG (display) and EXR (linear).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <unistd.h>

#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/commands.hpp"
#include "apps/voxgi/timings_report.hpp"
#include "engine/gpu/context.hpp"
#include "engine/graph/dump.hpp"
#include "engine/graph/executor.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::cli {
namespace {

namespace fs = std::filesystem;

Args render_args() {
  return Args(
      "voxgi render",
      {{"scene", true, false, "cornell|PATH.gltf|PATH.glb", "scene to render (default cornell)"},
       {"graph", true, false, "FILE", "graph file (default graphs/default.json)"},
       {"width", true, false, "W", "image width (default 1280)"},
       {"height", true, false, "H", "image height (default 720)"},
       {"camera", true, false, "NAME", "glTF camera (default: the scene's first)"},
       {"frames", true, false, "N", "frames to render (default 1)"},
       {"fps", true, false, "N", "frames per second of scene time for animations (default 30)"},
       {"out", true, false, "PATH",
        "output stem: writes PATH.png and PATH.exr (default out/default)"},
       {"set", true, true, "KEY=VALUE", "override a graph or pass parameter (pass.param=value)"},
       {"variant", true, false, "NAME", "render one of the graph file's named variants"},
       {"timings", true, false, "PATH.json",
        "write per-pass GPU/CPU times (medians after warm-up)"},
       {"device", true, false, "INDEX|NAME",
        "Vulkan device (default: discrete GPU, else lavapipe)"},
       {"validation", false, false, "",
        "enable the Vulkan validation layer; messages fail the run"},
       {"full-barriers", false, false, "", "a full barrier between passes (to rule out sync bugs)"},
       {"no-memory-sharing", false, false, "", "give every transient resource its own memory"},
       {"dump-dir", true, false, "DIR", "write every compile phase (JSON, DOT) to DIR"},
       {"help", false, false, "", "show this help"}});
}

fs::path output_stem(const std::string& arg) {
  fs::path stem(arg);
  const std::string ext = stem.extension().string();
  if (ext == ".png" || ext == ".exr") stem.replace_extension();
  return stem;
}

// Fails early, before any GPU work, when the output folder cannot be written.
void check_writable_folder(const fs::path& file, const std::string& option) {
  const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) {
    throw std::runtime_error(option + ": cannot create folder '" + folder.string() +
                             "': " + ec.message());
  }
  const fs::path probe = folder / (".voxgi-write-test-" + std::to_string(::getpid()));
  {
    std::ofstream out(probe);
    if (!out) {
      throw std::runtime_error(option + ": folder '" + folder.string() + "' is not writable");
    }
  }
  fs::remove(probe, ec);
}

}  // namespace

int render_command(const std::vector<std::string>& argv) {
  Args args = render_args();
  args.parse(argv);
  if (args.flag("help")) {
    std::cout << "usage: voxgi render [options]\n" << args.help();
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("voxgi render: unexpected argument '" + args.positional().front() + "'");
  }
  const uint32_t width = static_cast<uint32_t>(args.integer("width", 1280, 1, 16384));
  const uint32_t height = static_cast<uint32_t>(args.integer("height", 720, 1, 16384));
  const int frames = args.integer("frames", 1, 1, 1000000);
  const int fps = args.integer("fps", 30, 1, 1000);
  const fs::path stem = output_stem(args.value_or("out", "out/default"));
  const std::optional<std::string> timings_path = args.value("timings");

  check_writable_folder(stem, "--out");
  if (timings_path) check_writable_folder(*timings_path, "--timings");

  const graph::GraphDesc desc = graph::load_graph_file(
      runtime::resolve_graph_path(args.value_or("graph", "graphs/default.json")));
  scene::Scene scene = runtime::load_scene(args.value_or("scene", "cornell"));
  // The loader's warnings name only the field; the scene file completes the location.
  for (const std::string& warning : scene.warnings)
    std::cerr << "voxgi: warning: " << scene.source << ": " << warning << "\n";
  const scene::Camera camera = choose_camera(scene, args.value_or("camera", ""));

  // The device before compiling: `when` conditions may read its features. It is announced once
  // the graph compiled, when rendering starts.
  runtime::RuntimeOptions runtime_options;
  runtime_options.device = args.value_or("device", "");
  runtime_options.validation = args.flag("validation") || runtime::validation_from_environment();
  runtime::Runtime runtime(runtime_options, std::move(scene));
  const graph::CompileOptions options =
      compile_options(args, runtime.scene(), width, height, &runtime.context());
  runtime::GraphSettings settings;
  settings.width = width;
  settings.height = height;
  settings.overrides = options.overrides;
  settings.full_barriers = options.full_barriers;
  settings.alias_transients = options.alias_transients;
  runtime::GraphInstance instance(runtime, desc, settings);
  const graph::CompiledGraph& compiled = instance.compiled();
  gpu::Context& context = runtime.context();
  std::cerr << "voxgi: device: " << context.device_summary() << "\n";
  if (const std::optional<std::string> dump_dir = args.value("dump-dir")) {
    graph::dump_phases(desc, compiled, *dump_dir);
  }

  // The first frames compile pipelines and warm caches: they are not measured.
  const uint32_t warmup = frames > 1 ? std::min(2, frames - 1) : 0;
  TimingsReport report(warmup);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const runtime::FrameView view = runtime::frame_view(camera, aspect);
  for (int frame = 0; frame < frames; ++frame) {
    const double time = static_cast<double>(frame) / fps;
    const bool moved = frame > 0 && runtime.animate(time);
    instance.render(view, time, runtime::FrameChanges{false, moved, moved});
    const graph::Executor& executor = instance.executor();
    report.add_frame(executor.timings(), graph::barrier_count(executor.frame_barriers()),
                     executor.frame_gpu_ms());
  }

  for (const auto& [name, resource] : compiled.outputs) {
    (void)resource;
    const image::ImageRGBA32F picture = instance.read(name);
    if (name == "display") {
      image::write_png(fs::path(stem.string() + ".png"), picture);
      std::cerr << "voxgi: wrote " << stem.string() << ".png\n";
    } else {
      const std::string suffix = name == "linear" ? "" : "-" + name;
      const fs::path file = stem.string() + suffix + ".exr";
      image::write_exr(file, picture);
      std::cerr << "voxgi: wrote " << file.string() << "\n";
    }
  }
  std::cerr << report.table();
  if (timings_path) {
    report.write_json(*timings_path, context.device_summary(), runtime.scene().source, desc.file,
                      width, height);
    std::cerr << "voxgi: wrote " << *timings_path << "\n";
  }
  if (runtime_options.validation && context.validation_message_count() > 0) {
    std::cerr << "voxgi: error: the validation layer reported "
              << context.validation_message_count() << " message(s)\n";
    return 1;
  }
  return 0;
}

}  // namespace voxgi::cli
