#include "apps/voxgi/cli_args.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

namespace voxgi::cli {

Args::Args(std::string command, std::vector<OptionSpec> specs)
    : command_(std::move(command)), specs_(std::move(specs)) {}

const OptionSpec* Args::find(const std::string& name) const {
  for (const OptionSpec& spec : specs_) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

void Args::parse(const std::vector<std::string>& argv) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& arg = argv[i];
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2);
    std::optional<std::string> inline_value;
    if (const size_t eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const OptionSpec* spec = find(name);
    if (!spec) {
      std::vector<std::string> names;
      for (const OptionSpec& s : specs_) names.push_back(s.name);
      std::string message = command_ + ": unknown option '--" + name + "'";
      if (std::string close = closest_match(name, names); !close.empty()) {
        message += " (did you mean '--" + close + "'?)";
      }
      throw UsageError(message);
    }
    if (!spec->takes_value) {
      if (inline_value) throw UsageError(command_ + ": option '--" + name + "' takes no value");
      flags_.insert(name);
      continue;
    }
    std::string value;
    if (inline_value) {
      value = *inline_value;
    } else {
      if (i + 1 >= argv.size()) {
        throw UsageError(command_ + ": option '--" + name + "' needs a value (" + spec->value_name +
                         ")");
      }
      value = argv[++i];
    }
    std::vector<std::string>& slot = values_[name];
    if (!slot.empty() && !spec->repeatable) {
      throw UsageError(command_ + ": option '--" + name + "' given more than once");
    }
    slot.push_back(value);
  }
}

std::optional<std::string> Args::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

std::string Args::value_or(const std::string& name, const std::string& fallback) const {
  return value(name).value_or(fallback);
}

std::vector<std::string> Args::values(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

int Args::integer(const std::string& name, int fallback, int min, int max) const {
  const std::optional<std::string> text = value(name);
  if (!text) return fallback;
  int result = 0;
  const char* end = text->data() + text->size();
  auto [ptr, ec] = std::from_chars(text->data(), end, result);
  if (ec != std::errc() || ptr != end || result < min || result > max) {
    throw UsageError(command_ + ": option '--" + name + "': expected an integer in [" +
                     std::to_string(min) + ", " + std::to_string(max) + "], got '" + *text + "'");
  }
  return result;
}

std::string Args::help() const {
  std::ostringstream out;
  for (const OptionSpec& spec : specs_) {
    std::string left = "  --" + spec.name;
    if (spec.takes_value) left += " " + spec.value_name;
    out << left;
    if (left.size() < 28)
      out << std::string(28 - left.size(), ' ');
    else
      out << "\n" << std::string(28, ' ');
    out << spec.doc << (spec.repeatable ? " (repeatable)" : "") << "\n";
  }
  return out.str();
}

namespace {
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}
}  // namespace

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    const size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

}  // namespace voxgi::cli
