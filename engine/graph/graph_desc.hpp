#pragma once
// A graph file as written: parsed but not validated. Every field keeps its source location so
// that the compiler can point at it.

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/json.hpp"

namespace voxgi::graph {

// A field that is a number or an expression string ("viewport/2", "${voxel.resolution}").
struct ExprField {
  bool present = false;
  bool is_number = false;
  double number = 0.0;
  std::string text;  // the expression, or the number as written out
  SourceLoc loc;
};

struct ResourceDesc {
  std::string name;
  SourceLoc loc;     // of the name
  std::string type;  // "image2d", "image3d", "clipmap", "buffer"
  SourceLoc type_loc;
  std::string format;
  SourceLoc format_loc;
  std::vector<ExprField> size;  // 1 (square / cube / bytes) to 3 components; empty when absent
  SourceLoc size_loc;
  ExprField mips;  // text "full" for a full chain
  ExprField layers;
  ExprField resolution;  // clipmap
  ExprField levels;      // clipmap
  bool persistent = false;
  std::string doc;
};

// "slot": "resource" or "slot": "resource@mip".
struct BindingDesc {
  std::string slot;
  SourceLoc slot_loc;
  std::string resource;
  int mip = -1;
  // "name@previous": the resource as the previous frame left it (inputs only; docs/design.md,
  // "Frame history").
  bool previous = false;
  SourceLoc loc;  // of the value
};

struct ParamSetting {
  std::string name;
  SourceLoc name_loc;
  json::Value value;
};

// { "repeat": count, "index": "k", "from": 1, "passes": [...] } in a pass list: its passes
// once per k = from .. from + count - 1, with "{{k}}" replaced in their strings. The count is
// an expression over graph parameters and scene features; the compiler expands the repeat
// once --set overrides are known (compose.hpp).
struct RepeatDesc {
  ExprField count;
  std::string index = "index";
  int from = 1;
  std::vector<json::Value> passes;  // as written, placeholders unfilled
  SourceLoc loc;
};

struct PassDesc {
  // Set for a repeat block (then no other field is): the compiler expands it into passes.
  std::shared_ptr<const RepeatDesc> repeat;
  std::string name;
  SourceLoc loc;  // of the pass object
  SourceLoc name_loc;
  std::string type;
  SourceLoc type_loc;
  std::string when;  // empty: always
  SourceLoc when_loc;
  std::vector<ParamSetting> params;
  std::vector<BindingDesc> inputs;
  std::vector<BindingDesc> outputs;
  std::string doc;
};

struct GraphParam {
  std::string name;
  SourceLoc loc;
  double value = 0.0;
  bool is_bool = false;
};

struct OutputDesc {
  std::string name;  // "display", "linear", ...
  std::string resource;
  SourceLoc loc;
};

// What a GI graph's `indirect` output computes, so that `voxgi bench` can compare it with a path
// tracer limited to the same light transport. "indirect": {"bounces": 1, "brdf": "diffuse"}.
struct IndirectDesc {
  bool present = false;
  // Bounces of indirect light, a number or an expression over graph parameters
  // ("${dvs.bounces} + 1"), evaluated after overrides.
  ExprField bounces;
  // Which BRDF terms the indirect light models: "diffuse" (Lambertian of the base colour
  // only) or "full".
  std::string brdf = "full";
  SourceLoc brdf_loc;
  // Optional condition over scene features and graph parameters ("scene.has_glossy"): where it
  // holds, the indirect light also holds a glossy specular term (and its diffuse the rest), so
  // it models the full BRDF whatever `brdf` says.
  ExprField specular;
  // Which faces of glTF single-sided materials (doubleSided false) reflect and emit: "both"
  // (as the path tracer shades them by default, and Cycles) or "front" (only the side their
  // normals face; their backs are culled from view and stay dark, as in the rasterised passes).
  std::string faces = "both";
  SourceLoc loc;
};

// A named variant of the graph: overrides applied as `--set` would apply them (before the
// command line's own). "variants": {"isotropic": {"doc": "...", "set": {"filter.mode":
// "isotropic"}}}. Compile one with CompileOptions::overrides["variant"] (`--variant NAME`).
struct VariantDesc {
  struct Setting {
    std::string key;  // a graph parameter or "pass.param"
    std::string value;
    SourceLoc loc;  // of the value
  };
  std::string name;
  SourceLoc loc;
  std::string doc;
  std::vector<Setting> settings;
};

// The override key that selects a variant.
inline constexpr const char* kVariantKey = "variant";

struct GraphDesc {
  std::string file;
  std::string name;
  std::string doc;
  std::vector<GraphParam> parameters;
  std::vector<ResourceDesc> resources;
  std::vector<PassDesc> passes;  // in file order
  std::vector<OutputDesc> outputs;
  IndirectDesc indirect;
  std::vector<VariantDesc> variants;        // in file order
  std::vector<std::string> included_files;  // the fragments it was composed from

  const ResourceDesc* find_resource(std::string_view name) const;
  const VariantDesc* find_variant(std::string_view name) const;
  // The pass families named by pass types "family.pass", sorted, each once.
  std::vector<std::string> families() const;
};

// Throw GraphError listing every structural problem found (wrong JSON kinds, unknown keys,
// missing names); semantic checks are the compiler's. Includes are resolved here (relative to
// `file_name`'s folder, then the shipped graphs folder); repeats are left to the compiler.
GraphDesc parse_graph(std::string_view text, std::string file_name);

// The passes of a pass list (an expanded repeat's, say), parsed as parse_graph parses the
// graph's own; `field` names the list in messages ("passes").
std::vector<PassDesc> parse_pass_list(const std::vector<json::Value>& items,
                                      const std::string& field, DiagnosticList& diags);
GraphDesc load_graph_file(const std::filesystem::path& path);

}  // namespace voxgi::graph
