#include "engine/graph/compose.hpp"

#include <algorithm>
#include <optional>
#include <system_error>
#include <vector>

#include "engine/graph/input_file.hpp"

namespace voxgi::graph {

namespace {

using json::Member;
using json::Value;

// "{{name}}" occurrences in `text`, as (start, end, name); `end` is one past the closing braces.
struct Placeholder {
  size_t start = 0;
  size_t end = 0;
  std::string name;
};

std::vector<Placeholder> placeholders(const std::string& text) {
  std::vector<Placeholder> found;
  size_t from = 0;
  while (true) {
    const size_t open = text.find("{{", from);
    if (open == std::string::npos) break;
    const size_t close = text.find("}}", open + 2);
    if (close == std::string::npos) break;
    std::string name = text.substr(open + 2, close - open - 2);
    while (!name.empty() && name.front() == ' ') name.erase(name.begin());
    while (!name.empty() && name.back() == ' ') name.pop_back();
    found.push_back(Placeholder{open, close + 2, name});
    from = close + 2;
  }
  return found;
}

class Substituter {
 public:
  Substituter(const std::map<std::string, Value>& arguments, const std::set<std::string>& kept,
              DiagnosticList& diags)
      : arguments_(arguments), kept_(kept), diags_(diags) {}

  // Empty optional: the value is exactly a null argument and is to be removed.
  std::optional<Value> apply(const Value& v) {
    switch (v.kind()) {
      case Value::Kind::String:
        return string(v);
      case Value::Kind::Array: {
        std::vector<Value> items;
        for (const Value& item : v.items()) {
          if (std::optional<Value> s = apply(item)) items.push_back(std::move(*s));
        }
        return Value::make_array(std::move(items), v.loc());
      }
      case Value::Kind::Object: {
        std::vector<Member> members;
        for (const Member& m : v.members()) {
          std::optional<Value> value = apply(m.value);
          if (!value) continue;
          std::string key = text(m.key, m.key_loc);
          members.push_back(Member{std::move(key), m.key_loc, std::move(*value)});
        }
        return Value::make_object(std::move(members), v.loc());
      }
      default:
        return v;
    }
  }

 private:
  const Value* argument(const Placeholder& p, const SourceLoc& loc) {
    auto it = arguments_.find(p.name);
    if (it != arguments_.end()) return &it->second;
    if (!kept_.count(p.name)) {
      std::vector<std::string> names;
      for (const auto& [name, value] : arguments_) names.push_back(name);
      names.insert(names.end(), kept_.begin(), kept_.end());
      diags_.error(loc, {}, {},
                   "'{{" + p.name + "}}' names no argument of this fragment" +
                       (names.empty() ? std::string(" (it declares none)") : std::string()),
                   did_you_mean(p.name, names));
    }
    return nullptr;
  }

  std::optional<Value> string(const Value& v) {
    const std::string& s = v.as_string();
    const std::vector<Placeholder> found = placeholders(s);
    if (found.size() == 1 && found[0].start == 0 && found[0].end == s.size()) {
      const Value* arg = argument(found[0], v.loc());
      if (!arg) return v;
      if (arg->is_null()) return std::nullopt;
      if (arg->is_number()) return Value::make_number(arg->as_number(), v.loc());
      if (arg->is_bool()) return Value::make_bool(arg->as_bool(), v.loc());
      return Value::make_string(arg->as_string(), v.loc());
    }
    return Value::make_string(text(s, v.loc()), v.loc());
  }

  std::string text(const std::string& s, const SourceLoc& loc) {
    const std::vector<Placeholder> found = placeholders(s);
    if (found.empty()) return s;
    std::string out;
    size_t at = 0;
    for (const Placeholder& p : found) {
      out += s.substr(at, p.start - at);
      at = p.end;
      const Value* arg = argument(p, loc);
      if (!arg) {
        out += s.substr(p.start, p.end - p.start);
      } else if (arg->is_null()) {
        diags_.error(loc, {}, {},
                     "argument '" + p.name +
                         "' is null here, which only removes a value that is exactly '{{" + p.name +
                         "}}'");
      } else if (arg->is_number()) {
        out += json::number_text(arg->as_number());
      } else if (arg->is_bool()) {
        out += arg->as_bool() ? "true" : "false";
      } else {
        out += arg->as_string();
      }
    }
    return out + s.substr(at);
  }

  const std::map<std::string, Value>& arguments_;
  const std::set<std::string>& kept_;
  DiagnosticList& diags_;
};

// The index names of every repeat in `v`: placeholders that the compiler fills in later.
void collect_repeat_indices(const Value& v, std::set<std::string>& names) {
  if (v.is_array()) {
    for (const Value& item : v.items()) collect_repeat_indices(item, names);
  } else if (v.is_object()) {
    if (v.find("repeat")) {
      const Value* index = v.find("index");
      names.insert(index && index->is_string() ? index->as_string() : std::string("index"));
    }
    for (const Member& m : v.members()) collect_repeat_indices(m.value, names);
  }
}

std::vector<std::string> key_list(std::initializer_list<const char*> list) {
  return {list.begin(), list.end()};
}

void check_keys(const Value& object, const std::vector<std::string>& allowed,
                const std::string& what, DiagnosticList& diags) {
  for (const Member& m : object.members()) {
    bool known = false;
    for (const std::string& a : allowed) known = known || a == m.key;
    if (!known) {
      diags.error(m.key_loc, {}, what + m.key, "unknown field", did_you_mean(m.key, allowed));
    }
  }
}

// A condition string for a pass included under the include's `when`.
Value combined_when(const Value& include_when, const Value* pass_when) {
  const auto text = [](const Value& w) {
    return w.is_bool() ? std::string(w.as_bool() ? "true" : "false") : w.as_string();
  };
  if (!pass_when) return include_when;
  std::string both = "(";
  both.append(text(include_when)).append(") && (").append(text(*pass_when)).append(")");
  return Value::make_string(std::move(both), pass_when->loc());
}

Value with_when(const Value& pass, const Value& include_when) {
  std::vector<Member> members;
  bool done = false;
  for (const Member& m : pass.members()) {
    if (m.key == "when" && (m.value.is_string() || m.value.is_bool())) {
      members.push_back(Member{m.key, m.key_loc, combined_when(include_when, &m.value)});
      done = true;
    } else if (m.key == "passes" && pass.find("repeat") && m.value.is_array()) {
      std::vector<Value> body;
      for (const Value& item : m.value.items()) {
        body.push_back(item.is_object() ? with_when(item, include_when) : item);
      }
      members.push_back(
          Member{m.key, m.key_loc, Value::make_array(std::move(body), m.value.loc())});
    } else {
      members.push_back(m);
    }
  }
  if (!done && !pass.find("repeat"))
    members.push_back(Member{"when", include_when.loc(), include_when});
  return Value::make_object(std::move(members), pass.loc());
}

std::filesystem::path shipped_graph_dir() {
  return std::filesystem::path(VOXGI_GRAPH_DIR);
}

// Declarations gathered from included fragments, merged into the includer at the end.
struct Included {
  std::vector<Member> parameters;
  std::vector<Member> resources;
  std::vector<Member> outputs;
};

class Composer {
 public:
  explicit Composer(DiagnosticList& diags) : diags_(diags) {}

  const std::vector<std::string>& files_read() const { return files_read_; }

  Value compose(const Value& doc, const std::string& file, std::vector<std::string>& stack) {
    if (!doc.is_object()) return doc;
    const Value* passes = doc.find("passes");
    if (!passes || !passes->is_array()) return doc;
    Included included;
    std::vector<Value> items = expand_list(passes->items(), file, stack, included);
    return merged(doc, Value::make_array(std::move(items), passes->loc()), included);
  }

 private:
  // A pass list with its includes replaced, in repeats too: a fragment included in a repeat
  // is included once, and the repeat then copies its passes ("with" values may hold the
  // repeat's "{{k}}").
  std::vector<Value> expand_list(const std::vector<Value>& list, const std::string& file,
                                 std::vector<std::string>& stack, Included& included) {
    std::vector<Value> items;
    for (const Value& item : list) {
      if (item.is_object() && item.find("include")) {
        include(item, file, stack, included, items);
      } else if (item.is_object() && item.find("repeat") && item.find("passes") &&
                 item.find("passes")->is_array()) {
        std::vector<Member> members;
        for (const Member& m : item.members()) {
          if (m.key != "passes") {
            members.push_back(m);
            continue;
          }
          members.push_back(
              Member{m.key, m.key_loc,
                     Value::make_array(expand_list(m.value.items(), file, stack, included),
                                       m.value.loc())});
        }
        items.push_back(Value::make_object(std::move(members), item.loc()));
      } else {
        items.push_back(item);
      }
    }
    return items;
  }

  std::optional<std::filesystem::path> resolve(const std::string& name,
                                               const std::string& includer) const {
    const std::filesystem::path relative(name);
    std::vector<std::filesystem::path> candidates;
    if (relative.is_absolute()) {
      candidates.push_back(relative);
    } else {
      candidates.push_back(std::filesystem::path(includer).parent_path() / relative);
      candidates.push_back(shipped_graph_dir() / relative);
    }
    for (const std::filesystem::path& c : candidates) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(c, ec)) return c;
    }
    return std::nullopt;
  }

  void include(const Value& item, const std::string& file, std::vector<std::string>& stack,
               Included& included, std::vector<Value>& items) {
    check_keys(item, key_list({"include", "with", "when", "doc"}), "include.", diags_);
    const Value& name_value = *item.find("include");
    if (!name_value.is_string()) {
      diags_.error(name_value.loc(), {}, "include",
                   std::string("expected a fragment file name, found ") +
                       json::kind_name(name_value.kind()));
      return;
    }
    const std::string& name = name_value.as_string();
    const std::optional<std::filesystem::path> path = resolve(name, file);
    if (!path) {
      diags_.error(name_value.loc(), {}, "include",
                   "fragment file '" + name + "' not found (looked next to '" + file + "' and in " +
                       shipped_graph_dir().string() + ")");
      return;
    }
    std::error_code ec;
    const std::string key = std::filesystem::weakly_canonical(*path, ec).string();
    for (const std::string& open : stack) {
      if (open == key) {
        diags_.error(name_value.loc(), {}, "include",
                     "fragment '" + name + "' includes itself (through " + file + ")");
        return;
      }
    }
    if (static_cast<int>(stack.size()) > kMaxIncludeDepth) {
      diags_.error(name_value.loc(), {}, "include",
                   "fragments nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
      return;
    }
    std::vector<std::string> chain{format_location(name_value.loc())};
    chain.insert(chain.end(), name_value.loc().included_from.begin(),
                 name_value.loc().included_from.end());
    Value fragment;
    try {
      fragment = json::parse(read_input_file(*path, "graph fragment"), path->string(), chain);
    } catch (const GraphError& e) {
      for (Diagnostic d : e.diagnostics()) {
        if (d.loc.line == 0) {
          d.message = "cannot include '" + name + "': " + d.message;
          d.loc = name_value.loc();
        }
        diags_.add(std::move(d));
      }
      return;
    }
    const std::optional<Value> instance = instantiate(fragment, item, name);
    if (!instance) return;
    if (std::find(files_read_.begin(), files_read_.end(), path->string()) == files_read_.end())
      files_read_.push_back(path->string());
    stack.push_back(key);
    const Value composed = compose(*instance, path->string(), stack);
    stack.pop_back();
    take(composed, item.find("when"), included, items);
  }

  // The fragment with its arguments filled in from the include's "with"; nullopt when it is
  // not a fragment at all.
  std::optional<Value> instantiate(const Value& fragment, const Value& include,
                                   const std::string& name) {
    if (!fragment.is_object() || !fragment.find("fragment")) {
      diags_.error(fragment.loc(), {}, "fragment",
                   "'" + name +
                       "' is not a graph fragment (expected an object with \"fragment\": "
                       "\"<name>\")");
      return std::nullopt;
    }
    check_keys(
        fragment,
        key_list({"fragment", "doc", "arguments", "parameters", "resources", "passes", "outputs"}),
        {}, diags_);
    std::map<std::string, Value> arguments;
    std::vector<std::string> declared;
    std::set<std::string> required;
    if (const Value* args = fragment.find("arguments")) {
      if (!args->is_object()) {
        diags_.error(args->loc(), {}, "arguments", "expected an object of name: default value");
      } else {
        for (const Member& m : args->members()) {
          declared.push_back(m.key);
          // {"doc": "...", "default": v}; no default makes the argument required.
          if (m.value.is_object()) {
            check_keys(m.value, key_list({"doc", "default"}), "arguments." + m.key + ".", diags_);
            if (const Value* d = m.value.find("default")) {
              arguments[m.key] = *d;
            } else {
              required.insert(m.key);
            }
          } else if (m.value.is_array()) {
            diags_.error(m.value.loc(), {}, "arguments." + m.key,
                         "expected a default value (string, number, boolean or null) or "
                         "{\"doc\", \"default\"}");
          } else {
            arguments[m.key] = m.value;
          }
        }
      }
    }
    if (const Value* with = include.find("with")) {
      if (!with->is_object()) {
        diags_.error(with->loc(), {}, "with", "expected an object of argument: value");
      } else {
        for (const Member& m : with->members()) {
          bool known = false;
          for (const std::string& d : declared) known = known || d == m.key;
          if (!known) {
            diags_.error(m.key_loc, {}, "with." + m.key,
                         "fragment '" + name + "' has no argument '" + m.key + "'",
                         did_you_mean(m.key, declared));
            continue;
          }
          if (m.value.is_array() || m.value.is_object()) {
            diags_.error(m.value.loc(), {}, "with." + m.key,
                         "expected a string, number, boolean or null");
            continue;
          }
          arguments[m.key] = m.value;
          required.erase(m.key);
        }
      }
    }
    for (const std::string& r : required) {
      diags_.error(include.loc(), {}, "with." + r,
                   "fragment '" + name + "' needs argument '" + r + "'");
    }
    std::vector<Member> body;
    for (const Member& m : fragment.members()) {
      if (m.key != "arguments") body.push_back(m);
    }
    std::set<std::string> kept;
    collect_repeat_indices(fragment, kept);
    std::optional<Value> filled = Substituter(arguments, kept, diags_)
                                      .apply(Value::make_object(std::move(body), fragment.loc()));
    return filled;
  }

  void take(const Value& fragment, const Value* when, Included& included,
            std::vector<Value>& items) {
    if (const Value* passes = fragment.find("passes"); passes && passes->is_array()) {
      for (const Value& pass : passes->items()) {
        const bool can_combine = when && (when->is_string() || when->is_bool()) && pass.is_object();
        items.push_back(can_combine ? with_when(pass, *when) : pass);
      }
    }
    if (when && !when->is_string() && !when->is_bool()) {
      diags_.error(when->loc(), {}, "when", "expected a condition string or a boolean");
    }
    const auto append = [&](const char* section, std::vector<Member>& into) {
      const Value* v = fragment.find(section);
      if (!v) return;
      if (!v->is_object()) {
        diags_.error(v->loc(), {}, section, "expected an object");
        return;
      }
      into.insert(into.end(), v->members().begin(), v->members().end());
    };
    append("parameters", included.parameters);
    append("resources", included.resources);
    append("outputs", included.outputs);
  }

  // `doc` with its passes replaced and the included declarations merged in: the includer's
  // own parameters and outputs win over a fragment's; a resource declared twice, or a
  // parameter two fragments give different defaults, is an error.
  Value merged(const Value& doc, Value passes, const Included& included) {
    std::vector<Member> members;
    bool has[3] = {false, false, false};
    static const char* const kSections[3] = {"parameters", "resources", "outputs"};
    const std::vector<Member>* from[3] = {&included.parameters, &included.resources,
                                          &included.outputs};
    for (const Member& m : doc.members()) {
      if (m.key == "passes") {
        members.push_back(Member{m.key, m.key_loc, passes});
        continue;
      }
      bool merged_section = false;
      for (int s = 0; s < 3; ++s) {
        if (m.key != kSections[s] || !m.value.is_object()) continue;
        has[s] = true;
        merged_section = true;
        members.push_back(
            Member{m.key, m.key_loc, merge_section(s, m.value, *from[s], m.value.loc())});
      }
      if (!merged_section) members.push_back(m);
    }
    for (int s = 0; s < 3; ++s) {
      if (has[s] || from[s]->empty()) continue;
      members.push_back(
          Member{kSections[s], doc.loc(),
                 merge_section(s, Value::make_object({}, doc.loc()), *from[s], doc.loc())});
    }
    return Value::make_object(std::move(members), doc.loc());
  }

  Value merge_section(int section, const Value& own, const std::vector<Member>& included,
                      const SourceLoc& loc) {
    std::vector<Member> members = own.members();
    const size_t own_count = members.size();
    for (const Member& m : included) {
      Member* existing = nullptr;
      size_t index = 0;
      for (size_t i = 0; i < members.size(); ++i) {
        if (members[i].key == m.key) {
          existing = &members[i];
          index = i;
        }
      }
      if (!existing) {
        members.push_back(m);
        continue;
      }
      if (index < own_count && section != 1) continue;  // the includer's own value wins
      if (section == 0 && same_scalar(existing->value, m.value)) continue;
      const char* what = section == 0 ? "parameter" : section == 1 ? "resource" : "output";
      diags_.error(
          m.key_loc, {}, std::string(section == 0 ? "parameters." : "") + m.key,
          std::string(what) + " '" + m.key + "' is also declared at " +
              format_location(existing->key_loc) +
              (section == 0 ? " with another default (set it in the including file)" : ""));
    }
    return Value::make_object(std::move(members), loc);
  }

  static bool same_scalar(const Value& a, const Value& b) {
    if (a.kind() != b.kind()) return false;
    if (a.is_number()) return a.as_number() == b.as_number();
    if (a.is_bool()) return a.as_bool() == b.as_bool();
    if (a.is_string()) return a.as_string() == b.as_string();
    return false;
  }

  DiagnosticList& diags_;
  std::vector<std::string> files_read_;
};

}  // namespace

json::Value compose_includes(const json::Value& root, const std::string& file,
                             DiagnosticList& diags, std::vector<std::string>* included_files) {
  std::vector<std::string> stack;
  std::error_code ec;
  stack.push_back(std::filesystem::weakly_canonical(file, ec).string());
  Composer composer(diags);
  json::Value composed = composer.compose(root, file, stack);
  if (included_files) *included_files = composer.files_read();
  return composed;
}

json::Value substitute_arguments(const json::Value& value,
                                 const std::map<std::string, json::Value>& arguments,
                                 const std::set<std::string>& kept, DiagnosticList& diags) {
  std::optional<json::Value> out = Substituter(arguments, kept, diags).apply(value);
  return out ? std::move(*out) : json::Value::make_null(value.loc());
}

std::set<std::string> repeat_indices(const json::Value& value) {
  std::set<std::string> names;
  collect_repeat_indices(value, names);
  return names;
}

}  // namespace voxgi::graph
