// Pass-owned sizes: a resource the graph declares without a size (and format) takes the one
// its first writer's slot derives from the pass's parameters, the scene, the viewport or
// another bound resource; every way this can fail is a located error.
#include <gtest/gtest.h>

#include "engine/graph/dump.hpp"
#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

using test::compile_text;

const Registry& registry() {
  return test::shared_registry();
}

CompiledGraph compile_graph(const std::string& resources, const std::string& passes,
                            CompileOptions options = {}) {
  return compile_text(test::graph_text(resources, passes), registry(), options);
}

// The one error of a graph with the given resources and passes, plus vol8 (sized by a pass
// "make" of test.sized when the passes have one) and a pass writing the display image.
std::string single_error(const std::string& resources, const std::string& passes) {
  const std::string display =
      R"(, { "name": "clear", "type": "test.clear", "out": { "color": "ldr" } })";
  return test::single_compile_error(
      test::graph_text(resources + R"("vol8": { "type": "clipmap" },)", passes + display),
      registry());
}

const CompiledResource& resource(const CompiledGraph& g, const std::string& name) {
  const int index = g.find_resource(name);
  EXPECT_GE(index, 0) << name;
  return g.resources.at(static_cast<size_t>(index));
}

// Both resources unsized: "make" sizes vol and records, "follow" sizes copy from vol.
const std::string kUnsized = R"(
    "vol": { "type": "clipmap", "persistent": true },
    "records": { "type": "buffer" },
    "copy": { "type": "clipmap" },)";
const std::string kMakeAndFollow = R"(
    { "name": "make", "type": "test.sized", "params": { "resolution": 16, "levels": 3 },
      "out": { "volume": "vol", "records": "records" } },
    { "name": "follow", "type": "test.follow", "in": { "src": "vol" }, "out": { "dst": "copy" } },
    { "name": "shade", "type": "test.shade", "in": { "src": "copy" }, "out": { "color": "ldr" } })";

TEST(CompilerSizes, WritersDeriveSizeAndFormat) {
  const CompiledGraph g = compile_graph(kUnsized, kMakeAndFollow);
  const CompiledResource& vol = resource(g, "vol");
  EXPECT_EQ(vol.info.kind, ResourceKind::Clipmap);
  EXPECT_EQ(vol.info.format, VK_FORMAT_R16G16B16A16_SFLOAT);  // the slot's only format
  EXPECT_EQ(vol.info.extent.width, 16u);
  EXPECT_EQ(vol.info.extent.depth, 48u);
  EXPECT_EQ(vol.info.clipmap_levels, 3u);
  EXPECT_EQ(vol.info.mip_levels, 1u);
  EXPECT_TRUE(vol.info.persistent);
  EXPECT_EQ(vol.derived_by, "make");
  EXPECT_EQ(resource(g, "records").info.buffer_size, 16u * 16u * 16u * 16u);
  // Laid out as its input, with the full chain of a 16^3 level.
  const CompiledResource& copy = resource(g, "copy");
  EXPECT_EQ(copy.info.extent.depth, 48u);
  EXPECT_EQ(copy.info.clipmap_levels, 3u);
  EXPECT_EQ(copy.info.mip_levels, 5u);
  EXPECT_EQ(copy.derived_by, "follow");
  // A graph-sized resource says nothing of a writer.
  EXPECT_TRUE(resource(g, "ldr").derived_by.empty());
  EXPECT_NE(explain(g).find("sized by pass 'make'"), std::string::npos) << explain(g);
}

TEST(CompilerSizes, OverridesOfSizingParametersResize) {
  CompileOptions options;
  options.overrides = {{"make.resolution", "32"}};
  const CompiledGraph g = compile_graph(kUnsized, kMakeAndFollow, options);
  EXPECT_EQ(resource(g, "vol").info.extent.width, 32u);
  EXPECT_EQ(resource(g, "copy").info.extent.depth, 96u);
  EXPECT_EQ(resource(g, "records").info.buffer_size, 32u * 32u * 32u * 16u);
}

TEST(CompilerSizes, GraphSizeAndMipsWin) {
  const CompiledGraph g = compile_graph(
      R"("vol": { "type": "clipmap", "format": "rgba16f", "resolution": 8, "levels": 2 },
         "copy": { "type": "clipmap", "mips": 2 },)",
      R"({ "name": "make", "type": "test.sized", "params": { "resolution": 16 }, "out": { "volume": "vol" } },
         { "name": "follow", "type": "test.follow", "in": { "src": "vol" }, "out": { "dst": "copy" } },
         { "name": "shade", "type": "test.shade", "in": { "src": "copy" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(resource(g, "vol").info.extent.width, 8u);
  EXPECT_TRUE(resource(g, "vol").derived_by.empty());
  EXPECT_EQ(resource(g, "copy").info.extent.width, 8u);
  EXPECT_EQ(resource(g, "copy").info.mip_levels, 2u);
}

TEST(CompilerSizes, ViewportFraction) {
  // compile_text's viewport: 64 x 32
  const CompiledGraph g = compile_graph(
      R"("half": { "type": "image2d", "format": "rgba8" }, "vol8": { "type": "clipmap" },)",
      R"({ "name": "make", "type": "test.sized", "params": { "resolution": 8 },
           "out": { "volume": "vol8", "color": "half" } },
         { "name": "shade", "type": "test.shade", "in": { "src": "half" }, "out": { "color": "ldr" } })");
  EXPECT_EQ(resource(g, "half").info.extent.width, 32u);
  EXPECT_EQ(resource(g, "half").info.extent.height, 16u);
  EXPECT_EQ(resource(g, "half").info.format, VK_FORMAT_R8G8B8A8_UNORM);
}

TEST(CompilerSizes, WriterWithoutRule) {
  const std::string e =
      single_error(R"("plain": { "type": "image2d", "format": "rgba16f" },)",
                   R"({ "name": "make", "type": "test.sized", "params": { "resolution": 8 },
                                          "out": { "volume": "vol8", "unsizable": "plain" } })");
  EXPECT_NE(e.find("graphs/test.json:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("field 'resources.plain'"), std::string::npos) << e;
  EXPECT_NE(e.find("slot 'unsizable' of its first writer, pass 'make' (type 'test.sized'), does "
                   "not derive one: give 'size'"),
            std::string::npos)
      << e;
}

TEST(CompilerSizes, RuleCannotDerive) {
  const std::string e =
      single_error(R"("vol": { "type": "clipmap" },)",
                   R"({ "name": "make", "type": "test.sized", "out": { "volume": "vol" } },
                                        { "name": "make8", "type": "test.sized", "params": { "resolution": 8 },
                                          "out": { "volume": "vol8" } })");
  EXPECT_NE(e.find("field 'resources.vol'"), std::string::npos) << e;
  EXPECT_NE(e.find("pass 'make' cannot derive one for slot 'volume': parameter 'resolution' is 0 "
                   "(or give 'resolution' and 'levels')"),
            std::string::npos)
      << e;
}

TEST(CompilerSizes, FormatMustBeSingle) {
  const std::string e =
      single_error(R"("half": { "type": "image2d" },)",
                   R"({ "name": "make", "type": "test.sized", "params": { "resolution": 8 },
                                          "out": { "volume": "vol8", "color": "half" } })");
  EXPECT_NE(e.find("field 'resources.half.format'"), std::string::npos) << e;
  EXPECT_NE(e.find("does not name exactly one: give 'format'"), std::string::npos) << e;
}

TEST(CompilerSizes, NeverWritten) {
  const std::string e =
      single_error(R"("lonely": { "type": "buffer" },)",
                   R"({ "name": "make", "type": "test.sized", "params": { "resolution": 8 },
                                          "out": { "volume": "vol8" } })");
  EXPECT_NE(e.find("field 'resources.lonely'"), std::string::npos) << e;
  EXPECT_NE(e.find("no size given, and no pass writes it to derive one: give 'size'"),
            std::string::npos)
      << e;
}

TEST(CompilerSizes, ReadBeforeItsWriter) {
  const std::string e = single_error(
      R"("vol": { "type": "clipmap" },)",
      R"({ "name": "shade", "type": "test.shade", "in": { "src": "vol" }, "out": { "color": "hdr" } },
         { "name": "make", "type": "test.sized", "params": { "resolution": 8 }, "out": { "volume": "vol" } },
         { "name": "make8", "type": "test.sized", "params": { "resolution": 8 }, "out": { "volume": "vol8" } })");
  EXPECT_NE(e.find("pass 'shade' field 'in.src'"), std::string::npos) << e;
  EXPECT_NE(e.find("resource 'vol' has no size: it gives none, and no pass writing it comes "
                   "before this one to derive it"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace voxgi::graph
