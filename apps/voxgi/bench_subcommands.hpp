#pragma once
// The parts of `voxgi bench` besides measuring: merging shard results and BVH statistics.

#include <string>
#include <vector>

namespace voxgi::cli {

// The usage lines of every `voxgi bench` form.
extern const char* const kBenchUsage;

int bench_merge_command(const std::vector<std::string>& args);
int bench_bvh_command(const std::vector<std::string>& args);

}  // namespace voxgi::cli
