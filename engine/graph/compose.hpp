#pragma once
// Graph files built from fragments (docs/graph-format.md, "Composition").
//
// A pass list may hold, besides passes:
//   { "include": "fragments/foundation.json", "with": { "specular": "gi.specular" },
//     "when": "scene.has_lights" }
// which stands for the fragment's passes at that place; the fragment's parameters, resources
// and outputs join the including file's (the includer's own declarations of a parameter or an
// output win). A fragment declares its arguments, written "{{name}}" in any string of it; an
// argument that is null removes the member (or array item) that is exactly "{{name}}", which
// leaves an optional slot unbound. And
//   { "repeat": "${dvs.bounces}", "index": "k", "from": 1, "passes": [ ... "bounce{{k}}" ... ] }
// stands for its passes once per index value; the count is an expression over graph
// parameters and scene features, so it is expanded by the compiler after --set overrides.

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/json.hpp"

namespace voxgi::graph {

// Fragments may include fragments; deeper chains are refused (they are cycles in practice).
inline constexpr int kMaxIncludeDepth = 16;
// A repeat expands to at most this many copies of its passes.
inline constexpr int kMaxRepeatCount = 256;

// The graph document `root` (read from `file`) with every include replaced by its fragment.
// Fragment paths are relative to the including file, then to the shipped graphs folder.
// Problems are added to `diags` at the include (and inside the fragment, with the include
// chain); what could not be included is left out.
// `included_files` receives every fragment file read, once each, for hot reload.
json::Value compose_includes(const json::Value& root, const std::string& file,
                             DiagnosticList& diags,
                             std::vector<std::string>* included_files = nullptr);

// `value` with "{{name}}" replaced by `arguments[name]` in every string and object key. A
// string that is exactly "{{name}}" takes the argument's kind (a number stays a number); a
// null argument removes that member or array item. Names in `kept` are left as written (the
// index of an enclosing repeat); any other unknown name is reported.
json::Value substitute_arguments(const json::Value& value,
                                 const std::map<std::string, json::Value>& arguments,
                                 const std::set<std::string>& kept, DiagnosticList& diags);

// The index names of the repeats in `value` (at any depth).
std::set<std::string> repeat_indices(const json::Value& value);

}  // namespace voxgi::graph
