// Graph composition: fragments included with arguments, repeats expanded after overrides, and
// errors located inside fragments with the include chain.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "tests/graph/test_passes.hpp"

namespace voxgi::graph {
namespace {

namespace fs = std::filesystem;

// A folder of graph and fragment files, removed afterwards.
class GraphFolder {
 public:
  GraphFolder() {
    std::random_device random;
    dir_ = fs::temp_directory_path() / ("voxgi_compose_" + std::to_string(random()));
    fs::create_directories(dir_);
  }
  ~GraphFolder() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path;
  }

 private:
  fs::path dir_;
};

CompiledGraph compile_file(const fs::path& path, CompileOptions options = {}) {
  options.viewport_width = 64;
  options.viewport_height = 32;
  return compile(load_graph_file(path), test::make_registry(), options);
}

std::vector<std::string> errors_of(const fs::path& path, CompileOptions options = {}) {
  try {
    compile_file(path, options);
  } catch (const GraphError& e) {
    std::vector<std::string> lines;
    for (const Diagnostic& d : e.diagnostics()) lines.push_back(format(d));
    return lines;
  }
  ADD_FAILURE() << path << " compiled without errors";
  return {};
}

std::vector<std::string> pass_names(const CompiledGraph& g) {
  std::vector<std::string> names;
  for (const CompiledPass& p : g.passes) names.push_back(p.name);
  return names;
}

// Clears an image and blurs it into another: the shape of a fragment a graph instantiates.
const char* kBlurFragment = R"({
  "fragment": "blur",
  "arguments": {
    "name": { "doc": "the pass name", "default": "blur" },
    "src": { "doc": "the image read" },
    "extra": null
  },
  "parameters": { "blur.size": 8 },
  "resources": {
    "{{name}}.out": { "type": "image2d", "format": "rgba16f", "size": "${blur.size}" }
  },
  "passes": [
    { "name": "{{name}}", "type": "test.blur",
      "in": { "src": "{{src}}", "extra": "{{extra}}" }, "out": { "dst": "{{name}}.out" } }
  ],
  "outputs": { "{{name}}": "{{name}}.out" }
})";

// One pass and nothing else.
const char* kPlainBlurFragment = R"({
  "fragment": "plain_blur",
  "passes": [
    { "name": "blur", "type": "test.blur", "in": { "src": "hdr" }, "out": { "dst": "blurred" } }
  ]
})";

// `extra`: a resource the last pass reads too, so that the passes writing it are needed.
std::string graph_with(const std::string& passes, const std::string& parameters = "",
                       const std::string& extra = "hdr") {
  return R"({
  "parameters": {)" +
         parameters + R"(},
  "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 }
  },
  "passes": [
    { "name": "clear", "type": "test.clear", "out": { "color": "hdr" } },
)" + passes +
         R"(
    { "name": "shade", "type": "test.shade", "in": { "src": "hdr", "extra": ")" +
         extra +
         R"(" },
      "out": { "color": "ldr" } }
  ],
  "outputs": { "display": "ldr" }
})";
}

TEST(GraphCompose, IncludedFragmentBringsPassesResourcesParametersAndOutputs) {
  GraphFolder folder;
  folder.write("parts/blur.json", kBlurFragment);
  const fs::path graph = folder.write(
      "g.json", graph_with(R"(    { "include": "parts/blur.json", "with": { "src": "hdr" } },
    { "include": "parts/blur.json", "with": { "name": "again", "src": "blur.out",
                                              "extra": "hdr" } },)",
                           R"("blur.size": 4)"));
  const CompiledGraph g = compile_file(graph);
  EXPECT_EQ(pass_names(g), (std::vector<std::string>{"clear", "blur", "again", "shade"}));
  // The includer's parameter wins over the fragment's default.
  EXPECT_EQ(g.resources[static_cast<size_t>(g.find_resource("blur.out"))].info.extent.width, 4u);
  const CompiledPass* blur = g.find_pass("blur");
  ASSERT_NE(blur, nullptr);
  // A null argument leaves the optional slot unbound; a given one binds it.
  const SlotBinding* unbound = blur->binding("extra");
  EXPECT_TRUE(unbound == nullptr || unbound->resource == -1);
  ASSERT_NE(g.find_pass("again"), nullptr);
  const SlotBinding* bound = g.find_pass("again")->binding("extra");
  ASSERT_NE(bound, nullptr);
  EXPECT_EQ(bound->resource, g.find_resource("hdr"));
  EXPECT_TRUE(g.outputs.count("again")) << "the fragment's outputs join the graph's";
  // Each fragment read is listed once, for hot reload.
  EXPECT_EQ(load_graph_file(graph).included_files,
            (std::vector<std::string>{(graph.parent_path() / "parts/blur.json").string()}));
}

TEST(GraphCompose, ErrorInsideAFragmentNamesItsLineAndTheIncludeChain) {
  GraphFolder folder;
  folder.write("parts/outer.json", R"({
  "fragment": "outer",
  "passes": [
    { "include": "inner.json" }
  ]
})");
  folder.write("parts/inner.json", R"({
  "fragment": "inner",
  "passes": [
    { "name": "bad", "type": "test.blurr", "in": { "src": "hdr" }, "out": { "dst": "ldr" } }
  ]
})");
  const fs::path graph =
      folder.write("g.json", graph_with(R"(    { "include": "parts/outer.json" },)"));
  const std::vector<std::string> errors = errors_of(graph);
  ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  const std::string inner = (graph.parent_path() / "parts/inner.json").string();
  const std::string outer = (graph.parent_path() / "parts/outer.json").string();
  EXPECT_EQ(errors[0].rfind(inner + ":4:30: error: pass 'bad' field 'type'", 0), 0u) << errors[0];
  EXPECT_NE(errors[0].find("did you mean 'test.blur'"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("\n  included from " + outer + ":4:18\n  included from " +
                           graph.string() + ":9:18"),
            std::string::npos)
      << errors[0];
}

TEST(GraphCompose, BadIncludesAreLocated) {
  GraphFolder folder;
  folder.write("parts/blur.json", kBlurFragment);
  folder.write("parts/self.json",
               R"({ "fragment": "self", "passes": [ { "include": "self.json" } ] })");
  folder.write("parts/plain.json", R"({ "passes": [] })");
  const auto first_error = [&](const std::string& passes) {
    const std::vector<std::string> errors = errors_of(folder.write("g.json", graph_with(passes)));
    return errors.empty() ? std::string() : errors.front();
  };
  EXPECT_NE(first_error(R"(    { "include": "parts/missing.json" },)")
                .find("g.json:9:18: error: field 'include': fragment file 'parts/missing.json' "
                      "not found"),
            std::string::npos);
  EXPECT_NE(
      first_error(R"(    { "include": "parts/blur.json", "with": { "src": "hdr", "nmae": "x" } },)")
          .find("field 'with.nmae': fragment 'parts/blur.json' has no argument 'nmae' (did "
                "you mean 'name'?)"),
      std::string::npos);
  EXPECT_NE(first_error(R"(    { "include": "parts/blur.json" },)")
                .find("field 'with.src': fragment 'parts/blur.json' needs argument 'src'"),
            std::string::npos);
  EXPECT_NE(first_error(R"(    { "include": "parts/self.json" },)").find("includes itself"),
            std::string::npos);
  EXPECT_NE(
      first_error(R"(    { "include": "parts/plain.json" },)").find("is not a graph fragment"),
      std::string::npos);
  // A resource two instances declare.
  const std::vector<std::string> twice = errors_of(folder.write(
      "g2.json", graph_with(R"(    { "include": "parts/blur.json", "with": { "src": "hdr" } },
    { "include": "parts/blur.json", "with": { "src": "hdr" } },)")));
  ASSERT_FALSE(twice.empty());
  EXPECT_NE(twice[0].find("resource 'blur.out' is also declared at "), std::string::npos)
      << twice[0];
}

TEST(GraphCompose, IncludeConditionAppliesToEveryPassOfTheFragment) {
  GraphFolder folder;
  folder.write("parts/plain.json", kPlainBlurFragment);
  std::string text = graph_with(R"(    { "include": "parts/plain.json", "when": "${on}" },)",
                                R"("on": false)", "blurred");
  text.replace(
      text.find("\"hdr\": {"), 0,
      R"("blurred": { "type": "image2d", "format": "rgba16f", "size": 8, "persistent": true },
    )");
  const fs::path graph = folder.write("g.json", text);
  CompiledGraph g = compile_file(graph);
  ASSERT_NE(g.find_culled("blur"), nullptr);
  EXPECT_NE(g.find_culled("blur")->reason.find("when '${on}' is false"), std::string::npos)
      << g.find_culled("blur")->reason;
  CompileOptions on;
  on.overrides["on"] = "true";
  g = compile_file(graph, on);
  EXPECT_NE(g.find_pass("blur"), nullptr);
}

// A chain of blurs, each reading the previous one's output, as many as a parameter says.
const char* kChain = R"(    { "name": "blur0", "type": "test.blur", "in": { "src": "hdr" },
      "out": { "dst": "chain.0" } },
    { "repeat": "${steps}", "index": "k", "passes": [
      { "include": "parts/step.json", "with": { "name": "blur{{k}}", "k": "{{k}}" } }
    ] },)";

TEST(GraphCompose, RepeatExpandsAfterOverrides) {
  GraphFolder folder;
  folder.write("parts/step.json", R"({
  "fragment": "step",
  "arguments": { "name": null, "k": null },
  "passes": [
    { "name": "{{name}}", "type": "test.accumulate", "out": { "acc": "chain.0" } }
  ]
})");
  std::string text = graph_with(kChain, R"("steps": 2)", "chain.0");
  text.replace(text.find("\"hdr\": {"), 0,
               R"("chain.0": { "type": "image2d", "format": "rgba16f", "size": 8 },
    )");
  const fs::path graph = folder.write("g.json", text);
  EXPECT_EQ(pass_names(compile_file(graph)),
            (std::vector<std::string>{"clear", "blur0", "blur1", "blur2", "shade"}));
  CompileOptions none;
  none.overrides["steps"] = "0";
  EXPECT_EQ(pass_names(compile_file(graph, none)),
            (std::vector<std::string>{"clear", "blur0", "shade"}));
  CompileOptions bad;
  bad.overrides["steps"] = "-1";
  const std::vector<std::string> errors = errors_of(graph, bad);
  ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  EXPECT_NE(errors[0].find("field 'repeat': repeat count '${steps}' evaluates to -1, expected a "
                           "whole number from 0 to 256"),
            std::string::npos)
      << errors[0];
}

TEST(GraphCompose, UnknownPlaceholderIsReported) {
  GraphFolder folder;
  folder.write("parts/typo.json", R"({
  "fragment": "typo",
  "arguments": { "source": "hdr" },
  "passes": [
    { "name": "b", "type": "test.blur", "in": { "src": "{{sorce}}" }, "out": { "dst": "ldr" } }
  ]
})");
  const std::vector<std::string> errors =
      errors_of(folder.write("g.json", graph_with(R"(    { "include": "parts/typo.json" },)")));
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("typo.json:5:56: error: '{{sorce}}' names no argument of this "
                           "fragment (did you mean 'source'?)"),
            std::string::npos)
      << errors[0];
}

}  // namespace
}  // namespace voxgi::graph
