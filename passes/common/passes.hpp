#pragma once
// Registration functions of the "common" family, one per pass type.

#include "engine/graph/pass.hpp"

namespace voxgi::passes::common {

void register_gbuffer(graph::Registry& registry);
void register_shadow_maps(graph::Registry& registry);
void register_deferred_lighting(graph::Registry& registry);
void register_ambient(graph::Registry& registry);
void register_composite(graph::Registry& registry);
void register_display_transform(graph::Registry& registry);
void register_voxelize(graph::Registry& registry);

}  // namespace voxgi::passes::common
