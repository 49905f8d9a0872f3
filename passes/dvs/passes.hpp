#pragma once
// Registration functions of the "dvs" pass family, one per pass type.

#include "engine/graph/pass.hpp"

namespace voxgi::passes::dvs {

void register_voxel_lighting(graph::Registry& registry);
void register_voxel_bounce(graph::Registry& registry);

}  // namespace voxgi::passes::dvs
