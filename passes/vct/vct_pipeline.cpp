#include "passes/vct/vct_pipeline.hpp"

namespace voxgi::passes::vct {

std::string unbound_directional_slots(const graph::PassDeclaration& pass) {
  std::string missing;
  for (const char* slot : contracts::kDirectionalSlots) {
    if (!pass.has(slot)) missing += std::string(missing.empty() ? "" : ", ") + slot;
  }
  return missing;
}

FilteredVolumes bound_filtered_volumes(const graph::PassDeclaration& pass) {
  return unbound_directional_slots(pass).empty() ? FilteredVolumes::Anisotropic
                                                 : FilteredVolumes::Isotropic;
}

void check_filtered_volumes_bound(graph::PassCheck& check) {
  const std::string missing = unbound_directional_slots(check);
  if (missing.empty() || check.has(contracts::kFilteredSlot)) return;
  check.slot_error(contracts::kFilteredSlot,
                   "bind either slot 'filtered' (isotropic) or all six directional slots "
                   "pos_x..neg_z (anisotropic); unbound: filtered, " +
                       missing);
}

}  // namespace voxgi::passes::vct
