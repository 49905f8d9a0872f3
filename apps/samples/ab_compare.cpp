// Sample 3: A/B comparison without a window.
//
// Renders the same frame of a scene through two graph files (or two variants or sets of
// parameters of one file), writes both images, their difference (|A - B|, scaled so small
// differences show) and both per-pass timing tables, and prints how far apart the images are.
// Then it renders both as one graph in which the passes they share run once
// (graph::merge_for_ab), names those passes, checks that the merged graph's images are the
// separate ones, and compares the GPU time of its frame with the two frames run separately.
// This is the viewer's split screen and difference view as a batch job.
//
//   voxgi-sample-ab-compare --a graphs/default.json --b graphs/other.json
//                           [--variant-a NAME] [--variant-b NAME]
//                           [--set-a k=v ...] [--set-b k=v ...] [--scene cornell]
//                           [--frames 4] [--width 256] [--height 256] [--out out/ab]

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "engine/graph/ab_merge.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/output_files.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/runtime/scene_source.hpp"
#include "engine/runtime/timings.hpp"

namespace {

using namespace voxgi;

struct Side {
  std::string graph = "graphs/default.json";
  std::string variant;
  std::vector<std::string> sets;
};

// Renders `frames` frames (the first ones warm caches and shadow maps), keeps the timings and
// returns the median GPU time of a whole frame after the first.
double render(runtime::GraphInstance& graph, const runtime::FrameView& view, int frames,
              runtime::TimingsHistory& timings) {
  std::vector<double> gpu_ms;
  for (int frame = 0; frame < frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    graph.render(view, 0.0, {frame == 0, frame == 0, frame == 0});
    timings.add_frame(graph.timings(), std::chrono::duration<double, std::milli>(
                                           std::chrono::steady_clock::now() - start)
                                           .count());
    if (frame > 0 || frames == 1) gpu_ms.push_back(graph.executor().frame_gpu_ms());
  }
  return runtime::median(gpu_ms);
}

}  // namespace

int main(int argc, char** argv) {
  Side a, b;
  std::string scene_name = "cornell", out = "out/ab";
  uint32_t width = 256, height = 256;
  int frames = 4;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw std::invalid_argument(arg + ": expects a value");
      const std::string value = argv[++i];
      const long n = std::strtol(value.c_str(), nullptr, 10);
      if (arg == "--a") {
        a.graph = value;
      } else if (arg == "--b") {
        b.graph = value;
      } else if (arg == "--variant-a") {
        a.variant = value;
      } else if (arg == "--variant-b") {
        b.variant = value;
      } else if (arg == "--set-a") {
        a.sets.push_back(value);
      } else if (arg == "--set-b") {
        b.sets.push_back(value);
      } else if (arg == "--scene") {
        scene_name = value;
      } else if (arg == "--out") {
        out = value;
      } else if (arg == "--frames" && n >= 1 && n <= 10000) {
        frames = static_cast<int>(n);
      } else if ((arg == "--width" || arg == "--height") && n >= 1 && n <= 8192) {
        (arg == "--width" ? width : height) = static_cast<uint32_t>(n);
      } else {
        throw std::invalid_argument("bad argument '" + arg + " " + value + "'");
      }
    }

    runtime::Runtime runtime({}, runtime::load_scene(scene_name));
    const scene::Camera camera = runtime::choose_camera(runtime.scene(), "");
    const runtime::FrameView view =
        runtime::frame_view(camera, static_cast<float>(width) / static_cast<float>(height));
    const std::filesystem::path folder(out);
    std::filesystem::create_directories(folder);

    std::vector<image::ImageRGBA32F> display, linear;
    std::vector<graph::CompiledGraph> compiled;
    double separate_gpu_ms = 0.0;
    for (const auto& [side, name] : {std::pair{&a, "a"}, std::pair{&b, "b"}}) {
      runtime::GraphSettings settings;
      settings.width = width;
      settings.height = height;
      settings.overrides = runtime::parse_overrides(side->sets);
      if (!side->variant.empty()) settings.overrides[graph::kVariantKey] = side->variant;
      runtime::GraphInstance graph(runtime, runtime::resolve_graph_path(side->graph), settings);
      runtime::TimingsHistory timings(static_cast<size_t>(frames));
      separate_gpu_ms += render(graph, view, frames, timings);
      runtime::write_outputs(graph, folder / name);
      display.push_back(graph.read("display"));
      linear.push_back(graph.has_output("linear") ? graph.read("linear") : display.back());
      compiled.push_back(graph.compiled());
      timings.write_json(folder / (std::string(name) + "-timings.json"), {{"graph", side->graph}});
      std::cout << name << ": " << side->graph
                << (side->variant.empty() ? "" : " #" + side->variant) << "\n"
                << timings.table();
    }

    // Both as one graph: what they share runs once.
    const graph::AbMerge merge = graph::merge_for_ab(compiled[0], compiled[1]);
    runtime::GraphSettings merged_settings;
    merged_settings.width = width;
    merged_settings.height = height;
    runtime::GraphInstance merged(runtime, merge.desc, merged_settings);
    runtime::TimingsHistory merged_timings(static_cast<size_t>(frames));
    const double merged_gpu_ms = render(merged, view, frames, merged_timings);
    merged_timings.write_json(folder / "merged-timings.json", {{"graph", merge.desc.name}});
    std::string shared;
    for (const std::string& pass : merge.shared_passes) shared += " " + pass;
    const runtime::DifferenceStats same_a =
        runtime::difference_stats(display[0], merged.read("display"));
    const runtime::DifferenceStats same_b = runtime::difference_stats(
        display[1], merged.read(std::string(graph::kAbPrefix) + "display"));
    std::cout << "merged: " << merge.shared_passes.size()
              << " shared passes run once:" << (shared.empty() ? " none" : shared) << "; "
              << merge.b_passes.size() << " of B's run apart\n"
              << merged_timings.table() << "GPU ms per frame (median): A + B separately "
              << separate_gpu_ms << ", merged " << merged_gpu_ms << " ("
              << (separate_gpu_ms > 0.0 ? merged_gpu_ms / separate_gpu_ms : 0.0) << " x)\n"
              << "merged display vs separate: A max |d| " << same_a.max_abs << ", B max |d| "
              << same_b.max_abs << "\n";

    constexpr float kGain = 8.0f;  // differences of a few percent become visible
    image::write_png(folder / "difference.png", runtime::difference(display[0], display[1], kGain));
    image::write_exr(folder / "difference.exr", runtime::difference(linear[0], linear[1]));
    const runtime::DifferenceStats stats = runtime::difference_stats(linear[0], linear[1]);
    std::cout << "linear |A-B|: max " << stats.max_abs << ", mean " << stats.mean_abs << "\n"
              << "wrote a.png a.exr b.png b.exr difference.png difference.exr "
                 "a-timings.json b-timings.json merged-timings.json to "
              << folder.string() << "\n";
    // With VOXGI_VALIDATION=1 the layer watches the run; anything it says fails it.
    if (const size_t messages = runtime.context().validation_message_count()) {
      std::cerr << "voxgi-sample-ab-compare: error: the validation layer reported " << messages
                << " message(s)\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "voxgi-sample-ab-compare: error: " << e.what() << "\n";
    return 1;
  }
}
