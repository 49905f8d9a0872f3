#include "apps/voxgi/bench_same_bounce.hpp"

#include <cmath>
#include <cstdio>

#include "engine/graph/expression.hpp"

namespace voxgi::cli {

std::optional<IndirectModel> indirect_model_of(
    const graph::GraphDesc& desc, const std::map<std::string, double>& parameters,
    const std::map<std::string, double>& scene_features) {
  if (!desc.indirect.present) return std::nullopt;
  const graph::ExprField& field = desc.indirect.bounces;
  auto fail = [&](const std::string& message) {
    throw graph::GraphError(graph::Diagnostic{field.loc, "", "indirect.bounces", message, ""});
  };
  double bounces = field.number;
  if (!field.is_number) {
    graph::ExpressionEnv env;
    env.params = parameters;
    try {
      bounces = graph::evaluate_expression(field.text, env);
    } catch (const graph::ExpressionError& e) {
      fail("'" + field.text + "': " + e.what());
    }
  }
  if (bounces != std::floor(bounces) || bounces < 0.0 || bounces > 64.0) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", bounces);
    fail(std::string("expected an integer number of bounces in [0, 64], found ") + text);
  }
  IndirectModel model;
  model.bounces = static_cast<uint32_t>(bounces);
  model.diffuse_only = desc.indirect.brdf == "diffuse";
  const graph::ExprField& specular = desc.indirect.specular;
  if (model.diffuse_only && specular.present) {
    double value = specular.number;
    if (!specular.is_number) {
      graph::ExpressionEnv env;
      env.params = parameters;
      env.identifiers = scene_features;
      try {
        value = graph::evaluate_expression(specular.text, env);
      } catch (const graph::ExpressionError& e) {
        throw graph::GraphError(graph::Diagnostic{specular.loc, "", "indirect.specular",
                                                  "'" + specular.text + "': " + e.what(), ""});
      }
    }
    if (value != 0.0) model.diffuse_only = false;
  }
  return model;
}

std::string path_tracer_pass_of(const graph::GraphDesc& reference) {
  for (const graph::PassDesc& pass : reference.passes) {
    if (pass.type == "reference.path_tracer") return pass.name;
  }
  return {};
}

std::map<std::string, std::string> same_bounce_reference_set(
    const std::map<std::string, std::string>& reference_set, const std::string& path_tracer_pass,
    const IndirectModel& model) {
  std::map<std::string, std::string> set = reference_set;
  set[path_tracer_pass + ".max_depth"] = std::to_string(model.bounces + 1);
  set[path_tracer_pass + ".deferred_layers"] = "true";
  set[path_tracer_pass + ".pixel_jitter"] = "false";
  if (model.diffuse_only) set[path_tracer_pass + ".lambert"] = "true";
  return set;
}

double missing_indirect_fraction(double full_mean_luminance, double same_bounce_mean_luminance) {
  if (!(full_mean_luminance > 0.0)) return 0.0;
  return (full_mean_luminance - same_bounce_mean_luminance) / full_mean_luminance;
}

}  // namespace voxgi::cli
