// voxgi bench bvh --scene S: how long the reference path tracer's BVH takes to build for a
// scene and how good it is (SAH cost).

#include <chrono>
#include <cstdio>
#include <iostream>

#include "apps/voxgi/bench_results.hpp"
#include "apps/voxgi/bench_subcommands.hpp"
#include "apps/voxgi/cli_args.hpp"
#include "engine/runtime/scene_source.hpp"
#include "engine/scene/bvh.hpp"

namespace voxgi::cli {

int bench_bvh_command(const std::vector<std::string>& argv) {
  Args args("voxgi bench bvh",
            {{"scene", true, false, "cornell|PATH.gltf|PATH.glb", "scene (default cornell)"},
             {"repeat", true, false, "N", "builds to time (default 5); the median is printed"},
             {"help", false, false, "", "show this help"}});
  args.parse(argv);
  if (args.flag("help")) {
    std::cout << "usage: voxgi bench bvh [options]\n" << args.help();
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("voxgi bench bvh: unexpected argument '" + args.positional().front() + "'");
  }
  const int repeat = args.integer("repeat", 5, 1, 1000);
  const std::string source = args.value_or("scene", "cornell");
  const scene::Scene scene = runtime::load_scene(source);
  std::vector<double> build_ms;
  scene::BvhStats stats;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const scene::Bvh bvh = scene::Bvh::build(scene);
    build_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    stats = bvh.stats();
  }
  const Spread spread = spread_of(build_ms);
  std::printf("scene        %s\n", scene.source.c_str());
  std::printf("triangles    %u\n", stats.triangles);
  std::printf("nodes        %u (%u leaves, max depth %u)\n", stats.nodes, stats.leaves,
              stats.max_depth);
  std::printf("SAH cost     %.4f (relative to the root box; lower is better)\n", stats.sah_cost);
  std::printf("build ms     %.3f median of %d (min %.3f, max %.3f)\n", spread.median, repeat,
              spread.min, spread.max);
  return 0;
}

}  // namespace voxgi::cli
