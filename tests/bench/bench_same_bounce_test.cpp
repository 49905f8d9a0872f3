// Like-with-like references: the bounces and BRDF terms the GI graphs declare, and the path
// tracer settings of their same-bounce references.

#include "apps/voxgi/bench_same_bounce.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "engine/graph/graph_desc.hpp"

namespace voxgi::cli {
namespace {

const std::filesystem::path kRepo = VOXGI_SOURCE_DIR;

// The graph's parameters with their defaults, then `overrides` (as CompiledGraph::parameters).
std::map<std::string, double> parameters_of(const graph::GraphDesc& desc,
                                            const std::map<std::string, double>& overrides = {}) {
  std::map<std::string, double> parameters;
  for (const graph::GraphParam& p : desc.parameters) parameters[p.name] = p.value;
  for (const auto& [name, value] : overrides) parameters[name] = value;
  return parameters;
}

// A scene without glossy materials, and one with (SceneFeatures::as_map()).
const std::map<std::string, double> kMatte = {{"scene.has_glossy", 0.0}};
const std::map<std::string, double> kGlossy = {{"scene.has_glossy", 1.0}};

std::string error_of(const graph::GraphDesc& desc, const std::map<std::string, double>& params,
                     const std::map<std::string, double>& features = kMatte) {
  try {
    indirect_model_of(desc, params, features);
  } catch (const graph::GraphError& e) {
    return e.what();
  }
  return {};
}

TEST(BenchSameBounce, VctDeclaresOneDiffuseBounce) {
  const graph::GraphDesc vct = graph::load_graph_file(kRepo / "graphs" / "vct.json");
  const std::optional<IndirectModel> model = indirect_model_of(vct, parameters_of(vct), kMatte);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->bounces, 1u);
  EXPECT_TRUE(model->diffuse_only);
  EXPECT_EQ(model->brdf(), "diffuse");
}

// On a glossy scene the specular pass runs and the diffuse leaves it its share: the indirect
// light models the full BRDF and is compared with the full path tracer.
TEST(BenchSameBounce, GlossyScenesHoldTheFullBrdf) {
  for (const char* file :
       {"vct.json", "dvs.json", "vct_front_light.json", "dvs_front_light.json"}) {
    const graph::GraphDesc desc = graph::load_graph_file(kRepo / "graphs" / file);
    EXPECT_TRUE(indirect_model_of(desc, parameters_of(desc), kMatte)->diffuse_only) << file;
    EXPECT_EQ(indirect_model_of(desc, parameters_of(desc), kGlossy)->brdf(), "full") << file;
  }
  // lpv has no specular pass: diffuse on any scene.
  const graph::GraphDesc lpv = graph::load_graph_file(kRepo / "graphs" / "lpv.json");
  EXPECT_TRUE(indirect_model_of(lpv, parameters_of(lpv), kGlossy)->diffuse_only);
}

TEST(BenchSameBounce, DvsFollowsItsBounceParameter) {
  const graph::GraphDesc dvs = graph::load_graph_file(kRepo / "graphs" / "dvs.json");
  // K voxel bounces plus the final gather: K + 1 bounces of indirect light.
  EXPECT_EQ(indirect_model_of(dvs, parameters_of(dvs), kMatte)->bounces, 2u)
      << "default dvs.bounces 1";
  for (double k : {0.0, 1.0, 2.0, 3.0}) {
    const std::optional<IndirectModel> model =
        indirect_model_of(dvs, parameters_of(dvs, {{"dvs.bounces", k}}), kMatte);
    ASSERT_TRUE(model);
    EXPECT_EQ(model->bounces, static_cast<uint32_t>(k) + 1);
    EXPECT_TRUE(model->diffuse_only);
  }
}

TEST(BenchSameBounce, LpvDeclaresOneDiffuseBounce) {
  const graph::GraphDesc lpv = graph::load_graph_file(kRepo / "graphs" / "lpv.json");
  const std::optional<IndirectModel> model = indirect_model_of(lpv, parameters_of(lpv), kMatte);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->bounces, 1u);
  EXPECT_TRUE(model->diffuse_only);
}

TEST(BenchSameBounce, GraphsWithoutADeclarationHaveNone) {
  for (const char* file : {"default.json", "reference.json"}) {
    const graph::GraphDesc desc = graph::load_graph_file(kRepo / "graphs" / file);
    EXPECT_FALSE(indirect_model_of(desc, parameters_of(desc), kMatte)) << file;
  }
}

TEST(BenchSameBounce, SameBounceReferenceSettings) {
  const graph::GraphDesc reference = graph::load_graph_file(kRepo / "graphs" / "reference.json");
  const std::string pass = path_tracer_pass_of(reference);
  EXPECT_EQ(pass, "path_tracer");
  EXPECT_EQ(path_tracer_pass_of(graph::load_graph_file(kRepo / "graphs" / "default.json")), "");

  const std::map<std::string, std::string> user = {{"path_tracer.samples_per_frame", "4"},
                                                   {"path_tracer.max_depth", "9"}};
  // vct: one bounce, diffuse → the emitters one reflection behind make max_depth 2.
  const std::map<std::string, std::string> vct =
      same_bounce_reference_set(user, pass, IndirectModel{1, true});
  EXPECT_EQ(vct, (std::map<std::string, std::string>{{"path_tracer.samples_per_frame", "4"},
                                                     {"path_tracer.max_depth", "2"},
                                                     {"path_tracer.deferred_layers", "true"},
                                                     {"path_tracer.pixel_jitter", "false"},
                                                     {"path_tracer.lambert", "true"}}));
  // dvs with dvs.bounces = 2: three bounces, max_depth 4 (docs/dvs.md: K + 2).
  EXPECT_EQ(same_bounce_reference_set({}, pass, IndirectModel{3, true}).at("path_tracer.max_depth"),
            "4");
  // A technique modelling the full BRDF keeps the reference's materials.
  const std::map<std::string, std::string> full =
      same_bounce_reference_set({}, pass, IndirectModel{2, false});
  EXPECT_EQ(full.count("path_tracer.lambert"), 0u);
  EXPECT_EQ(full.at("path_tracer.max_depth"), "3");
  EXPECT_EQ(full.count("path_tracer.single_sided"), 0u);
  // A technique that lights single-sided materials' fronts only: so does its reference.
  IndirectModel front{1, true};
  front.front_faces_only = true;
  EXPECT_EQ(same_bounce_reference_set({}, pass, front).at("path_tracer.single_sided"), "true");
  EXPECT_EQ(front.terms(), "diffuse, front faces");
}

// "faces" is optional: both faces by default, as the path tracer shades them.
TEST(BenchSameBounce, FacesDeclaration) {
  const auto model_of = [](const std::string& indirect) {
    const graph::GraphDesc desc =
        graph::parse_graph(R"({ "name": "g", "indirect": )" + indirect +
                               R"(, "passes": [], "outputs": { "display": "x" } })",
                           "faces.json");
    return *indirect_model_of(desc, {}, kMatte);
  };
  EXPECT_FALSE(model_of(R"({ "bounces": 1 })").front_faces_only);
  EXPECT_FALSE(model_of(R"({ "bounces": 1, "faces": "both" })").front_faces_only);
  EXPECT_TRUE(model_of(R"({ "bounces": 1, "faces": "front" })").front_faces_only);
}

TEST(BenchSameBounce, MissingFraction) {
  EXPECT_DOUBLE_EQ(missing_indirect_fraction(2.0, 1.5), 0.25);
  EXPECT_DOUBLE_EQ(missing_indirect_fraction(2.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(missing_indirect_fraction(0.0, 1.0), 0.0) << "black full reference";
}

TEST(BenchSameBounce, BadDeclarationsNameTheGraphFileAndField) {
  const auto graph_with = [](const std::string& indirect) {
    return graph::parse_graph(R"({ "name": "g", "parameters": { "k": 1.5 },
      "indirect": )" + indirect + R"(,
      "passes": [], "outputs": { "display": "x" } })",
                              "bad-graph.json");
  };
  const graph::GraphDesc undefined = graph_with(R"({ "bounces": "${nope} + 1" })");
  std::string message = error_of(undefined, parameters_of(undefined));
  EXPECT_NE(message.find("bad-graph.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("field 'indirect.bounces'"), std::string::npos) << message;

  const graph::GraphDesc fractional = graph_with(R"({ "bounces": "${k}" })");
  message = error_of(fractional, parameters_of(fractional));
  EXPECT_NE(message.find("expected an integer number of bounces in [0, 64], found 1.5"),
            std::string::npos)
      << message;

  const graph::GraphDesc unknown_feature =
      graph_with(R"({ "bounces": 1, "brdf": "diffuse", "specular": "scene.has_glosy" })");
  message = error_of(unknown_feature, parameters_of(unknown_feature));
  EXPECT_NE(message.find("bad-graph.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("field 'indirect.specular'"), std::string::npos) << message;
  // The graph compiler's message for a failing expression: its column and a did-you-mean.
  EXPECT_NE(message.find("in expression \"scene.has_glosy\" at column 1"), std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'scene.has_glossy'"), std::string::npos) << message;

  for (const char* bad :
       {R"({ "bounces": 1, "brdf": "glossy" })", R"({ "brdf": "full" })",
        R"({ "bounces": 1, "bounce": 2 })", R"({ "bounces": 1, "faces": "back" })",
        R"({ "bounces": 1, "faces": true })", R"(3)"}) {
    try {
      graph_with(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const graph::GraphError& e) {
      EXPECT_NE(std::string(e.what()).find("bad-graph.json:2:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("indirect"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace voxgi::cli
