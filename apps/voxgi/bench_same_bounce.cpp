#include "apps/voxgi/bench_same_bounce.hpp"

#include <cmath>
#include <cstdio>

#include "engine/graph/expression_field.hpp"

namespace voxgi::cli {

namespace {

[[noreturn]] void fail_at(const graph::ExprField& f, const char* field,
                          const std::string& message) {
  throw graph::GraphError(graph::Diagnostic{f.loc, "", field, message, ""});
}

}  // namespace

std::optional<IndirectModel> indirect_model_of(
    const graph::GraphDesc& desc, const std::map<std::string, double>& parameters,
    const std::map<std::string, double>& scene_features) {
  if (!desc.indirect.present) return std::nullopt;
  graph::ExpressionEnv env;
  env.params = parameters;
  const double bounces = graph::evaluate_field(desc.indirect.bounces, "indirect.bounces", env);
  if (bounces != std::floor(bounces) || bounces < 0.0 || bounces > 64.0) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", bounces);
    fail_at(desc.indirect.bounces, "indirect.bounces",
            std::string("expected an integer number of bounces in [0, 64], found ") + text);
  }
  IndirectModel model;
  model.bounces = static_cast<uint32_t>(bounces);
  model.diffuse_only = desc.indirect.brdf == "diffuse";
  model.front_faces_only = desc.indirect.faces == "front";
  if (model.diffuse_only && desc.indirect.specular.present) {
    env.identifiers = scene_features;
    model.diffuse_only =
        graph::evaluate_field(desc.indirect.specular, "indirect.specular", env) == 0.0;
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
  if (model.front_faces_only) set[path_tracer_pass + ".single_sided"] = "true";
  return set;
}

double missing_indirect_fraction(double full_mean_luminance, double same_bounce_mean_luminance) {
  if (!(full_mean_luminance > 0.0)) return 0.0;
  return (full_mean_luminance - same_bounce_mean_luminance) / full_mean_luminance;
}

}  // namespace voxgi::cli
