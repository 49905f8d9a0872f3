#pragma once
// Helpers the vct passes share: checks of the filtered volume slots
// (their names and sampler: passes/contracts/filtered_volumes.hpp; shaders, compute pipelines
// and input versions: engine/graph/pass_helpers.hpp).

#include <string>
#include <vector>

#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "passes/contracts/filtered_volumes.hpp"

namespace voxgi::passes::vct {

// The directional slots left unbound, comma-separated; empty when all six are bound.
std::string unbound_directional_slots(const graph::PassDeclaration& pass);
// Which filtered volumes a pass reads: the six directional ones when all are bound, else the
// isotropic one (check_filtered_volumes_bound makes sure one of the two is).
enum class FilteredVolumes { Isotropic, Anisotropic };
FilteredVolumes bound_filtered_volumes(const graph::PassDeclaration& pass);
// For validate hooks of passes reading the filtered volumes.
void check_filtered_volumes_bound(graph::PassCheck& check);

// Workgroup edge of the family's 2D compute shaders.
inline constexpr uint32_t kTile = 8;

}  // namespace voxgi::passes::vct
