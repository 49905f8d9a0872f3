#pragma once
// Registration functions of the "reference" family, one per pass type.

#include "engine/graph/pass.hpp"

namespace voxgi::passes::reference {

void register_path_tracer(graph::Registry& registry);

}  // namespace voxgi::passes::reference
