#include "passes/contracts/voxel_volumes.hpp"

#include "engine/graph/pass_helpers.hpp"

namespace voxgi::contracts {

graph::SlotSpec voxel_faces_input() {
  return graph::sampled_clipmap_input(
      "faces",
      "the voxel's surfaces grouped by facing (contracts/voxel_volumes.glsl); each group is lit "
      "with its own normal, weighted by its area; unbound: the voxel is lit as one plane",
      true, {kVoxelFacesFormat});
}

graph::SlotSpec voxel_light_shares_output() {
  return {"light_shares",
          graph::kinds(graph::ResourceKind::Clipmap),
          graph::Access::StorageWrite,
          graph::kStageCompute,
          {kVoxelLightSharesFormat},
          true,
          "per face group its share of the voxel's light (contracts/voxel_volumes.glsl), for "
          "vct.filter; needs faces"};
}

void check_light_shares_have_faces(graph::PassCheck& check) {
  if (check.has("light_shares") && !check.has("faces")) {
    check.slot_error("light_shares", "needs the faces input bound (shares are per face group)");
  }
}

}  // namespace voxgi::contracts
