#pragma once
// The parts of `voxgi bench` besides measuring graphs: merging shard results, BVH statistics
// and the voxel injection model against exact surface sampling.

#include <string>
#include <vector>

namespace voxgi::cli {

// The usage lines of every `voxgi bench` form.
extern const char* const kBenchUsage;

int bench_merge_command(const std::vector<std::string>& args);
int bench_bvh_command(const std::vector<std::string>& args);
int bench_voxel_light_command(const std::vector<std::string>& args);

}  // namespace voxgi::cli
