#pragma once
// Registration functions of the "lpv" (light propagation volumes) pass family, one per pass
// type.

#include "engine/graph/pass.hpp"

namespace voxgi::passes::lpv {

void register_rsm(graph::Registry& registry);
void register_inject(graph::Registry& registry);
void register_downsample(graph::Registry& registry);
void register_propagate(graph::Registry& registry);
void register_merge(graph::Registry& registry);
void register_lookup(graph::Registry& registry);

}  // namespace voxgi::passes::lpv
