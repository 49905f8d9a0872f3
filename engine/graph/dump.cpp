#include "engine/graph/dump.hpp"

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "engine/graph/resource_plan.hpp"

namespace voxgi::graph {

using Json = nlohmann::json;

std::string layout_name(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED:
      return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL:
      return "GENERAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
      return "COLOR_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL:
      return "DEPTH_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
      return "DEPTH_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
      return "SHADER_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL:
      return "TRANSFER_SRC_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL:
      return "TRANSFER_DST_OPTIMAL";
    default:
      return "layout" + std::to_string(layout);
  }
}

namespace {

template <typename Flags>
std::string flags_text(Flags flags, std::initializer_list<std::pair<Flags, const char*>> names) {
  if (flags == 0) return "NONE";
  std::string text;
  for (const auto& [bit, name] : names) {
    if ((flags & bit) == bit) {
      text += (text.empty() ? "" : "|");
      text += name;
      flags &= ~bit;
    }
  }
  if (flags != 0) text += (text.empty() ? "0x" : "|0x") + std::to_string(flags);
  return text;
}

std::string mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

std::string size_text(const ResourceInfo& info) {
  if (info.kind == ResourceKind::Buffer) return std::to_string(info.buffer_size) + " bytes";
  std::string text = std::to_string(info.extent.width) + "x" + std::to_string(info.extent.height);
  if (info.kind != ResourceKind::Image2D) text += "x" + std::to_string(info.extent.depth);
  if (info.kind == ResourceKind::Clipmap) {
    text += " (" + std::to_string(info.clipmap_levels) + " levels of " +
            std::to_string(info.extent.width) + "^3)";
  }
  return text;
}

std::string slot_target(const CompiledGraph& g, const SlotBinding& b) {
  if (b.resource < 0) return "(unbound)";
  std::string text = g.resources[static_cast<size_t>(b.resource)].info.name;
  if (b.info.mip >= 0) text += "@" + std::to_string(b.info.mip);
  return text;
}

std::string barrier_text(const CompiledGraph& g, const Barrier& b) {
  std::string text;
  if (b.is_global) {
    text = "memory";
  } else {
    text = g.resources[static_cast<size_t>(b.resource)].info.name;
    if (!b.is_buffer) {
      text += " mips " + std::to_string(b.base_mip) + ".." +
              std::to_string(b.base_mip + b.mip_count - 1) + " " + layout_name(b.old_layout) +
              " -> " + layout_name(b.new_layout);
    }
  }
  text += " [" + stages_text(b.src_stages) + " " + access_text(b.src_access) + " => " +
          stages_text(b.dst_stages) + " " + access_text(b.dst_access) + "]";
  return text;
}

Json param_json(const ParamValue& v) {
  return Json{{"number", v.number}, {"text", v.text}};
}

Json barrier_json(const CompiledGraph& g, const Barrier& b) {
  Json j;
  j["resource"] =
      b.is_global ? Json(nullptr) : Json(g.resources[static_cast<size_t>(b.resource)].info.name);
  j["kind"] = b.is_global ? "memory" : b.is_buffer ? "buffer" : "image";
  if (!b.is_global && !b.is_buffer) {
    j["base_mip"] = b.base_mip;
    j["mip_count"] = b.mip_count;
    j["old_layout"] = layout_name(b.old_layout);
    j["new_layout"] = layout_name(b.new_layout);
  }
  j["src_stages"] = stages_text(b.src_stages);
  j["src_access"] = access_text(b.src_access);
  j["dst_stages"] = stages_text(b.dst_stages);
  j["dst_access"] = access_text(b.dst_access);
  return j;
}

Json loc_json(const SourceLoc& loc) {
  Json j{{"file", loc.file}, {"line", loc.line}, {"column", loc.column}};
  if (!loc.included_from.empty()) j["included_from"] = loc.included_from;
  return j;
}

// The frame of a static scene: every pass that may skip does, right after a frame in which
// all passes ran.
struct SkippingFrame {
  size_t all_passes_barriers = 0;     // in a frame in which every pass runs
  std::vector<std::string> skipping;  // pass names
  FrameBarriers barriers;
};

SkippingFrame skipping_frame(const CompiledGraph& g) {
  SkippingFrame frame;
  std::vector<bool> skipped(g.passes.size(), false);
  for (size_t s = 0; s < g.passes.size(); ++s) {
    skipped[s] = g.passes[s].type_info && g.passes[s].type_info->may_skip;
    if (skipped[s]) frame.skipping.push_back(g.passes[s].name);
  }
  FrameSync sync(g);
  frame.all_passes_barriers = barrier_count(sync.all_passes_frame());
  frame.barriers = sync.plan(skipped);
  return frame;
}

std::string dot_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string stages_text(VkPipelineStageFlags2 stages) {
  return flags_text<VkPipelineStageFlags2>(
      stages, {{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "ALL_COMMANDS"},
               {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "VERTEX_SHADER"},
               {VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT, "GEOMETRY_SHADER"},
               {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT_SHADER"},
               {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "EARLY_FRAGMENT_TESTS"},
               {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "LATE_FRAGMENT_TESTS"},
               {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_ATTACHMENT_OUTPUT"},
               {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE_SHADER"},
               {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "ALL_TRANSFER"}});
}

std::string access_text(VkAccessFlags2 access) {
  return flags_text<VkAccessFlags2>(
      access, {{VK_ACCESS_2_MEMORY_READ_BIT, "MEMORY_READ"},
               {VK_ACCESS_2_MEMORY_WRITE_BIT, "MEMORY_WRITE"},
               {VK_ACCESS_2_UNIFORM_READ_BIT, "UNIFORM_READ"},
               {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SHADER_SAMPLED_READ"},
               {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "SHADER_STORAGE_READ"},
               {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "SHADER_STORAGE_WRITE"},
               {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_ATTACHMENT_READ"},
               {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_ATTACHMENT_WRITE"},
               {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "DEPTH_STENCIL_ATTACHMENT_READ"},
               {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "DEPTH_STENCIL_ATTACHMENT_WRITE"},
               {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
               {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"}});
}

std::string explain(const CompiledGraph& g) {
  std::ostringstream out;
  out << "graph '" << g.name << "' (" << g.file << "), viewport " << g.viewport_width << "x"
      << g.viewport_height << (g.full_barriers ? ", full barriers" : "") << "\n";
  if (!g.variants.empty()) {
    out << "variant: "
        << (g.variant.empty() ? std::string("none (the file as written)") : g.variant)
        << "; the file's variants:";
    for (const std::string& v : g.variants) out << " " << v;
    out << " (--variant NAME)\n";
  }
  if (!g.parameters.empty()) {
    out << "\nparameters:\n";
    for (const auto& [name, value] : g.parameters) {
      out << "  " << name << " = " << format_number(value) << "\n";
    }
  }
  out << "\ndevice features ("
      << (g.device_queried ? (g.device_name.empty() ? std::string("of the device")
                                                    : "of '" + g.device_name + "'")
                           : std::string("no device: every feature reads as absent; "
                                         "--device D queries one"))
      << "):\n";
  for (const auto& [name, value] : g.device_features) {
    out << "  " << name << " = " << (value != 0.0 ? "true" : "false") << "\n";
  }
  if (!g.device_conditions.empty()) {
    out << "conditions decided by device features:\n";
    for (const DeviceCondition& c : g.device_conditions) {
      std::string features;
      for (const std::string& f : c.features) features += (features.empty() ? "" : ", ") + f;
      out << "  " << c.pass << ": when '" << c.when << "' is " << (c.value ? "true" : "false")
          << " (reads " << features << ")" << (c.value ? "" : ": pass culled") << "\n";
    }
  }
  out << "\nschedule (" << g.passes.size() << " passes):\n";
  if (!g.frame_start.empty()) {
    out << "  frame start:\n";
    for (const Barrier& b : g.frame_start) out << "      barrier " << barrier_text(g, b) << "\n";
  }
  for (size_t s = 0; s < g.passes.size(); ++s) {
    const CompiledPass& p = g.passes[s];
    out << "  " << s + 1 << ". " << p.name << " (" << p.type << ")\n";
    for (const Barrier& b : p.barriers) out << "      barrier " << barrier_text(g, b) << "\n";
    for (const SlotBinding& b : p.bindings) {
      out << "      " << (b.is_input ? "reads  " : "writes ") << b.slot << " <- "
          << slot_target(g, b) << " as " << access_name(b.spec->access) << "\n";
    }
    for (const auto& [name, value] : p.params)
      out << "      param " << name << " = " << value.text << "\n";
  }
  if (!g.history_copies.empty()) {
    out << "  previous-frame copies:\n";
    for (const Barrier& b : g.history_barriers)
      out << "      barrier " << barrier_text(g, b) << "\n";
    for (const HistoryCopy& c : g.history_copies) {
      out << "      copy " << g.resources[static_cast<size_t>(c.from)].info.name << " -> "
          << g.resources[static_cast<size_t>(c.to)].info.name << "\n";
    }
  }
  if (!g.frame_end.empty()) {
    out << "  frame end:\n";
    for (const Barrier& b : g.frame_end) out << "      barrier " << barrier_text(g, b) << "\n";
  }
  const SkippingFrame skipping = skipping_frame(g);
  out << "barriers per frame: " << skipping.all_passes_barriers << "\n";
  if (!skipping.skipping.empty()) {
    std::string names;
    for (const std::string& n : skipping.skipping) names += (names.empty() ? "" : ", ") + n;
    out << "\nframe in which " << names
        << " skip (a static scene): " << barrier_count(skipping.barriers) << " barriers\n";
    auto list = [&](const char* where, const std::vector<Barrier>& barriers) {
      if (barriers.empty()) return;
      out << "  " << where << ":\n";
      for (const Barrier& b : barriers) out << "      barrier " << barrier_text(g, b) << "\n";
    };
    list("frame start", skipping.barriers.frame_start);
    for (size_t s = 0; s < g.passes.size(); ++s)
      list(g.passes[s].name.c_str(), skipping.barriers.passes[s]);
    list("previous-frame copies", skipping.barriers.history);
    list("frame end", skipping.barriers.frame_end);
  }
  out << "\nculled (" << g.culled.size() << "):\n";
  for (const CulledPass& c : g.culled) {
    out << "  " << c.name << " (" << c.type << "): " << c.reason << "\n";
  }
  out << "\noutputs:\n";
  for (const auto& [name, r] : g.outputs) {
    out << "  " << name << " -> " << g.resources[static_cast<size_t>(r)].info.name << "\n";
  }
  out << "\nresources:\n";
  for (const CompiledResource& r : g.resources) {
    const ResourceInfo& i = r.info;
    out << "  " << i.name << ": " << kind_name(i.kind);
    if (i.kind != ResourceKind::Buffer) out << " " << format_name(i.format);
    out << " " << size_text(i);
    if (i.kind != ResourceKind::Buffer)
      out << ", mips " << i.mip_levels << ", layers " << i.array_layers;
    if (i.persistent) out << ", persistent";
    if (!r.derived_by.empty()) out << ", sized by pass '" << r.derived_by << "'";
    if (r.history_of >= 0) {
      out << ", the previous frame's '" << g.resources[static_cast<size_t>(r.history_of)].info.name
          << "' (copied as each frame ends)";
    }
    if (r.physical < 0) {
      out << ", unused\n";
      continue;
    }
    out << ", passes " << r.first_pass + 1 << ".."
        << (r.last_pass >= static_cast<int>(g.passes.size()) ? std::string("end")
                                                             : std::to_string(r.last_pass + 1))
        << ", physical #" << r.physical;
    const PhysicalResource& p = g.physical[static_cast<size_t>(r.physical)];
    if (p.resources.size() > 1) {
      out << " (shared with";
      for (int other : p.resources) {
        if (g.resources[static_cast<size_t>(other)].info.name != i.name)
          out << " " << g.resources[static_cast<size_t>(other)].info.name;
      }
      out << ")";
    }
    if (p.memory_block >= 0) out << ", memory block " << p.memory_block;
    out << ", " << mib(r.bytes) << "\n";
  }
  uint64_t identical_only = 0;  // sharing only between identical descriptions
  for (const PhysicalResource& p : g.physical) identical_only += p.bytes;
  out << "\nmemory: " << mib(g.total_bytes) << " in " << g.physical.size() << " allocations, "
      << g.memory_blocks.size() << " memory blocks taken in turn by transients ("
      << mib(identical_only) << " sharing only identical transients, "
      << mib(g.total_bytes_unshared) << " without sharing)\n";
  for (size_t b = 0; b < g.memory_blocks.size(); ++b) {
    out << "  block " << b << ", " << mib(g.memory_blocks[b].bytes) << ":";
    for (int p : g.memory_blocks[b].physical) {
      out << " "
          << g.resources[static_cast<size_t>(g.physical[static_cast<size_t>(p)].resources[0])]
                 .info.name;
    }
    out << "\n";
  }
  return out.str();
}

Json desc_to_json(const GraphDesc& d) {
  Json j;
  j["file"] = d.file;
  j["name"] = d.name;
  j["doc"] = d.doc;
  j["parameters"] = Json::object();
  for (const GraphParam& p : d.parameters) {
    j["parameters"][p.name] = p.is_bool ? Json(p.value != 0.0) : Json(p.value);
  }
  auto field = [](const ExprField& f) { return f.present ? Json(f.text) : Json(nullptr); };
  j["resources"] = Json::array();
  for (const ResourceDesc& r : d.resources) {
    Json size = Json::array();
    for (const ExprField& f : r.size) size.push_back(f.text);
    j["resources"].push_back(Json{{"name", r.name},
                                  {"type", r.type},
                                  {"format", r.format},
                                  {"size", size},
                                  {"mips", field(r.mips)},
                                  {"layers", field(r.layers)},
                                  {"resolution", field(r.resolution)},
                                  {"levels", field(r.levels)},
                                  {"persistent", r.persistent},
                                  {"loc", loc_json(r.loc)}});
  }
  j["passes"] = Json::array();
  for (const PassDesc& p : d.passes) {
    if (p.repeat) {
      j["passes"].push_back(Json{{"repeat", p.repeat->count.text},
                                 {"index", p.repeat->index},
                                 {"from", p.repeat->from},
                                 {"passes", p.repeat->passes.size()},
                                 {"loc", loc_json(p.loc)}});
      continue;
    }
    Json pass{{"name", p.name}, {"type", p.type}, {"when", p.when}, {"loc", loc_json(p.loc)}};
    for (const auto& [section, list] : {std::pair{"in", &p.inputs}, std::pair{"out", &p.outputs}}) {
      pass[section] = Json::object();
      for (const BindingDesc& b : *list) {
        std::string target = b.resource;
        if (b.mip >= 0) target.append("@").append(std::to_string(b.mip));
        pass[section][b.slot] = target;
      }
    }
    pass["params"] = Json::object();
    for (const ParamSetting& s : p.params) {
      const json::Value& v = s.value;
      pass["params"][s.name] = v.is_bool()     ? Json(v.as_bool())
                               : v.is_number() ? Json(v.as_number())
                               : v.is_string() ? Json(v.as_string())
                                               : Json(json::kind_name(v.kind()));
    }
    j["passes"].push_back(pass);
  }
  j["outputs"] = Json::object();
  for (const OutputDesc& o : d.outputs) j["outputs"][o.name] = o.resource;
  return j;
}

Json resolved_to_json(const CompiledGraph& g) {
  Json j;
  j["parameters"] = g.parameters;
  j["variant"] = g.variant;
  j["variants"] = g.variants;
  j["device"] = {
      {"queried", g.device_queried}, {"name", g.device_name}, {"features", g.device_features}};
  j["device_conditions"] = Json::array();
  for (const DeviceCondition& c : g.device_conditions) {
    j["device_conditions"].push_back(
        {{"pass", c.pass}, {"when", c.when}, {"features", c.features}, {"value", c.value}});
  }
  j["passes"] = Json::array();
  for (const CompiledPass& p : g.passes) {
    Json pass{
        {"name", p.name}, {"type", p.type}, {"params", Json::object()}, {"slots", Json::array()}};
    for (const auto& [name, value] : p.params) pass["params"][name] = param_json(value);
    for (const SlotBinding& b : p.bindings) {
      pass["slots"].push_back(Json{{"slot", b.slot},
                                   {"direction", b.is_input ? "in" : "out"},
                                   {"resource", slot_target(g, b)},
                                   {"access", access_name(b.spec->access)},
                                   {"layout", layout_name(b.state.layout)},
                                   {"stages", stages_text(b.state.stages)},
                                   {"access_flags", access_text(b.state.access)}});
    }
    j["passes"].push_back(pass);
  }
  return j;
}

Json culled_to_json(const CompiledGraph& g) {
  Json j = Json::array();
  for (const CulledPass& c : g.culled) {
    j.push_back(
        Json{{"name", c.name}, {"type", c.type}, {"reason", c.reason}, {"loc", loc_json(c.loc)}});
  }
  return j;
}

Json schedule_to_json(const CompiledGraph& g) {
  Json j = Json::array();
  for (size_t s = 0; s < g.passes.size(); ++s) {
    const CompiledPass& p = g.passes[s];
    Json deps = Json::array();
    for (size_t d : p.depends_on) deps.push_back(g.passes[d].name);
    j.push_back(Json{{"index", s},
                     {"name", p.name},
                     {"type", p.type},
                     {"file_index", p.file_index},
                     {"depends_on", deps}});
  }
  return j;
}

Json barriers_to_json(const CompiledGraph& g) {
  Json j;
  j["full_barriers"] = g.full_barriers;
  j["frame_start"] = Json::array();
  for (const Barrier& b : g.frame_start) j["frame_start"].push_back(barrier_json(g, b));
  j["passes"] = Json::array();
  for (const CompiledPass& p : g.passes) {
    Json list = Json::array();
    for (const Barrier& b : p.barriers) list.push_back(barrier_json(g, b));
    j["passes"].push_back(Json{{"pass", p.name}, {"barriers", list}});
  }
  j["history"] = Json::array();
  for (const Barrier& b : g.history_barriers) j["history"].push_back(barrier_json(g, b));
  j["frame_end"] = Json::array();
  for (const Barrier& b : g.frame_end) j["frame_end"].push_back(barrier_json(g, b));
  const SkippingFrame skipping = skipping_frame(g);
  j["per_frame"] = skipping.all_passes_barriers;
  j["skipping_frame"] =
      Json{{"skipping", skipping.skipping}, {"barriers", barrier_count(skipping.barriers)}};
  return j;
}

Json resources_to_json(const CompiledGraph& g) {
  Json j;
  j["resources"] = Json::array();
  for (const CompiledResource& r : g.resources) {
    const ResourceInfo& i = r.info;
    Json end = Json::array();
    for (const ResourceState& s : r.end_state) end.push_back(layout_name(s.layout));
    j["resources"].push_back(Json{{"name", i.name},
                                  {"kind", kind_name(i.kind)},
                                  {"format", format_name(i.format)},
                                  {"extent", {i.extent.width, i.extent.height, i.extent.depth}},
                                  {"buffer_size", i.buffer_size},
                                  {"mips", i.mip_levels},
                                  {"layers", i.array_layers},
                                  {"clipmap_levels", i.clipmap_levels},
                                  {"persistent", i.persistent},
                                  {"output", r.is_output},
                                  {"carries_contents", r.carries_contents},
                                  {"first_pass", r.first_pass},
                                  {"last_pass", r.last_pass},
                                  {"physical", r.physical},
                                  {"image_usage", r.image_usage},
                                  {"buffer_usage", r.buffer_usage},
                                  {"bytes", r.bytes},
                                  {"sized_by", r.derived_by},
                                  {"end_layouts", end}});
  }
  j["physical"] = Json::array();
  for (const PhysicalResource& p : g.physical) {
    Json names = Json::array();
    for (int r : p.resources) names.push_back(g.resources[static_cast<size_t>(r)].info.name);
    j["physical"].push_back(
        Json{{"resources", names}, {"bytes", p.bytes}, {"memory_block", p.memory_block}});
  }
  j["total_bytes"] = g.total_bytes;
  j["memory_blocks"] = Json::array();
  for (const MemoryBlock& block : g.memory_blocks) {
    j["memory_blocks"].push_back({{"physical", block.physical}, {"bytes", block.bytes}});
  }
  j["total_bytes_unshared"] = g.total_bytes_unshared;
  return j;
}

std::string to_dot(const CompiledGraph& g) {
  std::ostringstream out;
  out << "digraph \"" << dot_escape(g.name) << "\" {\n  rankdir=LR;\n";
  std::set<int> used;
  for (const CompiledPass& p : g.passes) {
    for (const SlotBinding& b : p.bindings) {
      if (b.resource >= 0) used.insert(b.resource);
    }
  }
  for (int r : used) {
    const CompiledResource& res = g.resources[static_cast<size_t>(r)];
    out << "  \"r:" << dot_escape(res.info.name) << "\" [shape=ellipse, label=\""
        << dot_escape(res.info.name) << "\\n"
        << kind_name(res.info.kind) << " "
        << (res.info.kind == ResourceKind::Buffer ? "" : format_name(res.info.format)) << "\""
        << (res.info.persistent ? ", style=bold" : "") << "];\n";
  }
  for (size_t s = 0; s < g.passes.size(); ++s) {
    const CompiledPass& p = g.passes[s];
    out << "  \"p:" << dot_escape(p.name) << "\" [shape=box, label=\"" << s + 1 << ". "
        << dot_escape(p.name) << "\\n"
        << dot_escape(p.type) << "\"];\n";
    for (const SlotBinding& b : p.bindings) {
      if (b.resource < 0) continue;
      const std::string r =
          "\"r:" + dot_escape(g.resources[static_cast<size_t>(b.resource)].info.name) + "\"";
      std::string label = dot_escape(b.slot);
      if (b.info.mip >= 0) label.append("@").append(std::to_string(b.info.mip));
      if (b.is_input) {
        out << "  " << r << " -> \"p:" << dot_escape(p.name) << "\" [label=\"" << label << "\"];\n";
      } else {
        out << "  \"p:" << dot_escape(p.name) << "\" -> " << r << " [label=\"" << label << "\"];\n";
      }
    }
  }
  for (const CulledPass& c : g.culled) {
    out << "  \"p:" << dot_escape(c.name)
        << "\" [shape=box, style=dashed, color=grey, fontcolor=grey, "
        << "label=\"" << dot_escape(c.name) << "\\n"
        << dot_escape(c.type) << "\", tooltip=\"" << dot_escape(c.reason) << "\"];\n";
  }
  for (const auto& [name, r] : g.outputs) {
    out << "  \"o:" << dot_escape(name) << "\" [shape=doubleoctagon, label=\"" << dot_escape(name)
        << "\"];\n  \"r:" << dot_escape(g.resources[static_cast<size_t>(r)].info.name)
        << "\" -> \"o:" << dot_escape(name) << "\";\n";
  }
  out << "}\n";
  return out.str();
}

void dump_phases(const GraphDesc& desc, const CompiledGraph& graph,
                 const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error("cannot create dump directory " + dir.string() + ": " + ec.message());
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream out(dir / name, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + (dir / name).string());
  };
  write("1-parsed.json", desc_to_json(desc).dump(2));
  write("2-resolved.json", resolved_to_json(graph).dump(2));
  write("3-culled.json", culled_to_json(graph).dump(2));
  write("4-schedule.json", schedule_to_json(graph).dump(2));
  write("5-barriers.json", barriers_to_json(graph).dump(2));
  write("6-resources.json", resources_to_json(graph).dump(2));
  write("graph.dot", to_dot(graph));
}

}  // namespace voxgi::graph
