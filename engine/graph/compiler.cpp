#include "engine/graph/compiler.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <queue>
#include <set>
#include <stdexcept>

#include "engine/gpu/context.hpp"
#include "engine/gpu/device_features.hpp"
#include "engine/graph/compose.hpp"
#include "engine/graph/expression.hpp"
#include "engine/graph/expression_field.hpp"
#include "engine/graph/resource_plan.hpp"

namespace voxgi::graph {

const SlotBinding* CompiledPass::binding(std::string_view slot) const {
  for (const SlotBinding& b : bindings) {
    if (b.slot == slot) return &b;
  }
  return nullptr;
}

bool skip_leaves_undefined(const SlotBinding& b) {
  return !b.is_input && b.resource >= 0 && access_writes(b.spec->access) && !b.spec->scratch &&
         !b.info.persistent;
}

int CompiledGraph::find_resource(std::string_view resource_name) const {
  for (size_t i = 0; i < resources.size(); ++i) {
    if (resources[i].info.name == resource_name) return static_cast<int>(i);
  }
  return -1;
}

const CompiledPass* CompiledGraph::find_pass(std::string_view pass_name) const {
  for (const CompiledPass& p : passes) {
    if (p.name == pass_name) return &p;
  }
  return nullptr;
}

const CulledPass* CompiledGraph::find_culled(std::string_view pass_name) const {
  for (const CulledPass& p : culled) {
    if (p.name == pass_name) return &p;
  }
  return nullptr;
}

void use_device(CompileOptions& options, const gpu::Context& context) {
  options.device_features = gpu::device_feature_values(context.features());
  options.device_name = context.device_name();
}

std::vector<Diagnostic> validate_pass(const CompiledPass& pass) {
  std::vector<Diagnostic> problems;
  if (!pass.type_info || !pass.type_info->validate) return problems;
  PassCheck check(pass, [&](const std::string& field, std::string message) {
    Diagnostic d = message_only(std::move(message));
    d.pass = pass.name;
    d.field = field;
    problems.push_back(std::move(d));
  });
  try {
    pass.type_info->validate(check);
  } catch (const std::exception& e) {
    Diagnostic d = message_only(std::string("validation of the pass failed: ") + e.what());
    d.pass = pass.name;
    problems.push_back(std::move(d));
  }
  return problems;
}

namespace {

constexpr uint32_t kMaxImageSize2D = 16384;
constexpr uint32_t kMaxImageSize3D = 2048;
constexpr double kMaxBufferBytes = 4.0 * 1024 * 1024 * 1024;

struct PassWork {
  const PassDesc* desc = nullptr;
  const PassTypeInfo* info = nullptr;  // null: unknown type
  bool usable = false;                 // known type and a unique name: part of the graph
  std::map<std::string, ParamValue> params;
  std::map<std::string, SourceLoc> param_locs;  // where a parameter is set: file or --set
  std::vector<SlotBinding> bindings;
  std::string culled;  // the reason, empty while live
};

bool binding_reads(const SlotBinding& b) {
  return b.is_input || b.spec->access == Access::StorageReadWrite;
}
bool binding_writes(const SlotBinding& b) {
  return !b.is_input && access_writes(b.spec->access);
}

std::string kinds_text(ResourceKinds kinds) {
  std::string text;
  for (ResourceKind k : {ResourceKind::Image2D, ResourceKind::Image3D, ResourceKind::Clipmap,
                         ResourceKind::Buffer}) {
    if (kinds & static_cast<uint32_t>(k)) text += (text.empty() ? "" : ", ") + kind_name(k);
  }
  return text;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "'" : ", '") + n + "'";
  return text;
}

// Where `declared` is, said from `from`: "line 9" in the same file, else "file:line:col".
std::string where(const SourceLoc& declared, const SourceLoc& from) {
  if (declared.file == from.file && declared.included_from == from.included_from)
    return "line " + std::to_string(declared.line);
  return format_location(declared);
}

class Compiler {
 public:
  Compiler(const GraphDesc& desc, const Registry& registry, const CompileOptions& options)
      : desc_(desc), registry_(registry), options_(options) {}

  CompiledGraph run() {
    graph_.file = desc_.file;
    graph_.name = desc_.name;
    graph_.viewport_width = options_.viewport_width;
    graph_.viewport_height = options_.viewport_height;
    graph_.full_barriers = options_.full_barriers;
    resolve_device_features();
    resolve_variant();
    resolve_parameters();
    expand_repeats();
    resolve_resources();
    resolve_passes();
    report_unmatched_overrides();
    check_skipping_passes_write_persistent();
    validate_passes();
    check_outputs_declared();
    check_reads_have_writers();
    check_cycles();
    diags_.throw_if_any();
    cull();
    check_outputs_written();
    diags_.throw_if_any();
    schedule();
    check_transients_written_first();
    diags_.throw_if_any();
    plan_resources(graph_, options_);
    return std::move(graph_);
  }

 private:
  // ---- device features ---------------------------------------------------------------------
  // Every known name is defined, so a misspelt one is an error with or without a device.
  void resolve_device_features() {
    graph_.device_queried = !options_.device_features.empty();
    graph_.device_name = options_.device_name;
    graph_.device_features = gpu::device_feature_values(gpu::DeviceFeatures{});
    for (const auto& [name, value] : options_.device_features) {
      if (!graph_.device_features.count(name)) {
        throw std::invalid_argument("CompileOptions::device_features: unknown device feature '" +
                                    name + "'");
      }
      graph_.device_features[name] = value;
    }
  }

  // Scene and device features for `when` conditions. Sizes read no device features: a graph
  // checked without a device would get other sizes than the one that runs.
  void add_features(ExpressionEnv& env) const {
    env.identifiers = options_.scene_features;
    for (const auto& [name, value] : graph_.device_features) env.identifiers[name] = value;
    env.identifier_families["device."] = "device feature";
  }

  // ---- variants ------------------------------------------------------------------------------
  // The overrides in force: the selected variant's settings (located in the graph file), then
  // the caller's own (--set), which win.
  void resolve_variant() {
    for (const VariantDesc& v : desc_.variants) graph_.variants.push_back(v.name);
    for (const GraphParam& p : desc_.parameters) {
      if (p.name == kVariantKey) {
        diags_.error(p.loc, {}, "parameters." + p.name,
                     "'variant' is reserved: it selects one of the graph's variants");
      }
    }
    overrides_ = options_.overrides;
    auto selected = overrides_.find(kVariantKey);
    if (selected == overrides_.end()) return;
    const std::string name = selected->second;
    overrides_.erase(selected);
    if (name.empty()) return;  // the file as written (a sweep over variants may include it)
    const VariantDesc* variant = desc_.find_variant(name);
    if (!variant) {
      Diagnostic d;
      d.loc = SourceLoc{desc_.file, 0, 0};
      d.field = kVariantKey;
      d.message = desc_.variants.empty()
                      ? "graph has no variants, so there is no variant '" + name + "'"
                      : "unknown variant '" + name +
                            "' (the graph's variants: " + quoted_list(graph_.variants) + ")";
      d.hint = did_you_mean(name, graph_.variants);
      diags_.add(std::move(d));
      return;
    }
    graph_.variant = name;
    for (const VariantDesc::Setting& s : variant->settings) {
      if (overrides_.count(s.key)) continue;  // the command line wins
      overrides_[s.key] = s.value;
      variant_locs_[s.key] = s.loc;
    }
  }

  // Where an override was written: in the graph's variant, or on the command line.
  SourceLoc override_loc(const std::string& key, const std::string& text) const {
    auto it = variant_locs_.find(key);
    if (it != variant_locs_.end()) return it->second;
    return SourceLoc{"--set " + key + "=" + text, 0, 0};
  }

  // ---- graph parameters and --set -------------------------------------------------------
  void resolve_parameters() {
    for (const GraphParam& p : desc_.parameters) graph_.parameters[p.name] = p.value;
    for (const auto& [key, text] : overrides_) {
      auto it = graph_.parameters.find(key);
      if (it == graph_.parameters.end()) continue;  // a pass parameter, resolved later
      const GraphParam* declared = nullptr;
      for (const GraphParam& p : desc_.parameters) {
        if (p.name == key) declared = &p;
      }
      if (text == "true" || text == "false") {
        it->second = text == "true" ? 1.0 : 0.0;
        continue;
      }
      char* end = nullptr;
      const double number = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(number)) {
        diags_.error(override_loc(key, text), {}, key,
                     std::string("expected ") +
                         (declared && declared->is_bool ? "true or false" : "a number") +
                         ", found '" + text + "'");
        continue;
      }
      it->second = number;
    }
  }

  ExpressionEnv size_env(double viewport) const {
    ExpressionEnv env;
    env.params = graph_.parameters;
    // Scene features let sizes follow the scene (e.g. shadow layers per light present).
    env.identifiers = options_.scene_features;
    env.identifiers["viewport"] = viewport;
    env.identifiers["viewport.width"] = static_cast<double>(options_.viewport_width);
    env.identifiers["viewport.height"] = static_cast<double>(options_.viewport_height);
    env.identifier_kind = "name";
    env.identifier_help =
        "sizes may use viewport, viewport.width, viewport.height, scene features, min(a, b), "
        "max(a, b) and ${parameters}";
    return env;
  }

  std::optional<double> evaluate(const ExprField& f, const std::string& pass,
                                 const std::string& field, const ExpressionEnv& env) {
    if (f.is_number) return f.number;
    try {
      return evaluate_expression(f.text, env);
    } catch (const ExpressionError& e) {
      diags_.add(expression_field_diagnostic(f, pass, field, e));
      return std::nullopt;
    }
  }

  // A positive whole number no larger than `max`; fractions round down.
  std::optional<uint32_t> evaluate_count(const ExprField& f, const std::string& field,
                                         const ExpressionEnv& env, double max, const char* what) {
    const std::optional<double> v = evaluate(f, {}, field, env);
    if (!v) return std::nullopt;
    const double whole = std::floor(*v);
    if (whole < 1.0 || whole > max) {
      diags_.error(f.loc, {}, field,
                   std::string(what) + " '" + f.text + "' evaluates to " + format_number(*v) +
                       ", expected 1 to " + format_number(max));
      return std::nullopt;
    }
    return static_cast<uint32_t>(whole);
  }

  // ---- repeats ----------------------------------------------------------------------------
  // The graph's passes with every repeat block replaced by its copies, now that parameters
  // (and so the counts) are known.
  void expand_repeats() { expand_into(desc_.passes, passes_, 0); }

  void expand_into(const std::vector<PassDesc>& list, std::vector<PassDesc>& out, int depth) {
    for (const PassDesc& pd : list) {
      if (!pd.repeat) {
        out.push_back(pd);
        continue;
      }
      const RepeatDesc& r = *pd.repeat;
      if (depth >= kMaxIncludeDepth) {
        diags_.error(r.loc, {}, "repeat",
                     "repeats nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
        continue;
      }
      ExpressionEnv env;
      env.params = graph_.parameters;
      env.identifiers = options_.scene_features;
      env.identifier_kind = "name";
      env.identifier_help = "a repeat count may use scene features and ${parameters}";
      const std::optional<double> count = evaluate(r.count, {}, "repeat", env);
      if (!count) continue;
      if (*count < 0 || *count > kMaxRepeatCount || std::floor(*count) != *count) {
        diags_.error(r.count.loc, {}, "repeat",
                     "repeat count '" + r.count.text + "' evaluates to " + format_number(*count) +
                         ", expected a whole number from 0 to " + std::to_string(kMaxRepeatCount));
        continue;
      }
      for (int i = 0; i < static_cast<int>(*count); ++i) {
        const std::map<std::string, json::Value> index{
            {r.index, json::Value::make_number(r.from + i, r.loc)}};
        std::vector<json::Value> items;
        for (const json::Value& item : r.passes)
          items.push_back(substitute_arguments(item, index, repeat_indices(item), diags_));
        expand_into(parse_pass_list(items, "repeat.passes", diags_), out, depth + 1);
      }
    }
  }

  // ---- resources ------------------------------------------------------------------------
  void resolve_resources() {
    resource_ok_.assign(desc_.resources.size(), false);
    sizing_.assign(desc_.resources.size(), Sizing::ByGraph);
    graph_.resources.resize(desc_.resources.size());
    for (size_t i = 0; i < desc_.resources.size(); ++i) {
      const ResourceDesc& rd = desc_.resources[i];
      const bool sized =
          rd.type == "clipmap" ? rd.resolution.present || rd.levels.present : !rd.size.empty();
      const size_t problems = diags_.size();
      resource_ok_[i] = resolve_resource(rd, graph_.resources[i], sized);
      // A resource already in error (its type, its format) is not sized again by a writer.
      if (!sized) sizing_[i] = diags_.size() == problems ? Sizing::ByWriter : Sizing::Failed;
    }
  }

  // ---- sizes the writing pass derives -----------------------------------------------------
  // A resource declared without a size takes the one its first writer's slot derives
  // (SlotSpec::size_rule), once that pass's parameters are resolved.
  void derive_sizes(const PassWork& w) {
    const PassDesc& pd = *w.desc;
    for (const BindingDesc& b : pd.outputs) {
      const int index = resource_index(b.resource);
      if (index < 0 || sizing_[static_cast<size_t>(index)] != Sizing::ByWriter) continue;
      const auto i = static_cast<size_t>(index);
      const SlotSpec* spec = find_slot(w.info->outputs, b.slot);
      if (!spec) continue;  // reported with the bindings
      const ResourceDesc& rd = desc_.resources[i];
      CompiledResource& r = graph_.resources[i];
      const std::string field = "resources." + rd.name;
      const std::string what = rd.type == "clipmap" ? "'resolution' and 'levels'" : "'size'";
      sizing_[i] = Sizing::Failed;
      if (!spec->size_rule) {
        diags_.error(rd.loc, {}, field,
                     "no size given, and slot '" + b.slot + "' of its first writer, pass '" +
                         pd.name + "' (type '" + pd.type + "'), does not derive one: give " + what);
        continue;
      }
      SizeQuery query;
      query.params = &w.params;
      query.scene = &options_.scene_features;
      query.viewport_width = options_.viewport_width;
      query.viewport_height = options_.viewport_height;
      bool upstream_failed = false;  // a slot it sizes from failed, with its own error
      query.bound = [&](std::string_view slot) -> const ResourceInfo* {
        for (const auto* list : {&pd.inputs, &pd.outputs}) {
          for (const BindingDesc& other : *list) {
            if (other.slot != slot) continue;
            const int o = resource_index(other.resource);
            if (o >= 0 && sizing_[static_cast<size_t>(o)] == Sizing::Failed) upstream_failed = true;
            if (o < 0 || !resource_ok_[static_cast<size_t>(o)]) return nullptr;
            return &graph_.resources[static_cast<size_t>(o)].info;
          }
        }
        return nullptr;
      };
      query.has = [&](std::string_view slot) {
        for (const auto* list : {&pd.inputs, &pd.outputs}) {
          for (const BindingDesc& other : *list) {
            if (other.slot == slot) return true;
          }
        }
        return false;
      };
      if (rd.type != "buffer" && rd.format.empty()) {
        // The graph may leave the format to a writer whose slot allows exactly one.
        if (spec->formats.size() != 1) {
          diags_.error(rd.loc, {}, field + ".format",
                       "no format given, and slot '" + b.slot + "' of its first writer, pass '" +
                           pd.name + "', does not name exactly one: give 'format'");
          continue;
        }
        r.info.format = spec->formats.front();
      }
      const DerivedSize size = spec->size_rule(query);
      // One error per cause: what failed upstream was reported there.
      if (!size.unavailable.empty() && upstream_failed) continue;
      if (!size.unavailable.empty()) {
        diags_.error(rd.loc, {}, field,
                     "no size given, and pass '" + pd.name + "' cannot derive one for slot '" +
                         b.slot + "': " + size.unavailable + " (or give " + what + ")");
        continue;
      }
      if (!apply_derived_size(rd, r, size, field, pd.name)) continue;
      sizing_[i] = Sizing::Derived;
      r.derived_by = pd.name;
      resource_ok_[i] = resolve_mips_and_layers(rd, r, field, size.full_mips);
      if (resource_ok_[i]) r.bytes = estimate_bytes(r.info);
    }
  }

  bool apply_derived_size(const ResourceDesc& rd, CompiledResource& r, const DerivedSize& size,
                          const std::string& field, const std::string& pass) {
    const auto bad = [&](const std::string& what) {
      diags_.error(rd.loc, {}, field, "pass '" + pass + "' derives " + what);
      return false;
    };
    switch (r.info.kind) {
      case ResourceKind::Buffer:
        if (size.bytes == 0 || size.bytes > kMaxBufferBytes)
          return bad("a buffer of " + std::to_string(size.bytes) +
                     " bytes (from 1 byte to 4 GiB); lower the parameters that size it");
        r.info.buffer_size = size.bytes;
        return true;
      case ResourceKind::Clipmap:
        if (size.resolution == 0 || size.levels == 0 || size.levels > 16 ||
            double(size.resolution) * size.levels > kMaxImageSize3D)
          return bad("a clipmap of " + std::to_string(size.levels) + " levels of " +
                     std::to_string(size.resolution) + "^3 (at most 16 levels and " +
                     std::to_string(kMaxImageSize3D) +
                     " voxels for resolution × levels); lower the parameters that size it");
        r.info.extent = {size.resolution, size.resolution, size.resolution * size.levels};
        r.info.clipmap_levels = size.levels;
        return true;
      case ResourceKind::Image2D:
      case ResourceKind::Image3D: {
        const bool flat = r.info.kind == ResourceKind::Image2D;
        const uint32_t depth = flat ? 1 : size.depth;
        const double max = flat ? kMaxImageSize2D : kMaxImageSize3D;
        if (size.width == 0 || size.height == 0 || depth == 0 || size.width > max ||
            size.height > max || depth > max)
          return bad("an image of " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + (flat ? "" : "x" + std::to_string(depth)) +
                     " (each side from 1 to " + std::to_string(uint32_t(max)) + ")");
        r.info.extent = {size.width, size.height, depth};
        if (flat && size.layers > 0) r.info.array_layers = size.layers;
        return true;
      }
    }
    return false;
  }

  // A resource left without a size because nothing before its first reader sized it.
  void report_unsized(size_t i, const std::string& pass, const SourceLoc& loc,
                      const std::string& field) {
    if (sizing_[i] != Sizing::ByWriter) return;
    sizing_[i] = Sizing::Failed;
    diags_.error(loc, pass, field,
                 "resource '" + desc_.resources[i].name +
                     "' has no size: it gives none, and no pass writing it comes before this "
                     "one to derive it");
  }

  void report_never_sized() {
    for (size_t i = 0; i < sizing_.size(); ++i) {
      if (sizing_[i] != Sizing::ByWriter) continue;
      const ResourceDesc& rd = desc_.resources[i];
      diags_.error(rd.loc, {}, "resources." + rd.name,
                   std::string("no size given, and no pass writes it to derive one: give ") +
                       (rd.type == "clipmap" ? "'resolution' and 'levels'" : "'size'"));
    }
  }

  // `sized`: the graph gives the size; otherwise only the rest is checked here and the
  // writer derives the size (derive_sizes).
  bool resolve_resource(const ResourceDesc& rd, CompiledResource& r, bool sized) {
    const std::string field = "resources." + rd.name;
    r.loc = rd.loc;
    r.info.name = rd.name;
    r.info.persistent = rd.persistent;
    static const std::vector<std::string> types = {"image2d", "image3d", "clipmap", "buffer"};
    if (rd.type.empty()) return false;  // reported by the parser
    if (rd.type == "image2d") {
      r.info.kind = ResourceKind::Image2D;
    } else if (rd.type == "image3d") {
      r.info.kind = ResourceKind::Image3D;
    } else if (rd.type == "clipmap") {
      r.info.kind = ResourceKind::Clipmap;
    } else if (rd.type == "buffer") {
      r.info.kind = ResourceKind::Buffer;
    } else {
      diags_.error(
          rd.type_loc, {}, field + ".type",
          "unknown resource type '" + rd.type + "' (expected image2d, image3d, clipmap or buffer)",
          did_you_mean(rd.type, types));
      return false;
    }
    const ResourceKind kind = r.info.kind;
    bool ok = true;
    if (kind == ResourceKind::Buffer) {
      if (!rd.format.empty()) {
        diags_.error(rd.format_loc, {}, field + ".format", "buffers have no format");
        ok = false;
      }
    } else if (rd.format.empty() && !sized) {
      // Left to the writing pass with the size (derive_sizes).
    } else if (rd.format.empty()) {
      diags_.error(rd.loc, {}, field + ".format",
                   "missing field 'format' (expected one of " + quoted_list(format_names()) + ")");
      ok = false;
    } else {
      r.info.format = format_from_name(rd.format);
      if (r.info.format == VK_FORMAT_UNDEFINED) {
        diags_.error(rd.format_loc, {}, field + ".format", "unknown format '" + rd.format + "'",
                     did_you_mean(rd.format, format_names()));
        ok = false;
      } else if (is_depth_format(r.info.format) && kind != ResourceKind::Image2D) {
        diags_.error(rd.format_loc, {}, field + ".format",
                     "depth format '" + rd.format + "' is only allowed for image2d resources");
        ok = false;
      }
    }
    if (!sized) {
      for (const ExprField* f : {&rd.resolution, &rd.levels}) {
        if (f->present && kind != ResourceKind::Clipmap) {
          diags_.error(f->loc, {}, field + (f == &rd.resolution ? ".resolution" : ".levels"),
                       "only clipmaps have 'resolution' and 'levels' (use 'size')");
          ok = false;
        }
      }
      return false;  // not usable until its writer sizes it
    }
    ok = resolve_extent(rd, r, field) && ok;
    ok = resolve_mips_and_layers(rd, r, field, false) && ok;
    if (ok) r.bytes = estimate_bytes(r.info);
    return ok;
  }

  bool resolve_extent(const ResourceDesc& rd, CompiledResource& r, const std::string& field) {
    const ResourceKind kind = r.info.kind;
    if (kind == ResourceKind::Clipmap) {
      if (!rd.size.empty()) {
        diags_.error(rd.size_loc, {}, field + ".size",
                     "clipmaps are sized by 'resolution' and 'levels', not 'size'");
        return false;
      }
      if (!rd.resolution.present || !rd.levels.present) {
        diags_.error(rd.loc, {}, field + (rd.resolution.present ? ".levels" : ".resolution"),
                     "a clipmap needs both 'resolution' and 'levels'");
        return false;
      }
      const auto res = evaluate_count(rd.resolution, field + ".resolution", size_env(0),
                                      kMaxImageSize3D, "resolution");
      const auto levels = evaluate_count(rd.levels, field + ".levels", size_env(0), 16, "levels");
      if (!res || !levels) return false;
      if (*res * *levels > kMaxImageSize3D) {
        diags_.error(rd.levels.loc, {}, field + ".levels",
                     "resolution x levels = " + std::to_string(*res * *levels) +
                         " exceeds the 3D image limit " + std::to_string(kMaxImageSize3D));
        return false;
      }
      r.info.extent = {*res, *res, *res * *levels};
      r.info.clipmap_levels = *levels;
      return true;
    }
    for (const ExprField* f : {&rd.resolution, &rd.levels}) {
      if (f->present) {
        diags_.error(f->loc, {}, field + (f == &rd.resolution ? ".resolution" : ".levels"),
                     "only clipmaps have 'resolution' and 'levels' (use 'size')");
        return false;
      }
    }
    if (rd.size.empty()) {
      diags_.error(
          rd.loc, {}, field + ".size",
          kind == ResourceKind::Buffer ? "missing field 'size' (bytes)" : "missing field 'size'");
      return false;
    }
    const size_t max_components = kind == ResourceKind::Image2D   ? 2
                                  : kind == ResourceKind::Image3D ? 3
                                                                  : 1;
    if (rd.size.size() > max_components || (kind == ResourceKind::Image3D && rd.size.size() == 2)) {
      diags_.error(rd.size_loc, {}, field + ".size",
                   "a " + kind_name(kind) + " size has " +
                       (kind == ResourceKind::Image2D   ? std::string("1 or 2 components [w, h]")
                        : kind == ResourceKind::Image3D ? std::string("1 or 3 components [w, h, d]")
                                                        : std::string("1 component (bytes)")) +
                       ", found " + std::to_string(rd.size.size()));
      return false;
    }
    if (kind == ResourceKind::Buffer) {
      const auto bytes =
          evaluate_count(rd.size[0], field + ".size", size_env(0), kMaxBufferBytes, "size");
      if (!bytes) return false;
      r.info.buffer_size = *bytes;
      return true;
    }
    const double max = kind == ResourceKind::Image2D ? kMaxImageSize2D : kMaxImageSize3D;
    const double w = options_.viewport_width;
    const double h = options_.viewport_height;
    uint32_t extent[3] = {1, 1, 1};
    const size_t dims = kind == ResourceKind::Image2D ? 2 : 3;
    for (size_t c = 0; c < dims; ++c) {
      // "viewport" alone means the width for x and the height for y.
      const ExprField& f = rd.size.size() == 1 ? rd.size[0] : rd.size[c];
      if (rd.size.size() == 1 && c > 0 && f.is_number) {
        extent[c] = extent[0];
        continue;
      }
      const auto v = evaluate_count(f, field + ".size", size_env(c == 1 ? h : w), max, "size");
      if (!v) return false;
      extent[c] = *v;
    }
    r.info.extent = {extent[0], extent[1], extent[2]};
    return true;
  }

  // `full_mips`: a full chain unless the graph gives 'mips' (a derived size may ask for it).
  bool resolve_mips_and_layers(const ResourceDesc& rd, CompiledResource& r,
                               const std::string& field, bool full_mips) {
    const ResourceKind kind = r.info.kind;
    if (kind == ResourceKind::Buffer) {
      for (const ExprField* f : {&rd.mips, &rd.layers}) {
        if (f->present) {
          diags_.error(f->loc, {}, field + (f == &rd.mips ? ".mips" : ".layers"),
                       "buffers have no mips or layers");
          return false;
        }
      }
      return true;
    }
    const VkExtent3D e = r.info.extent;
    uint32_t largest = std::max(e.width, e.height);
    if (kind != ResourceKind::Image2D)
      largest = std::max(largest, kind == ResourceKind::Clipmap ? e.width : e.depth);
    uint32_t full_chain = 1;
    while (largest > 1) {
      largest >>= 1;
      ++full_chain;
    }
    if (!rd.mips.present && full_mips) r.info.mip_levels = full_chain;
    if (rd.mips.present) {
      if (!rd.mips.is_number && rd.mips.text == "full") {
        r.info.mip_levels = full_chain;
      } else {
        const auto mips = evaluate_count(rd.mips, field + ".mips", size_env(0), 64, "mips");
        if (!mips) return false;
        if (*mips > full_chain) {
          diags_.error(rd.mips.loc, {}, field + ".mips",
                       "mip count " + std::to_string(*mips) + " exceeds the full chain of " +
                           std::to_string(full_chain) + " levels for this size");
          return false;
        }
        r.info.mip_levels = *mips;
      }
    }
    if (rd.layers.present) {
      if (kind != ResourceKind::Image2D) {
        diags_.error(rd.layers.loc, {}, field + ".layers", "only image2d resources have layers");
        return false;
      }
      const auto layers = evaluate_count(rd.layers, field + ".layers", size_env(0), 2048, "layers");
      if (!layers) return false;
      r.info.array_layers = *layers;
    }
    return true;
  }

  int resource_index(std::string_view name) const {
    for (size_t i = 0; i < desc_.resources.size(); ++i) {
      if (desc_.resources[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }

  std::vector<std::string> resource_names() const {
    std::vector<std::string> names;
    for (const ResourceDesc& r : desc_.resources) names.push_back(r.name);
    return names;
  }

  // ---- passes ---------------------------------------------------------------------------
  void resolve_passes() {
    std::map<std::string, const PassDesc*> first_by_name;
    std::vector<std::string> types;
    for (const PassTypeInfo* info : registry_.all()) types.push_back(info->type);
    for (const PassDesc& pd : passes_) {
      PassWork w;
      w.desc = &pd;
      bool unique = !pd.name.empty();
      if (unique) {
        auto [it, inserted] = first_by_name.emplace(pd.name, &pd);
        if (!inserted) {
          diags_.error(pd.name_loc, pd.name, "name",
                       "duplicate pass name (first defined at " +
                           where(it->second->name_loc, pd.name_loc) + ")");
          unique = false;
        }
      }
      if (!pd.type.empty()) {
        w.info = registry_.find(pd.type);
        if (!w.info) {
          diags_.error(pd.type_loc, pd.name, "type", "unknown pass type '" + pd.type + "'",
                       did_you_mean(pd.type, types));
        }
      }
      if (w.info) {
        resolve_params(w);
        apply_pass_overrides(w);
        derive_sizes(w);
        resolve_bindings(w);
      }
      resolve_when(w);
      w.usable = w.info && unique;
      work_.push_back(std::move(w));
    }
    bind_deferred_previous();
    report_never_sized();
  }

  // Scene features as in `when`, so that a pass can follow a condition that adds another pass
  // (vct.cone_trace's specular_layer with the specular pass's scene.has_glossy).
  ExpressionEnv param_env() const {
    ExpressionEnv env;
    env.params = graph_.parameters;
    env.identifiers = options_.scene_features;
    env.identifier_kind = "name";
    env.identifier_help = "pass parameters may use numbers, scene features and ${graph parameters}";
    return env;
  }

  void resolve_params(PassWork& w) {
    const PassDesc& pd = *w.desc;
    for (const ParamSpec& spec : w.info->params) {
      ParamValue v;
      v.number = spec.default_value;
      if (spec.type == ParamType::Enum) {
        const auto index = static_cast<size_t>(spec.default_value);
        v.text = index < spec.choices.size() ? spec.choices[index] : std::string();
      } else if (spec.type == ParamType::Bool) {
        v.text = spec.default_value != 0.0 ? "true" : "false";
      } else {
        v.text = format_number(spec.default_value);
      }
      w.params[spec.name] = v;
    }
    std::vector<std::string> names;
    for (const ParamSpec& spec : w.info->params) names.push_back(spec.name);
    for (const ParamSetting& setting : pd.params) {
      const std::string field = "params." + setting.name;
      const ParamSpec* spec = find_param(*w.info, setting.name);
      if (!spec) {
        diags_.error(setting.name_loc, pd.name, field,
                     "unknown parameter '" + setting.name + "' of pass type '" + pd.type + "'",
                     did_you_mean(setting.name, names));
        continue;
      }
      const json::Value& value = setting.value;
      w.param_locs[spec->name] = value.loc();
      try {
        if (spec->type == ParamType::Enum) {
          if (!value.is_string()) {
            throw GraphError(message_only(std::string("expected a choice name string, found ") +
                                          json::kind_name(value.kind())));
          }
          w.params[spec->name] = parse_param_value(*spec, field, value.as_string());
        } else if (value.is_string()) {
          const ExprField f{true, false, 0.0, value.as_string(), value.loc()};
          const std::optional<double> number = evaluate(f, pd.name, field, param_env());
          if (number) w.params[spec->name] = param_from_number(*spec, field, *number);
        } else if (spec->type == ParamType::Bool) {
          if (!value.is_bool()) {
            throw GraphError(message_only(std::string("expected true or false, found ") +
                                          json::kind_name(value.kind())));
          }
          w.params[spec->name] = param_from_number(*spec, field, value.as_bool() ? 1.0 : 0.0);
        } else {
          if (!value.is_number()) {
            throw GraphError(
                message_only(std::string("expected ") +
                             (spec->type == ParamType::Int ? "an integer" : "a number") +
                             ", found " + json::kind_name(value.kind())));
          }
          w.params[spec->name] = param_from_number(*spec, field, value.as_number());
        }
      } catch (const GraphError& e) {
        for (const Diagnostic& d : e.diagnostics()) {
          diags_.error(value.loc(), pd.name, field, d.message, d.hint);
        }
      }
    }
  }

  static const ParamSpec* find_param(const PassTypeInfo& info, std::string_view name) {
    for (const ParamSpec& spec : info.params) {
      if (spec.name == name) return &spec;
    }
    return nullptr;
  }

  static const SlotSpec* find_slot(const std::vector<SlotSpec>& slots, std::string_view name) {
    for (const SlotSpec& s : slots) {
      if (s.name == name) return &s;
    }
    return nullptr;
  }

  void resolve_bindings(PassWork& w) {
    const PassDesc& pd = *w.desc;
    for (const bool is_input : {true, false}) {
      const std::vector<BindingDesc>& bindings = is_input ? pd.inputs : pd.outputs;
      const std::vector<SlotSpec>& specs = is_input ? w.info->inputs : w.info->outputs;
      const std::vector<SlotSpec>& others = is_input ? w.info->outputs : w.info->inputs;
      const std::string section = is_input ? "in" : "out";
      // A slot written in the wrong section is reported there, not again as missing.
      std::set<std::string> mentioned;
      for (const BindingDesc& b : pd.inputs) mentioned.insert(b.slot);
      for (const BindingDesc& b : pd.outputs) mentioned.insert(b.slot);
      for (const BindingDesc& b : bindings) {
        const std::string field = section + "." + b.slot;
        const SlotSpec* spec = find_slot(specs, b.slot);
        if (!spec) {
          if (find_slot(others, b.slot)) {
            diags_.error(b.slot_loc, pd.name, field,
                         "'" + b.slot + "' is an " + (is_input ? "output" : "input") +
                             " slot of pass type '" + pd.type + "'; move it to \"" +
                             (is_input ? "out" : "in") + "\"");
          } else {
            std::vector<std::string> names;
            for (const SlotSpec& s : specs) names.push_back(s.name);
            diags_.error(b.slot_loc, pd.name, field,
                         "unknown " + std::string(is_input ? "input" : "output") + " slot '" +
                             b.slot + "' of pass type '" + pd.type + "' (it has " +
                             (names.empty() ? std::string("none") : quoted_list(names)) + ")",
                         did_you_mean(b.slot, names));
          }
          continue;
        }
        const int index = resource_index(b.resource);
        if (index < 0) {
          diags_.error(b.loc, pd.name, field, "unknown resource '" + b.resource + "'",
                       did_you_mean(b.resource, resource_names()));
          continue;
        }
        if (b.previous && !is_input) {
          diags_.error(b.loc, pd.name, field,
                       "'" + b.resource +
                           "@previous' is the previous frame's version: a pass may read it, "
                           "not write it");
          continue;
        }
        if (b.previous && sizing_[static_cast<size_t>(index)] == Sizing::ByWriter) {
          // A temporal loop reads the previous frame before the writer that sizes the
          // resource: bound once every pass has been seen (bind_deferred_previous).
          deferred_previous_.push_back({work_.size(), &b, spec, index, field});
          continue;
        }
        bind(w, b, is_input, spec, index, field);
      }
      for (const SlotSpec& s : specs) {
        if (!s.optional && !mentioned.count(s.name)) {
          diags_.error(pd.loc, pd.name, section + "." + s.name,
                       "missing required " + std::string(is_input ? "input" : "output") +
                           " slot '" + s.name + "'" + (s.doc.empty() ? "" : " (" + s.doc + ")"));
        }
      }
    }
  }

  // The resource "<name>@previous" that holds what `index` held at the end of the previous
  // frame: persistent, laid out alike, written only by the executor's copy as a frame ends.
  int history_twin(int index) {
    CompiledResource& original = graph_.resources[static_cast<size_t>(index)];
    if (original.history >= 0) return original.history;
    CompiledResource twin = original;
    twin.info.name += "@previous";
    twin.info.persistent = true;
    twin.derived_by.clear();
    twin.history_of = index;
    const int twin_index = static_cast<int>(graph_.resources.size());
    original.history = twin_index;
    graph_.resources.push_back(std::move(twin));
    resource_ok_.push_back(true);
    sizing_.push_back(Sizing::ByGraph);
    return twin_index;
  }

  // One slot bound to resource `index` (its "@previous" twin for b.previous), checked against
  // the slot's kinds, formats and mips.
  void bind(PassWork& w, const BindingDesc& b, bool is_input, const SlotSpec* spec, int index,
            const std::string& field) {
    const PassDesc& pd = *w.desc;
    if (!resource_ok_[static_cast<size_t>(index)]) {
      report_unsized(static_cast<size_t>(index), pd.name, b.loc, field);
      return;  // otherwise already reported
    }
    if (b.previous) index = history_twin(index);
    const ResourceInfo& info = graph_.resources[static_cast<size_t>(index)].info;
    if (!(spec->kinds & static_cast<uint32_t>(info.kind))) {
      diags_.error(b.loc, pd.name, field,
                   "resource '" + b.resource + "' is a " + kind_name(info.kind) +
                       ", but the slot accepts " + kinds_text(spec->kinds));
      return;
    }
    if (!spec->formats.empty() &&
        std::find(spec->formats.begin(), spec->formats.end(), info.format) == spec->formats.end()) {
      std::vector<std::string> accepted;
      for (VkFormat f : spec->formats) accepted.push_back(format_name(f));
      diags_.error(b.loc, pd.name, field,
                   "resource '" + b.resource + "' has format " + format_name(info.format) +
                       ", but the slot accepts " + quoted_list(accepted));
      return;
    }
    if (b.mip >= 0) {
      if (info.kind == ResourceKind::Buffer) {
        diags_.error(b.loc, pd.name, field,
                     "'@" + std::to_string(b.mip) + "' selects a mip level, but '" + b.resource +
                         "' is a buffer");
        return;
      }
      if (static_cast<uint32_t>(b.mip) >= info.mip_levels) {
        diags_.error(b.loc, pd.name, field,
                     "mip " + std::to_string(b.mip) + " is out of range: resource '" + b.resource +
                         "' has " + std::to_string(info.mip_levels) + " mip level(s) (0.." +
                         std::to_string(info.mip_levels - 1) + ")");
        return;
      }
    }
    SlotBinding sb;
    sb.slot = b.slot;
    sb.is_input = is_input;
    sb.spec = spec;
    sb.resource = index;
    sb.info = info;
    sb.info.mip = b.mip;
    sb.state = state_for(spec->access, spec->stages, info.kind, info.format);
    sb.loc = b.loc;
    check_layout_conflicts(w, sb, field);
    w.bindings.push_back(std::move(sb));
  }

  // The "@previous" reads of resources their writer sized after the reader.
  void bind_deferred_previous() {
    for (const DeferredPrevious& d : deferred_previous_) {
      PassWork& w = work_[d.work];
      if (sizing_[static_cast<size_t>(d.index)] == Sizing::ByWriter) continue;  // never sized
      bind(w, *d.binding, true, d.spec, d.index, d.field);
    }
  }

  // One pass may bind a resource to several slots only where the layouts agree.
  void check_layout_conflicts(const PassWork& w, const SlotBinding& b, const std::string& field) {
    for (const SlotBinding& other : w.bindings) {
      if (other.resource != b.resource || other.info.kind == ResourceKind::Buffer) continue;
      const bool overlap = other.info.mip < 0 || b.info.mip < 0 || other.info.mip == b.info.mip;
      if (overlap && other.state.layout != b.state.layout) {
        diags_.error(b.loc, w.desc->name, field,
                     "resource '" + b.info.name + "' is also bound to slot '" + other.slot +
                         "' as " + access_name(other.spec->access) +
                         "; one pass cannot use the same " + "mip as " +
                         access_name(b.spec->access) + " too (bind different mips with '@N')");
      }
    }
  }

  void resolve_when(PassWork& w) {
    const PassDesc& pd = *w.desc;
    if (pd.when.empty()) return;
    ExpressionEnv env;
    env.params = graph_.parameters;
    add_features(env);
    env.identifier_kind = "scene feature";
    ExprField f{true, false, 0.0, pd.when, pd.when_loc};
    if (pd.when == "true" || pd.when == "false") f.loc.column -= 1;  // a JSON boolean, no quote
    const std::optional<double> value = evaluate(f, pd.name, "when", env);
    if (!value) return;
    const std::vector<std::string> device_features = device_features_read(pd.when);
    if (!device_features.empty()) {
      graph_.device_conditions.push_back({pd.name, pd.when, device_features, *value != 0.0});
    }
    if (*value != 0.0) return;
    w.culled = "when '" + pd.when + "' is false for this scene";
    if (device_features.empty()) return;
    w.culled += graph_.device_queried
                    ? " and device" + (graph_.device_name.empty() ? std::string()
                                                                  : " '" + graph_.device_name + "'")
                    : " (compiled without a device: device features read as absent)";
  }

  // The device features an expression that evaluated without error reads.
  static std::vector<std::string> device_features_read(const std::string& text) {
    std::vector<std::string> features;
    for (const std::string& name : Expression::parse(text).identifiers()) {
      if (name.rfind("device.", 0) == 0) features.push_back(name);
    }
    return features;
  }

  // The overrides that name this pass's parameters, applied before its sizes are derived.
  void apply_pass_overrides(PassWork& w) {
    const std::string& name = w.desc->name;
    for (const auto& [key, text] : overrides_) {
      if (graph_.parameters.count(key)) continue;
      if (key.size() <= name.size() + 1 || key.compare(0, name.size(), name) != 0 ||
          key[name.size()] != '.') {
        continue;
      }
      const ParamSpec* spec = find_param(*w.info, key.substr(name.size() + 1));
      if (!spec) continue;
      matched_overrides_.insert(key);
      w.param_locs[spec->name] = override_loc(key, text);
      try {
        w.params[spec->name] = parse_param_value(*spec, key, text);
      } catch (const GraphError& e) {
        for (const Diagnostic& d : e.diagnostics()) {
          diags_.error(override_loc(key, text), name, key, d.message, d.hint);
        }
      }
    }
  }

  void report_unmatched_overrides() {
    for (const auto& [key, text] : overrides_) {
      if (graph_.parameters.count(key) || matched_overrides_.count(key)) continue;
      std::vector<std::string> candidates;
      for (const auto& [param, value] : graph_.parameters) candidates.push_back(param);
      for (const PassWork& w : work_) {
        if (!w.info) continue;
        for (const ParamSpec& spec : w.info->params) {
          candidates.push_back(w.desc->name + "." + spec.name);
        }
      }
      const std::string source = variant_locs_.count(key)
                                     ? "key '" + key + "' of variant '" + graph_.variant + "'"
                                     : "--set key '" + key + "'";
      diags_.error(override_loc(key, text), {}, key,
                   "unknown " + source + " (expected a graph parameter or 'pass.parameter')",
                   did_you_mean(key, candidates));
    }
  }

  // ---- pass type rules -------------------------------------------------------------------
  // A pass that skips a frame keeps what it wrote in an earlier one, which only a persistent
  // resource still holds.
  void check_skipping_passes_write_persistent() {
    for (const PassWork& w : work_) {
      if (!w.usable || !w.info->may_skip) continue;
      for (const SlotBinding& b : w.bindings) {
        if (!skip_leaves_undefined(b)) continue;
        const CompiledResource& r = graph_.resources[static_cast<size_t>(b.resource)];
        diags_.error(b.loc, w.desc->name, "out." + b.slot,
                     "pass type '" + w.desc->type +
                         "' may skip frames whose inputs did not change and keep what it wrote "
                         "earlier, but resource '" +
                         r.info.name + "' (" + where(r.loc, b.loc) +
                         ") is transient, so it would be undefined then: mark it "
                         "\"persistent\": true");
      }
    }
  }

  // The type's own checks of parameter and slot combinations, on every pass the file declares
  // (culled or not) whose parameters and bindings resolved without errors.
  void validate_passes() {
    for (const PassWork& w : work_) {
      if (!w.usable || !w.info->validate) continue;
      const PassDesc& pd = *w.desc;
      const bool all_bound = w.bindings.size() == pd.inputs.size() + pd.outputs.size();
      const bool reported = std::any_of(diags_.items().begin(), diags_.items().end(),
                                        [&](const Diagnostic& d) { return d.pass == pd.name; });
      if (!all_bound || reported) continue;
      CompiledPass declared;
      declared.name = pd.name;
      declared.type = pd.type;
      declared.type_info = w.info;
      declared.loc = pd.loc;
      declared.params = w.params;
      declared.bindings = w.bindings;
      for (Diagnostic& d : validate_pass(declared)) {
        d.loc = field_loc(w, d.field);
        diags_.add(std::move(d));
      }
    }
  }

  // Where a field of a pass is written: a parameter's value (or its --set), a slot's binding;
  // the pass itself for what the file leaves out.
  static SourceLoc field_loc(const PassWork& w, const std::string& field) {
    const size_t dot = field.find('.');
    const std::string section = field.substr(0, dot);
    const std::string name = dot == std::string::npos ? std::string() : field.substr(dot + 1);
    if (section == "params") {
      auto it = w.param_locs.find(name);
      if (it != w.param_locs.end()) return it->second;
    } else {
      for (const SlotBinding& b : w.bindings) {
        if (b.slot == name && b.is_input == (section == "in")) return b.loc;
      }
    }
    return w.desc->loc;
  }

  // A transient holds nothing when a frame starts, so the first pass using it must write it;
  // reading it there would silently carry it from the previous frame.
  void check_transients_written_first() {
    std::vector<bool> used(graph_.resources.size(), false);
    for (const CompiledPass& p : graph_.passes) {
      for (const SlotBinding& b : p.bindings) {
        if (b.resource < 0 || used[static_cast<size_t>(b.resource)]) continue;
        const CompiledResource& r = graph_.resources[static_cast<size_t>(b.resource)];
        if (r.info.persistent) continue;
        for (const SlotBinding& other : p.bindings) {
          if (other.resource != b.resource || !binding_reads(other) || other.spec->scratch)
            continue;
          diags_.error(other.loc, p.name, (other.is_input ? "in." : "out.") + other.slot,
                       "resource '" + r.info.name +
                           "' is transient, so it holds nothing when the frame starts, but its "
                           "first use here reads it (" +
                           access_name(other.spec->access) +
                           "): let an earlier pass write it, or mark it \"persistent\": true to "
                           "keep it across frames");
        }
      }
      for (const SlotBinding& b : p.bindings) {
        if (b.resource >= 0) used[static_cast<size_t>(b.resource)] = true;
      }
    }
  }

  // ---- whole-graph checks ---------------------------------------------------------------
  void check_outputs_declared() {
    for (const OutputDesc& o : desc_.outputs) {
      if (resource_index(o.resource) < 0) {
        diags_.error(o.loc, {}, "outputs." + o.name, "unknown output resource '" + o.resource + "'",
                     did_you_mean(o.resource, resource_names()));
      }
    }
  }

  std::vector<size_t> writers_of(int resource, const std::vector<bool>* live = nullptr) const {
    std::vector<size_t> writers;
    for (size_t i = 0; i < work_.size(); ++i) {
      if (!work_[i].usable || (live && !(*live)[i])) continue;
      for (const SlotBinding& b : work_[i].bindings) {
        if (b.resource == resource && binding_writes(b)) {
          writers.push_back(i);
          break;
        }
      }
    }
    return writers;
  }

  void check_reads_have_writers() {
    for (const PassWork& w : work_) {
      for (const SlotBinding& b : w.bindings) {
        if (!binding_reads(b) || !b.is_input) continue;
        const CompiledResource& r = graph_.resources[static_cast<size_t>(b.resource)];
        if (r.info.persistent) continue;
        // Counted from the file, so that a mistake in a writer's binding is reported once,
        // not again as a missing write.
        bool written = false;
        for (const PassDesc& other : passes_) {
          for (const BindingDesc& ob : other.outputs)
            written = written || ob.resource == r.info.name;
        }
        if (!written) {
          diags_.error(b.loc, w.desc->name, "in." + b.slot,
                       "resource '" + r.info.name +
                           "' is read before any write: no pass writes it (mark it \"persistent\": "
                           "true if it carries data from earlier frames)");
        }
      }
    }
  }

  struct Dependencies {
    std::vector<std::set<size_t>> order;  // must run after (all hazards)
    std::vector<std::set<size_t>> data;   // takes data from (for culling)
  };

  // Dependencies among the passes in `live`, decided by file order (see the graph docs):
  // a reader takes the last earlier write; a transient read with no earlier writer takes the
  // frame's final version; a persistent one the previous frame's.
  Dependencies dependencies(const std::vector<bool>& live) const {
    Dependencies deps;
    deps.order.resize(work_.size());
    deps.data.resize(work_.size());
    for (size_t r = 0; r < graph_.resources.size(); ++r) {
      struct Use {
        size_t pass;
        bool reads, writes;
      };
      std::vector<Use> uses;
      for (size_t i = 0; i < work_.size(); ++i) {
        if (!live[i]) continue;
        Use u{i, false, false};
        for (const SlotBinding& b : work_[i].bindings) {
          if (b.resource != static_cast<int>(r)) continue;
          u.reads = u.reads || binding_reads(b);
          u.writes = u.writes || binding_writes(b);
        }
        if (u.reads || u.writes) uses.push_back(u);
      }
      std::optional<size_t> final_writer;
      for (const Use& u : uses) {
        if (u.writes) final_writer = u.pass;
      }
      const bool persistent = graph_.resources[r].info.persistent;
      std::optional<size_t> last_writer;
      std::vector<size_t> readers;
      for (const Use& u : uses) {
        if (u.reads) {
          if (last_writer) {
            deps.order[u.pass].insert(*last_writer);
            deps.data[u.pass].insert(*last_writer);
            readers.push_back(u.pass);
          } else if (final_writer && *final_writer != u.pass && !persistent && !u.writes) {
            deps.order[u.pass].insert(*final_writer);
            deps.data[u.pass].insert(*final_writer);
          } else {
            // Previous frame's contents: the final writer feeds it, one frame later.
            if (final_writer && *final_writer != u.pass) deps.data[u.pass].insert(*final_writer);
            readers.push_back(u.pass);
          }
        }
        if (u.writes) {
          if (last_writer) {
            deps.order[u.pass].insert(*last_writer);
            deps.data[u.pass].insert(*last_writer);
          }
          for (size_t reader : readers) {
            if (reader != u.pass) deps.order[u.pass].insert(reader);
          }
          readers.clear();
          last_writer = u.pass;
        }
      }
    }
    return deps;
  }

  // Kahn's algorithm, ties broken by file order. Returns the passes left over on a cycle.
  std::vector<size_t> topological_order(const std::vector<bool>& live, const Dependencies& deps,
                                        std::vector<size_t>& leftover) const {
    std::vector<size_t> pending(work_.size(), 0);
    std::vector<std::vector<size_t>> dependents(work_.size());
    std::priority_queue<size_t, std::vector<size_t>, std::greater<>> ready;
    for (size_t i = 0; i < work_.size(); ++i) {
      if (!live[i]) continue;
      pending[i] = deps.order[i].size();
      for (size_t d : deps.order[i]) dependents[d].push_back(i);
      if (pending[i] == 0) ready.push(i);
    }
    std::vector<size_t> order;
    while (!ready.empty()) {
      const size_t i = ready.top();
      ready.pop();
      order.push_back(i);
      for (size_t next : dependents[i]) {
        if (--pending[next] == 0) ready.push(next);
      }
    }
    leftover.clear();
    for (size_t i = 0; i < work_.size(); ++i) {
      if (live[i] && pending[i] > 0) leftover.push_back(i);
    }
    return order;
  }

  void check_cycles() {
    std::vector<bool> usable(work_.size());
    for (size_t i = 0; i < work_.size(); ++i) usable[i] = work_[i].usable;
    const Dependencies deps = dependencies(usable);
    std::vector<size_t> leftover;
    topological_order(usable, deps, leftover);
    if (leftover.empty()) return;
    // Walk dependencies inside the leftover set from its first pass until one repeats.
    std::set<size_t> left(leftover.begin(), leftover.end());
    std::vector<size_t> path{leftover.front()};
    while (true) {
      size_t next = 0;
      for (size_t d : deps.order[path.back()]) {
        if (left.count(d)) {
          next = d;
          break;
        }
      }
      auto seen = std::find(path.begin(), path.end(), next);
      if (seen != path.end()) {
        path.erase(path.begin(), seen);
        path.push_back(next);
        break;
      }
      path.push_back(next);
    }
    // path: a → b means a must run after b; print in execution direction.
    std::reverse(path.begin(), path.end());
    std::string text;
    for (size_t i : path) text += (text.empty() ? "'" : " -> '") + work_[i].desc->name + "'";
    const PassDesc& first = *work_[path.front()].desc;
    diags_.error(first.loc, first.name, {}, "dependency cycle between passes: " + text);
  }

  // ---- culling --------------------------------------------------------------------------
  void cull() {
    std::vector<bool> live(work_.size());
    for (size_t i = 0; i < work_.size(); ++i) live[i] = work_[i].usable && work_[i].culled.empty();
    // Inputs whose every writer is culled: required ones cull the reader, optional ones unbind.
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t i = 0; i < work_.size(); ++i) {
        if (!live[i]) continue;
        for (SlotBinding& b : work_[i].bindings) {
          if (!b.is_input || b.resource < 0) continue;
          std::vector<size_t> all = writers_of(b.resource);
          all.erase(std::remove(all.begin(), all.end(), i), all.end());
          if (all.empty()) continue;
          if (std::any_of(all.begin(), all.end(), [&](size_t j) { return live[j]; })) continue;
          if (b.spec->optional) {
            b.resource = -1;
            continue;
          }
          std::vector<std::string> names;
          for (size_t j : all) names.push_back(work_[j].desc->name);
          work_[i].culled = "input '" + b.slot + "' is only written by culled pass" +
                            (names.size() > 1 ? "es " : " ") + quoted_list(names);
          live[i] = false;
          changed = true;
          break;
        }
      }
    }
    // Keep what an output needs.
    const Dependencies deps = dependencies(live);
    std::vector<bool> needed(work_.size(), false);
    std::vector<size_t> stack;
    for (const OutputDesc& o : desc_.outputs) {
      for (size_t j : writers_of(resource_index(o.resource), &live)) stack.push_back(j);
    }
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      if (needed[i]) continue;
      needed[i] = true;
      for (size_t d : deps.data[i]) stack.push_back(d);
      // A reader of the previous frame's version needs what writes the current one (without
      // running after it: the copy happens as the frame ends).
      for (const SlotBinding& b : work_[i].bindings) {
        if (!b.is_input || b.resource < 0) continue;
        const int original = graph_.resources[static_cast<size_t>(b.resource)].history_of;
        if (original >= 0) {
          for (size_t j : writers_of(original, &live)) stack.push_back(j);
        }
      }
    }
    for (size_t i = 0; i < work_.size(); ++i) {
      if (live[i] && !needed[i]) {
        work_[i].culled = "no output depends on it";
        live[i] = false;
      }
    }
    live_ = live;
    for (size_t i = 0; i < work_.size(); ++i) {
      if (!work_[i].usable || live[i]) continue;
      const PassDesc& pd = *work_[i].desc;
      graph_.culled.push_back(CulledPass{pd.name, pd.type, i, pd.loc, work_[i].culled});
    }
  }

  void check_outputs_written() {
    for (const OutputDesc& o : desc_.outputs) {
      const int r = resource_index(o.resource);
      graph_.outputs[o.name] = r;
      graph_.resources[static_cast<size_t>(r)].is_output = true;
      if (!writers_of(r, &live_).empty()) continue;
      const std::vector<size_t> all = writers_of(r);
      if (all.empty()) {
        diags_.error(o.loc, {}, "outputs." + o.name,
                     "output resource '" + o.resource + "' is never written by any pass");
        continue;
      }
      std::string why;
      for (size_t j : all) {
        why +=
            (why.empty() ? "" : "; ") + ("pass '" + work_[j].desc->name + "': " + work_[j].culled);
      }
      diags_.error(o.loc, {}, "outputs." + o.name,
                   "output resource '" + o.resource +
                       "' has no writer left: every pass writing it was culled (" + why + ")");
    }
  }

  void schedule() {
    const Dependencies deps = dependencies(live_);
    std::vector<size_t> leftover;
    const std::vector<size_t> order = topological_order(live_, deps, leftover);
    std::map<size_t, size_t> schedule_index;
    for (size_t s = 0; s < order.size(); ++s) schedule_index[order[s]] = s;
    for (size_t s = 0; s < order.size(); ++s) {
      PassWork& w = work_[order[s]];
      CompiledPass p;
      p.name = w.desc->name;
      p.type = w.desc->type;
      p.type_info = w.info;
      p.file_index = order[s];
      p.loc = w.desc->loc;
      p.params = std::move(w.params);
      p.bindings = std::move(w.bindings);
      for (size_t d : deps.order[order[s]]) p.depends_on.push_back(schedule_index.at(d));
      std::sort(p.depends_on.begin(), p.depends_on.end());
      graph_.passes.push_back(std::move(p));
    }
  }

  const GraphDesc& desc_;
  std::map<std::string, std::string> overrides_;   // the variant's and the caller's
  std::map<std::string, SourceLoc> variant_locs_;  // overrides the variant set, by key
  std::set<std::string> matched_overrides_;        // pass parameter overrides applied
  std::vector<PassDesc> passes_;                   // desc_.passes with repeats expanded
  enum class Sizing { ByGraph, ByWriter, Derived, Failed };
  std::vector<Sizing> sizing_;  // per resource
  struct DeferredPrevious {
    size_t work;  // index into work_
    const BindingDesc* binding;
    const SlotSpec* spec;
    int index;  // the resource whose previous version is read
    std::string field;
  };
  std::vector<DeferredPrevious> deferred_previous_;
  const Registry& registry_;
  const CompileOptions& options_;
  DiagnosticList diags_;
  CompiledGraph graph_;
  std::vector<bool> resource_ok_;
  std::vector<PassWork> work_;
  std::vector<bool> live_;
};

}  // namespace

CompiledGraph compile(const GraphDesc& desc, const Registry& registry,
                      const CompileOptions& options) {
  return Compiler(desc, registry, options).run();
}

}  // namespace voxgi::graph
