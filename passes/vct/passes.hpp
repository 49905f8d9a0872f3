#pragma once
// Registration functions of the "vct" (voxel cone tracing) family, one per pass type.

#include "engine/graph/pass.hpp"

namespace voxgi::passes::vct {

void register_inject(graph::Registry& registry);
void register_filter(graph::Registry& registry);
void register_cone_trace(graph::Registry& registry);
void register_cone_trace_specular(graph::Registry& registry);

}  // namespace voxgi::passes::vct
