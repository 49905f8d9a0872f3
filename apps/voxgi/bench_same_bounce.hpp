#pragma once
// Like-with-like references for `voxgi bench`: a GI graph declares how many bounces of indirect
// light its `indirect` output holds and which BRDF terms it models ("indirect" in the graph
// file); its same-bounce reference is the bench's path tracer limited to that, with the
// direct/indirect split of deferred lighting plus voxel GI (docs/reference.md).

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "engine/graph/graph_desc.hpp"

namespace voxgi::cli {

struct IndirectModel {
  uint32_t bounces = 0;
  bool diffuse_only = false;
  // Single-sided materials reflect and emit on their front only (`indirect.faces` "front").
  bool front_faces_only = false;
  std::string brdf() const { return diffuse_only ? "diffuse" : "full"; }
  // The BRDF terms and, where only fronts count, "front faces": "diffuse, front faces".
  std::string terms() const { return brdf() + (front_faces_only ? ", front faces" : ""); }
};

// The graph's declared indirect light with its bounce count evaluated over the graph
// parameters after overrides (CompiledGraph::parameters), and its BRDF terms: "full" where
// `indirect.specular` holds for the scene's features (a glossy scene whose specular pass runs),
// else `indirect.brdf`, and its faces (`indirect.faces`); nullopt when the graph declares none.
// Throws GraphError at the graph file's `indirect.bounces` or `indirect.specular` when the
// expression fails, or when the bounces are not an integer in [0, 64].
std::optional<IndirectModel> indirect_model_of(const graph::GraphDesc& desc,
                                               const std::map<std::string, double>& parameters,
                                               const std::map<std::string, double>& scene_features);

// The name of the reference graph's `reference.path_tracer` pass, or "" when it has none.
std::string path_tracer_pass_of(const graph::GraphDesc& reference);

// The reference overrides plus, on the path tracer pass: max_depth = bounces + 1 (the
// deferred split counts emitters one reflection behind), deferred_layers = true,
// pixel_jitter = false (every sample through the pixel's centre, where the techniques' G-buffer
// shades: the pixel's area would mix in what no per-pixel gather can show, such as a 1 mm gap at an
// emitter's rim), lambert = true for a diffuse-only technique and single_sided = true for one
// that lights single-sided materials' fronts only.
std::map<std::string, std::string> same_bounce_reference_set(
    const std::map<std::string, std::string>& reference_set, const std::string& path_tracer_pass,
    const IndirectModel& model);

// What the full reference's indirect light has beyond the same-bounce reference's, as a
// fraction of the full one's mean luminance: the part a technique cannot reach however well it
// approximates what it models. 0 when the full reference's indirect is black.
double missing_indirect_fraction(double full_mean_luminance, double same_bounce_mean_luminance);

}  // namespace voxgi::cli
