#include "engine/graph/graph_desc.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/graph/compose.hpp"
#include "engine/graph/input_file.hpp"

namespace voxgi::graph {

const ResourceDesc* GraphDesc::find_resource(std::string_view resource_name) const {
  for (const ResourceDesc& r : resources) {
    if (r.name == resource_name) return &r;
  }
  return nullptr;
}

const VariantDesc* GraphDesc::find_variant(std::string_view variant_name) const {
  for (const VariantDesc& v : variants) {
    if (v.name == variant_name) return &v;
  }
  return nullptr;
}

namespace {

void add_family(const std::string& type, std::set<std::string>& names) {
  const size_t dot = type.find('.');
  if (dot != std::string::npos && dot > 0) names.insert(type.substr(0, dot));
}

// The types written in a repeat's passes (and nested repeats'), before expansion.
void add_repeat_families(const std::vector<json::Value>& items, std::set<std::string>& names) {
  for (const json::Value& item : items) {
    if (!item.is_object()) continue;
    if (const json::Value* t = item.find("type"); t && t->is_string())
      add_family(t->as_string(), names);
    if (const json::Value* body = item.find("passes"); body && body->is_array())
      add_repeat_families(body->items(), names);
  }
}

}  // namespace

std::vector<std::string> GraphDesc::families() const {
  std::set<std::string> names;
  for (const PassDesc& p : passes) {
    if (p.repeat) {
      add_repeat_families(p.repeat->passes, names);
    } else {
      add_family(p.type, names);
    }
  }
  return {names.begin(), names.end()};
}

namespace {

using json::Member;
using json::Value;

std::vector<std::string> keys(std::initializer_list<const char*> list) {
  return {list.begin(), list.end()};
}

class DescParser {
 public:
  explicit DescParser(DiagnosticList& diags) : diags_(diags) {}

  // Reports every member whose key is not one of `allowed`.
  void check_keys(const Value& object, const std::vector<std::string>& allowed,
                  const std::string& pass, const std::string& prefix) {
    for (const Member& m : object.members()) {
      if (std::find(allowed.begin(), allowed.end(), m.key) == allowed.end()) {
        diags_.error(m.key_loc, pass, prefix + m.key, "unknown field",
                     did_you_mean(m.key, allowed));
      }
    }
  }

  bool expect(const Value& v, Value::Kind kind, const std::string& pass, const std::string& field,
              const char* expected) {
    if (v.kind() == kind) return true;
    diags_.error(v.loc(), pass, field,
                 std::string("expected ") + expected + ", found " + json::kind_name(v.kind()));
    return false;
  }

  ExprField expr_field(const Value& v, const std::string& owner, const std::string& field) {
    ExprField f;
    f.loc = v.loc();
    if (v.is_number()) {
      f.present = true;
      f.is_number = true;
      f.number = v.as_number();
      std::ostringstream text;
      text << f.number;
      f.text = text.str();
    } else if (v.is_string()) {
      f.present = true;
      f.text = v.as_string();
    } else {
      diags_.error(v.loc(), {}, owner + "." + field,
                   std::string("expected a number or an expression string, found ") +
                       json::kind_name(v.kind()));
    }
    return f;
  }

  void parse_indirect(const Value& v, GraphDesc& desc) {
    if (!expect(v, Value::Kind::Object, {}, "indirect", "an object {\"bounces\", \"brdf\"}"))
      return;
    check_keys(v, keys({"bounces", "brdf", "specular", "faces", "doc"}), {}, "indirect.");
    IndirectDesc& indirect = desc.indirect;
    indirect.present = true;
    indirect.loc = v.loc();
    if (const Value* b = v.find("bounces")) {
      indirect.bounces = expr_field(*b, "indirect", "bounces");
    } else {
      diags_.error(v.loc(), {}, "indirect.bounces", "missing (required)");
    }
    if (const Value* brdf = v.find("brdf")) {
      indirect.brdf_loc = brdf->loc();
      if (!brdf->is_string() || (brdf->as_string() != "diffuse" && brdf->as_string() != "full")) {
        diags_.error(brdf->loc(), {}, "indirect.brdf", "expected \"diffuse\" or \"full\"");
      } else {
        indirect.brdf = brdf->as_string();
      }
    }
    if (const Value* specular = v.find("specular")) {
      indirect.specular = expr_field(*specular, "indirect", "specular");
    }
    if (const Value* faces = v.find("faces")) {
      if (!faces->is_string() || (faces->as_string() != "front" && faces->as_string() != "both")) {
        diags_.error(faces->loc(), {}, "indirect.faces", "expected \"front\" or \"both\"");
      } else {
        indirect.faces = faces->as_string();
      }
    }
  }

  void parse_parameters(const Value& v, GraphDesc& desc) {
    if (!expect(v, Value::Kind::Object, {}, "parameters", "an object")) return;
    for (const Member& m : v.members()) {
      GraphParam p;
      p.name = m.key;
      p.loc = m.value.loc();
      if (m.value.is_bool()) {
        p.is_bool = true;
        p.value = m.value.as_bool() ? 1.0 : 0.0;
      } else if (m.value.is_number()) {
        p.value = m.value.as_number();
      } else {
        diags_.error(m.value.loc(), {}, "parameters." + m.key,
                     std::string("expected a number or a boolean, found ") +
                         json::kind_name(m.value.kind()));
        continue;
      }
      desc.parameters.push_back(std::move(p));
    }
  }

  void parse_variants(const Value& v, GraphDesc& desc) {
    if (!expect(v, Value::Kind::Object, {}, "variants", "an object of name: {\"set\": {...}}"))
      return;
    for (const Member& m : v.members()) {
      const std::string field = "variants." + m.key;
      if (!expect(m.value, Value::Kind::Object, {}, field, "an object {\"doc\", \"set\"}"))
        continue;
      check_keys(m.value, keys({"doc", "set"}), {}, field + ".");
      VariantDesc variant;
      variant.name = m.key;
      variant.loc = m.key_loc;
      if (const Value* d = m.value.find("doc")) {
        if (expect(*d, Value::Kind::String, {}, field + ".doc", "a string"))
          variant.doc = d->as_string();
      }
      const Value* set = m.value.find("set");
      if (!set) {
        diags_.error(m.value.loc(), {}, field + ".set",
                     "missing (the overrides the variant applies, {\"pass.param\": value})");
        continue;
      }
      if (!expect(*set, Value::Kind::Object, {}, field + ".set", "an object of key: value"))
        continue;
      for (const Member& s : set->members()) {
        std::string value;
        if (s.value.is_string()) {
          value = s.value.as_string();
        } else if (s.value.is_bool()) {
          value = s.value.as_bool() ? "true" : "false";
        } else if (s.value.is_number()) {
          value = json::number_text(s.value.as_number());
        } else {
          diags_.error(s.value.loc(), {}, field + ".set." + s.key,
                       std::string("expected a number, string or boolean, found ") +
                           json::kind_name(s.value.kind()));
          continue;
        }
        if (s.key == kVariantKey) {
          diags_.error(s.key_loc, {}, field + ".set." + s.key,
                       "a variant cannot select another variant");
          continue;
        }
        variant.settings.push_back({s.key, std::move(value), s.value.loc()});
      }
      desc.variants.push_back(std::move(variant));
    }
  }

  void parse_resource(const Member& m, GraphDesc& desc) {
    const std::string field = "resources." + m.key;
    if (!expect(m.value, Value::Kind::Object, {}, field, "an object")) return;
    const Value& v = m.value;
    check_keys(v,
               keys({"type", "format", "size", "mips", "layers", "resolution", "levels",
                     "persistent", "doc"}),
               {}, field + ".");
    ResourceDesc r;
    r.name = m.key;
    r.loc = m.key_loc;
    r.type_loc = r.format_loc = r.size_loc = v.loc();
    if (const Value* t = v.find("type")) {
      r.type_loc = t->loc();
      if (expect(*t, Value::Kind::String, {}, field + ".type", "a string")) r.type = t->as_string();
    } else {
      diags_.error(v.loc(), {}, field + ".type",
                   "missing field 'type' (expected image2d, image3d, clipmap or buffer)");
    }
    if (const Value* f = v.find("format")) {
      r.format_loc = f->loc();
      if (expect(*f, Value::Kind::String, {}, field + ".format", "a string"))
        r.format = f->as_string();
    }
    if (const Value* s = v.find("size")) {
      r.size_loc = s->loc();
      if (s->is_array()) {
        if (s->items().empty() || s->items().size() > 3) {
          diags_.error(s->loc(), {}, field + ".size",
                       "expected 1 to 3 components [w, h] or [w, h, d], found " +
                           std::to_string(s->items().size()));
        }
        for (const Value& item : s->items()) r.size.push_back(expr_field(item, field, "size"));
      } else {
        r.size.push_back(expr_field(*s, field, "size"));
      }
    }
    if (const Value* x = v.find("mips")) r.mips = expr_field(*x, field, "mips");
    if (const Value* x = v.find("layers")) r.layers = expr_field(*x, field, "layers");
    if (const Value* x = v.find("resolution")) r.resolution = expr_field(*x, field, "resolution");
    if (const Value* x = v.find("levels")) r.levels = expr_field(*x, field, "levels");
    if (const Value* p = v.find("persistent")) {
      if (expect(*p, Value::Kind::Bool, {}, field + ".persistent", "true or false"))
        r.persistent = p->as_bool();
    }
    if (const Value* d = v.find("doc")) {
      if (expect(*d, Value::Kind::String, {}, field + ".doc", "a string")) r.doc = d->as_string();
    }
    desc.resources.push_back(std::move(r));
  }

  void parse_bindings(const Value& v, const std::string& pass, const std::string& section,
                      std::vector<BindingDesc>& out) {
    if (!expect(v, Value::Kind::Object, pass, section, "an object of slot: resource")) return;
    for (const Member& m : v.members()) {
      const std::string field = section + "." + m.key;
      if (!expect(m.value, Value::Kind::String, pass, field, "a resource name string")) continue;
      BindingDesc b;
      b.slot = m.key;
      b.slot_loc = m.key_loc;
      b.loc = m.value.loc();
      const std::string& text = m.value.as_string();
      const size_t at = text.find('@');
      b.resource = text.substr(0, at);
      if (at != std::string::npos && text.substr(at + 1) == "previous") {
        b.previous = true;
      } else if (at != std::string::npos) {
        const std::string level = text.substr(at + 1);
        const bool digits =
            !level.empty() && level.size() < 3 &&
            std::all_of(level.begin(), level.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (!digits) {
          diags_.error(b.loc, pass, field,
                       "expected a mip level number (\"name@2\") or \"previous\" (the previous "
                       "frame's version) after '@', found '" +
                           level + "'");
          continue;
        }
        b.mip = std::stoi(level);
      }
      if (b.resource.empty()) {
        diags_.error(b.loc, pass, field, "expected a resource name");
        continue;
      }
      out.push_back(std::move(b));
    }
  }

  void parse_repeat(const Value& v, const std::string& field, std::vector<PassDesc>& list) {
    check_keys(v, keys({"repeat", "index", "from", "passes", "doc"}), {}, field + ".");
    auto repeat = std::make_shared<RepeatDesc>();
    repeat->loc = v.loc();
    repeat->count = expr_field(*v.find("repeat"), field, "repeat");
    if (const Value* i = v.find("index")) {
      if (expect(*i, Value::Kind::String, {}, field + ".index", "a name string"))
        repeat->index = i->as_string();
    }
    if (const Value* f = v.find("from")) {
      if (!f->is_number() || f->as_number() != std::floor(f->as_number()) ||
          std::fabs(f->as_number()) > 1e6) {
        diags_.error(f->loc(), {}, field + ".from", "expected a whole number");
      } else {
        repeat->from = static_cast<int>(f->as_number());
      }
    }
    if (const Value* ps = v.find("passes")) {
      if (expect(*ps, Value::Kind::Array, {}, field + ".passes", "an array of passes"))
        repeat->passes = ps->items();
    } else {
      diags_.error(v.loc(), {}, field + ".passes", "missing field 'passes'");
    }
    PassDesc p;
    p.loc = p.name_loc = p.type_loc = p.when_loc = v.loc();
    p.repeat = std::move(repeat);
    list.push_back(std::move(p));
  }

  void parse_pass(const Value& v, const std::string& field, std::vector<PassDesc>& list) {
    if (!expect(v, Value::Kind::Object, {}, field, "a pass object")) return;
    if (v.find("repeat")) {
      parse_repeat(v, field, list);
      return;
    }
    PassDesc p;
    p.loc = v.loc();
    p.name_loc = p.type_loc = p.when_loc = v.loc();
    if (const Value* n = v.find("name")) {
      p.name_loc = n->loc();
      if (expect(*n, Value::Kind::String, {}, field + ".name", "a string")) p.name = n->as_string();
    } else {
      diags_.error(v.loc(), {}, field + ".name", "missing field 'name'");
    }
    const std::string owner = p.name;
    const std::string prefix = owner.empty() ? field + "." : std::string();
    check_keys(v, keys({"name", "type", "when", "params", "in", "out", "doc"}), owner, prefix);
    if (const Value* t = v.find("type")) {
      p.type_loc = t->loc();
      if (expect(*t, Value::Kind::String, owner, prefix + "type", "a string"))
        p.type = t->as_string();
    } else {
      diags_.error(v.loc(), owner, prefix + "type", "missing field 'type' (\"family.pass\")");
    }
    if (const Value* w = v.find("when")) {
      p.when_loc = w->loc();
      if (w->is_bool()) {
        p.when = w->as_bool() ? "true" : "false";
      } else if (expect(*w, Value::Kind::String, owner, prefix + "when",
                        "a condition string or a boolean")) {
        p.when = w->as_string();
      }
    }
    if (const Value* ps = v.find("params")) {
      if (expect(*ps, Value::Kind::Object, owner, prefix + "params", "an object")) {
        for (const Member& m : ps->members()) {
          p.params.push_back(ParamSetting{m.key, m.key_loc, m.value});
        }
      }
    }
    if (const Value* in = v.find("in")) parse_bindings(*in, owner, prefix + "in", p.inputs);
    if (const Value* out = v.find("out")) parse_bindings(*out, owner, prefix + "out", p.outputs);
    if (const Value* d = v.find("doc")) {
      if (expect(*d, Value::Kind::String, owner, prefix + "doc", "a string"))
        p.doc = d->as_string();
    }
    list.push_back(std::move(p));
  }

  void parse_outputs(const Value& v, GraphDesc& desc) {
    if (!expect(v, Value::Kind::Object, {}, "outputs", "an object of name: resource")) return;
    for (const Member& m : v.members()) {
      if (!expect(m.value, Value::Kind::String, {}, "outputs." + m.key, "a resource name string"))
        continue;
      desc.outputs.push_back(OutputDesc{m.key, m.value.as_string(), m.value.loc()});
    }
  }

 private:
  DiagnosticList& diags_;
};

}  // namespace

std::vector<PassDesc> parse_pass_list(const std::vector<json::Value>& items,
                                      const std::string& field, DiagnosticList& diags) {
  std::vector<PassDesc> passes;
  DescParser parser(diags);
  for (size_t i = 0; i < items.size(); ++i)
    parser.parse_pass(items[i], field + "[" + std::to_string(i) + "]", passes);
  return passes;
}

GraphDesc parse_graph(std::string_view text, std::string file_name) {
  DiagnosticList diags;
  GraphDesc desc;
  const json::Value root =
      compose_includes(json::parse(text, file_name), file_name, diags, &desc.included_files);
  desc.file = std::move(file_name);
  DescParser parser(diags);
  if (!root.is_object()) {
    diags.error(root.loc(), {}, {},
                std::string("expected the graph to be a JSON object, found ") +
                    json::kind_name(root.kind()));
    diags.throw_if_any();
  }
  parser.check_keys(root,
                    keys({"name", "doc", "parameters", "indirect", "variants", "resources",
                          "passes", "outputs", "output"}),
                    {}, {});
  if (const Value* n = root.find("name")) {
    if (parser.expect(*n, Value::Kind::String, {}, "name", "a string")) desc.name = n->as_string();
  }
  if (const Value* d = root.find("doc")) {
    if (parser.expect(*d, Value::Kind::String, {}, "doc", "a string")) desc.doc = d->as_string();
  }
  if (const Value* p = root.find("parameters")) parser.parse_parameters(*p, desc);
  if (const Value* i = root.find("indirect")) parser.parse_indirect(*i, desc);
  if (const Value* v = root.find("variants")) parser.parse_variants(*v, desc);
  if (const Value* r = root.find("resources")) {
    if (parser.expect(*r, Value::Kind::Object, {}, "resources", "an object")) {
      for (const Member& m : r->members()) parser.parse_resource(m, desc);
    }
  }
  if (const Value* ps = root.find("passes")) {
    if (parser.expect(*ps, Value::Kind::Array, {}, "passes", "an array of passes")) {
      for (size_t i = 0; i < ps->items().size(); ++i)
        parser.parse_pass(ps->items()[i], "passes[" + std::to_string(i) + "]", desc.passes);
    }
  } else {
    diags.error(root.loc(), {}, "passes", "missing field 'passes'");
  }
  if (const Value* o = root.find("outputs")) parser.parse_outputs(*o, desc);
  // "output": "resource" is shorthand for one display output.
  if (const Value* o = root.find("output")) {
    if (parser.expect(*o, Value::Kind::String, {}, "output", "a resource name string"))
      desc.outputs.push_back(OutputDesc{"display", o->as_string(), o->loc()});
  }
  if (desc.outputs.empty() && diags.empty()) {
    diags.error(root.loc(), {}, "outputs",
                "the graph has no outputs (expected \"outputs\": { \"display\": \"resource\" })");
  }
  diags.throw_if_any();
  return desc;
}

GraphDesc load_graph_file(const std::filesystem::path& path) {
  return parse_graph(read_input_file(path, "graph file"), path.string());
}

}  // namespace voxgi::graph
