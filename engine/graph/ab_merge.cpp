#include "engine/graph/ab_merge.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <set>

#include "engine/graph/resource_plan.hpp"

namespace voxgi::graph {
namespace {

using Json = nlohmann::json;

// A resource as a graph file declares it, with its compiled (literal) description.
Json resource_json(const ResourceInfo& info) {
  Json j;
  j["type"] = kind_name(info.kind);
  if (info.kind != ResourceKind::Buffer) {
    j["format"] = format_name(info.format);
    j["mips"] = info.mip_levels;
  }
  switch (info.kind) {
    case ResourceKind::Buffer:
      j["size"] = info.buffer_size;
      break;
    case ResourceKind::Image2D:
      j["size"] = {info.extent.width, info.extent.height};
      j["layers"] = info.array_layers;
      break;
    case ResourceKind::Image3D:
      j["size"] = {info.extent.width, info.extent.height, info.extent.depth};
      break;
    case ResourceKind::Clipmap:
      j["resolution"] = info.extent.width;
      j["levels"] = info.clipmap_levels;
      break;
  }
  j["persistent"] = info.persistent;
  return j;
}

Json param_json(const ParamSpec& spec, const ParamValue& value) {
  switch (spec.type) {
    case ParamType::Bool:
      return value.number != 0.0;
    case ParamType::Int:
      return static_cast<int64_t>(value.number);
    case ParamType::Float:
      return value.number;
    case ParamType::Enum:
      return value.text;
  }
  return value.number;
}

bool same_params(const CompiledPass& a, const CompiledPass& b) {
  if (a.params.size() != b.params.size()) return false;
  for (const auto& [name, value] : a.params) {
    auto it = b.params.find(name);
    if (it == b.params.end() || it->second.number != value.number || it->second.text != value.text)
      return false;
  }
  return true;
}

// The live passes writing each resource.
std::map<int, std::set<std::string>> writers(const CompiledGraph& g) {
  std::map<int, std::set<std::string>> by_resource;
  for (const CompiledPass& p : g.passes) {
    for (const SlotBinding& b : p.bindings) {
      if (!b.is_input && b.resource >= 0) by_resource[b.resource].insert(p.name);
    }
  }
  return by_resource;
}

class Merger {
 public:
  Merger(const CompiledGraph& a, const CompiledGraph& b) : a_(a), b_(b) {}

  AbMerge run() {
    decide_sharing();
    Json graph;
    graph["name"] = a_.name + " + " + b_.name;
    graph["doc"] = "A/B: " + a_.file + " and " + b_.file + ", shared passes once";
    Json resources = Json::object();
    for (const CompiledResource& r : a_.resources) {
      if (r.history_of < 0) resources[r.info.name] = resource_json(r.info);
    }
    for (size_t i = 0; i < b_.resources.size(); ++i) {
      const CompiledResource& r = b_.resources[i];
      if (r.history_of < 0 && shared_resource_[i] < 0) {
        resources[kAbPrefix + r.info.name] = resource_json(r.info);
      }
    }
    graph["resources"] = resources;
    AbMerge merge;
    Json passes = Json::array();
    for (const CompiledPass& p : a_.passes) {
      passes.push_back(pass_json(p, p.name, [&](int r) { return a_name(r); }));
      if (shared_pass_.count(p.name)) merge.shared_passes.push_back(p.name);
    }
    for (const CompiledPass& p : b_.passes) {
      if (shared_pass_.count(p.name)) continue;
      merge.b_passes.push_back(kAbPrefix + p.name);
      passes.push_back(pass_json(p, kAbPrefix + p.name, [&](int r) { return b_name(r); }));
    }
    graph["passes"] = passes;
    Json outputs = Json::object();
    for (const auto& [name, r] : a_.outputs) outputs[name] = a_name(r);
    for (const auto& [name, r] : b_.outputs) outputs[kAbPrefix + name] = b_name(r);
    graph["outputs"] = outputs;
    merge.desc = parse_graph(graph.dump(1), a_.file + " + " + b_.file);
    return merge;
  }

 private:
  // Optimistic to a fixed point: everything that could be shared is, until an input or a
  // writer says otherwise (so a feedback loop through persistent resources shares too).
  void decide_sharing() {
    std::map<std::string, const CompiledPass*> a_passes;
    for (const CompiledPass& p : a_.passes) a_passes[p.name] = &p;
    for (const CompiledPass& p : b_.passes) {
      auto it = a_passes.find(p.name);
      if (it != a_passes.end() && it->second->type == p.type && same_params(*it->second, p) &&
          it->second->bindings.size() == p.bindings.size()) {
        shared_pass_[p.name] = it->second;
      }
    }
    const std::map<int, std::set<std::string>> a_writers = writers(a_);
    const std::map<int, std::set<std::string>> b_writers = writers(b_);
    shared_resource_.assign(b_.resources.size(), -1);
    for (size_t i = 0; i < b_.resources.size(); ++i) {
      const CompiledResource& r = b_.resources[i];
      const int a = a_.find_resource(r.info.name);
      if (a < 0) continue;
      const CompiledResource& other = a_.resources[static_cast<size_t>(a)];
      const auto aw = a_writers.find(a);
      const auto bw = b_writers.find(static_cast<int>(i));
      const bool same_writers = (aw == a_writers.end()) == (bw == b_writers.end()) &&
                                (aw == a_writers.end() || aw->second == bw->second);
      if (same_description(r.info, other.info) && r.info.persistent == other.info.persistent &&
          (r.history_of < 0) == (other.history_of < 0) && same_writers) {
        shared_resource_[i] = a;
      }
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (auto it = shared_pass_.begin(); it != shared_pass_.end();) {
        if (bindings_match(*b_.find_pass(it->first), *it->second)) {
          ++it;
          continue;
        }
        it = shared_pass_.erase(it);
        changed = true;
      }
      for (size_t i = 0; i < b_.resources.size(); ++i) {
        if (shared_resource_[i] < 0) continue;
        const int base =
            b_.resources[i].history_of >= 0 ? b_.resources[i].history_of : static_cast<int>(i);
        const auto bw = b_writers.find(base);
        bool all_shared = shared_resource_[static_cast<size_t>(base)] >= 0;
        if (bw != b_writers.end()) {
          for (const std::string& w : bw->second) all_shared = all_shared && shared_pass_.count(w);
        }
        if (!all_shared) {
          shared_resource_[i] = -1;
          changed = true;
        }
      }
    }
  }

  // Every slot bound to the same (shared) resource, or unbound in both.
  bool bindings_match(const CompiledPass& b, const CompiledPass& a) const {
    for (const SlotBinding& bb : b.bindings) {
      const SlotBinding* ab = a.binding(bb.slot);
      if (!ab || ab->is_input != bb.is_input || ab->info.mip != bb.info.mip) return false;
      if ((ab->resource < 0) != (bb.resource < 0)) return false;
      if (bb.resource >= 0 && shared_resource_[static_cast<size_t>(bb.resource)] != ab->resource)
        return false;
    }
    return true;
  }

  std::string a_name(int r) const { return a_.resources[static_cast<size_t>(r)].info.name; }

  std::string b_name(int r) const {
    if (shared_resource_[static_cast<size_t>(r)] >= 0) {
      return a_name(shared_resource_[static_cast<size_t>(r)]);
    }
    const CompiledResource& res = b_.resources[static_cast<size_t>(r)];
    if (res.history_of >= 0) return b_name(res.history_of) + "@previous";
    return kAbPrefix + res.info.name;
  }

  template <typename Name>
  static Json pass_json(const CompiledPass& p, const std::string& name, Name resource_name) {
    Json j;
    j["name"] = name;
    j["type"] = p.type;
    Json params = Json::object();
    for (const ParamSpec& spec : p.type_info->params) {
      auto it = p.params.find(spec.name);
      if (it != p.params.end()) params[spec.name] = param_json(spec, it->second);
    }
    j["params"] = params;
    Json in = Json::object(), out = Json::object();
    for (const SlotBinding& b : p.bindings) {
      if (b.resource < 0) continue;
      std::string target = resource_name(b.resource);
      if (b.info.mip >= 0) target.append("@").append(std::to_string(b.info.mip));
      (b.is_input ? in : out)[b.slot] = target;
    }
    j["in"] = in;
    j["out"] = out;
    return j;
  }

  const CompiledGraph& a_;
  const CompiledGraph& b_;
  std::map<std::string, const CompiledPass*> shared_pass_;  // B's name -> A's pass
  std::vector<int> shared_resource_;                        // B's resource -> A's, or -1
};

}  // namespace

AbMerge merge_for_ab(const CompiledGraph& a, const CompiledGraph& b) {
  return Merger(a, b).run();
}

}  // namespace voxgi::graph
