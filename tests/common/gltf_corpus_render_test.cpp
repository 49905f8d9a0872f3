// Every file of the glTF corpus that loads also renders: through the voxel GI graph (G-buffer,
// shadow maps, voxelization with vertex colours, both UV sets and texture transforms, cone
// gather) with no validation message and no NaN, Inf or negative pixel.

#include <gtest/gtest.h>

#include "tests/common/render_harness.hpp"
#include "tests/scene/gltf_corpus.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

TEST(GltfCorpusRender, EveryLoadingFileRendersFinite) {
  const std::filesystem::path dir = fresh_dir("gltf-corpus-render");
  int rendered = 0;
  for (const GltfCorpusEntry& entry : gltf_corpus()) {
    if (!entry.refusal.empty()) continue;
    SCOPED_TRACE(entry.file);
    const std::filesystem::path path = dir / entry.file;
    entry.write(path);
    RenderSetup setup;
    setup.scene = path.string();
    setup.graph = "graphs/vct.json";
    setup.width = 32;
    setup.height = 32;
    setup.overrides = {{"voxel.resolution", "32"}, {"voxel.levels", "1"}};
    RenderHarness harness(setup);
    harness.render();
    expect_finite_non_negative(harness.output("linear"), entry.file + " linear");
    expect_finite_non_negative(harness.output("indirect"), entry.file + " indirect");
    ++rendered;
  }
  EXPECT_GE(rendered, 20);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxgi::test
