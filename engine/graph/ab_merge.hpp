#pragma once
// Two compiled graphs (two variants of one file, or two files) as one graph that renders both,
// so that an A/B view runs what they share once per frame. A pass of B is shared when A has a
// pass of the same name and type with the same resolved parameters, whose inputs are shared
// resources (or unbound in both) and whose outputs have the same descriptions; a resource is
// shared when it has the same name and description in both and every pass writing it, in A and
// in B, is shared. Everything B does not share runs as well, renamed "b/<name>".

#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/graph/graph_desc.hpp"

namespace voxgi::graph {

struct AbMerge {
  GraphDesc desc;  // literal sizes and parameters: compile it for the same scene and viewport
  std::vector<std::string> shared_passes;  // B's passes that A's run for both, in A's order
  std::vector<std::string> b_passes;       // B's other passes, as named in desc ("b/...")
};

inline constexpr const char* kAbPrefix = "b/";

// `a` and `b` compiled for the same scene, viewport and device. A's outputs keep their names,
// B's are "b/<output>".
AbMerge merge_for_ab(const CompiledGraph& a, const CompiledGraph& b);

}  // namespace voxgi::graph
