// voxgi passes [--markdown]: every registered pass type with its slots and parameters,
// generated from the plugins' own declarations.

#include <iostream>
#include <sstream>

#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/commands.hpp"

namespace voxgi::cli {
namespace {

std::string default_text(const graph::ParamSpec& p) {
  std::ostringstream out;
  switch (p.type) {
    case graph::ParamType::Bool:
      out << (p.default_value != 0.0 ? "true" : "false");
      break;
    case graph::ParamType::Enum: {
      const size_t i = static_cast<size_t>(p.default_value);
      out << (i < p.choices.size() ? p.choices[i] : "?");
      break;
    }
    default:
      out << p.default_value;
  }
  return out.str();
}

std::string range_text(const graph::ParamSpec& p) {
  std::ostringstream out;
  if (p.type == graph::ParamType::Enum) {
    for (size_t i = 0; i < p.choices.size(); ++i) out << (i ? " \\| " : "") << p.choices[i];
  } else if (p.type != graph::ParamType::Bool) {
    out << "[" << p.min << ", " << p.max << "]";
  }
  return out.str();
}

std::string slots_text(const std::vector<graph::SlotSpec>& slots) {
  std::string text;
  for (const graph::SlotSpec& s : slots) {
    text += (text.empty() ? "" : ", ") + s.name + (s.optional ? "?" : "");
  }
  return text.empty() ? "-" : text;
}

// The outputs whose size the pass derives when the graph gives none.
std::string sized_slots_text(const std::vector<graph::SlotSpec>& slots) {
  std::string text;
  for (const graph::SlotSpec& s : slots) {
    if (s.size_rule) text += (text.empty() ? "" : ", ") + s.name;
  }
  return text;
}

// How a change of the parameter takes effect.
const char* change_text(const graph::ParamSpec& p) {
  if (p.sizes_outputs) return "recompile";
  return p.live ? "yes" : "rebuild";
}

}  // namespace

int passes_command(const std::vector<std::string>& argv) {
  Args args("voxgi passes", {{"markdown", false, false, "", "print a Markdown table"},
                             {"help", false, false, "", "show this help"}});
  args.parse(argv);
  if (args.flag("help")) {
    std::cout << "usage: voxgi passes [--markdown]\n" << args.help();
    return 0;
  }
  graph::Registry registry;
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  loader.load_all(registry);
  const bool markdown = args.flag("markdown");
  for (const graph::PassTypeInfo* info : registry.all()) {
    if (markdown) {
      std::cout << "### `" << info->type << "`\n\n"
                << info->doc << "\n\n"
                << "inputs: " << slots_text(info->inputs)
                << " — outputs: " << slots_text(info->outputs) << " (`?` optional)\n\n";
      if (const std::string sized = sized_slots_text(info->outputs); !sized.empty()) {
        std::cout << "sizes (and formats) it derives for outputs the graph leaves unsized: "
                  << sized << "\n\n";
      }
      if (!info->params.empty()) {
        std::cout << "| parameter | type | default | range | live | description |\n"
                  << "|---|---|---|---|---|---|\n";
        for (const graph::ParamSpec& p : info->params) {
          std::cout << "| `" << p.name << "` | " << graph::param_type_name(p.type) << " | "
                    << default_text(p) << " | " << range_text(p) << " | " << change_text(p) << " | "
                    << p.doc << " |\n";
        }
        std::cout << "\n";
      }
      continue;
    }
    std::cout << info->type << " — " << info->doc << "\n"
              << "  inputs:  " << slots_text(info->inputs) << "\n"
              << "  outputs: " << slots_text(info->outputs) << "\n";
    if (const std::string sized = sized_slots_text(info->outputs); !sized.empty()) {
      std::cout << "  sizes:   " << sized << "\n";
    }
    for (const graph::ParamSpec& p : info->params) {
      std::cout << "  " << p.name << " (" << graph::param_type_name(p.type) << ", default "
                << default_text(p);
      if (const std::string range = range_text(p); !range.empty()) std::cout << ", " << range;
      std::cout << (p.sizes_outputs ? ", recompiles"
                    : p.live        ? ""
                                    : ", rebuilds")
                << "): " << p.doc << "\n";
    }
  }
  return 0;
}

}  // namespace voxgi::cli
