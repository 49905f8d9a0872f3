#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "engine/graph/plugin_loader.hpp"

namespace voxgi::graph {
namespace {

const std::filesystem::path kPlugins = TEST_PLUGIN_DIR;

std::string load_error(PluginLoader& loader, const std::string& family) {
  Registry registry;
  try {
    loader.load_family(family, registry);
  } catch (const PluginError& e) {
    return e.what();
  }
  ADD_FAILURE() << "family " << family << " loaded";
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PluginLoader, LoadsAFamilyOnce) {
  PluginLoader loader({kPlugins / "badabi", kPlugins / "testfam"});
  Registry registry;
  loader.load_family("testfam", registry);
  const PassTypeInfo* info = registry.find("testfam.copy");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->outputs.at(0).name, "dst");
  EXPECT_NE(registry.create("testfam.copy"), nullptr);
  loader.load_family("testfam", registry);  // idempotent: registering twice would throw
  EXPECT_EQ(registry.all().size(), 1u);
  EXPECT_EQ(loader.loaded_families().count("testfam"), 1u);
}

TEST(PluginLoader, LoadsTheFamiliesAGraphNames) {
  const GraphDesc desc = parse_graph(R"({
    "resources": { "a": { "type": "image2d", "format": "rgba8", "size": 4 } },
    "passes": [ { "name": "p", "type": "testfam.copy", "in": { "src": "a" }, "out": { "dst": "a" } } ],
    "outputs": { "display": "a" } })",
                                     "g.json");
  EXPECT_EQ(desc.families(), std::vector<std::string>{"testfam"});
  PluginLoader loader({kPlugins / "testfam"});
  Registry registry;
  loader.load_for_graph(desc, registry);
  EXPECT_NE(registry.find("testfam.copy"), nullptr);
}

TEST(PluginLoader, MissingFamilyNamesLibraryAndEveryDirectory) {
  PluginLoader loader({kPlugins / "testfam", kPlugins / "nowhere"});
  const std::string e = load_error(loader, "vct");
  EXPECT_TRUE(contains(e, "pass family 'vct'")) << e;
  EXPECT_TRUE(contains(e, "libvoxgi_passes_vct.so not found")) << e;
  EXPECT_TRUE(contains(e, (kPlugins / "testfam").string())) << e;
  EXPECT_TRUE(contains(e, (kPlugins / "nowhere").string())) << e;
}

TEST(PluginLoader, UnknownFamilyInAGraphIsLocatedWithTheFamiliesThatExist) {
  const GraphDesc desc = parse_graph(R"({
    "resources": { "a": { "type": "image2d", "format": "rgba8", "size": 4 } },
    "passes": [ { "name": "p", "type": "testfan.copy", "in": { "src": "a" }, "out": { "dst": "a" } } ],
    "outputs": { "display": "a" } })",
                                     "g.json");
  PluginLoader loader({kPlugins / "testfam", kPlugins / "testfam", kPlugins / "nowhere"});
  Registry registry;
  try {
    loader.load_for_graph(desc, registry);
    ADD_FAILURE() << "an unknown family loaded";
  } catch (const GraphError& e) {
    const std::string m = e.what();
    EXPECT_TRUE(contains(m, "g.json:3:40: error: pass 'p' field 'type'")) << m;
    EXPECT_TRUE(contains(m, "unknown pass family 'testfan' in pass type 'testfan.copy'")) << m;
    EXPECT_TRUE(contains(m, "families there: testfam")) << m;
    EXPECT_TRUE(contains(m, "did you mean 'testfam'")) << m;
  }
  // A directory given twice is searched and listed once.
  EXPECT_EQ(loader.search_dirs().size(), 2u);
}

TEST(PluginLoader, AbiMismatchNamesBothVersions) {
  PluginLoader loader({kPlugins / "badabi"});
  const std::string e = load_error(loader, "badabi");
  EXPECT_TRUE(contains(e, "pass family 'badabi'")) << e;
  EXPECT_TRUE(contains(e, (kPlugins / "badabi" / "libvoxgi_passes_badabi.so").string())) << e;
  EXPECT_TRUE(contains(e, "built for plugin ABI version " + std::to_string(kPluginAbiVersion + 41) +
                              ", expected version " + std::to_string(kPluginAbiVersion)))
      << e;
  EXPECT_TRUE(contains(e, "searched: " + (kPlugins / "badabi").string())) << e;
}

TEST(PluginLoader, MissingEntryPointIsNamed) {
  PluginLoader loader({kPlugins / "noentry"});
  const std::string e = load_error(loader, "noentry");
  EXPECT_TRUE(contains(e, "pass family 'noentry'")) << e;
  EXPECT_TRUE(contains(e, "libvoxgi_passes_noentry.so")) << e;
  EXPECT_TRUE(contains(e, "does not export the entry point voxgi_plugin_abi_version()")) << e;
  EXPECT_TRUE(contains(e, "searched: " + (kPlugins / "noentry").string())) << e;
}

TEST(PluginLoader, LoadAllFindsEveryFamilyAndStopsAtABadOne) {
  PluginLoader good({kPlugins / "testfam"});
  Registry registry;
  good.load_all(registry);
  EXPECT_NE(registry.find("testfam.copy"), nullptr);

  PluginLoader mixed({kPlugins / "testfam", kPlugins / "badabi"});
  Registry other;
  EXPECT_THROW(mixed.load_all(other), PluginError);
}

TEST(PluginLoader, DefaultSearchDirsStartWithTheEnvironment) {
  ASSERT_EQ(setenv("VOXGI_PLUGIN_PATH", "/first/dir:/second/dir", 1), 0);
  const std::vector<std::filesystem::path> dirs = PluginLoader::default_search_dirs();
  unsetenv("VOXGI_PLUGIN_PATH");
  ASSERT_GE(dirs.size(), 3u);
  EXPECT_EQ(dirs[0], "/first/dir");
  EXPECT_EQ(dirs[1], "/second/dir");
  EXPECT_EQ(dirs[2].filename(), "voxgi");  // <exe dir>/../lib/voxgi
}

}  // namespace
}  // namespace voxgi::graph
