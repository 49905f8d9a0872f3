#include "engine/graph/diagnostics.hpp"

#include <algorithm>

namespace voxgi::graph {

Diagnostic message_only(std::string message, std::string hint) {
  Diagnostic d;
  d.message = std::move(message);
  d.hint = std::move(hint);
  return d;
}

std::string format_location(const SourceLoc& loc) {
  std::string out = loc.file;
  if (loc.line > 0) {
    out += ':';
    out += std::to_string(loc.line);
    if (loc.column > 0) {
      out += ':';
      out += std::to_string(loc.column);
    }
  }
  return out;
}

std::string format(const Diagnostic& d) {
  std::string out;
  if (!d.loc.file.empty()) out += format_location(d.loc) + ": ";
  out += "error: ";
  if (!d.pass.empty()) out += "pass '" + d.pass + "' ";
  if (!d.field.empty()) out += "field '" + d.field + "'";
  if (!d.pass.empty() || !d.field.empty()) {
    if (out.back() == ' ') out.pop_back();
    out += ": ";
  }
  out += d.message;
  if (!d.hint.empty()) out += " (did you mean '" + d.hint + "'?)";
  for (const std::string& from : d.loc.included_from) out += "\n  included from " + from;
  return out;
}

static std::string join_lines(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics) {
    if (!text.empty()) text += '\n';
    text += format(d);
  }
  return text;
}

GraphError::GraphError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join_lines(diagnostics)), diagnostics_(std::move(diagnostics)) {}

GraphError::GraphError(Diagnostic diagnostic)
    : GraphError(std::vector<Diagnostic>{std::move(diagnostic)}) {}

void DiagnosticList::add(Diagnostic d) {
  const std::string text = format(d);
  for (const Diagnostic& existing : items_) {
    if (format(existing) == text) return;
  }
  items_.push_back(std::move(d));
}

void DiagnosticList::error(const SourceLoc& loc, std::string pass, std::string field,
                           std::string message, std::string hint) {
  add(Diagnostic{loc, std::move(pass), std::move(field), std::move(message), std::move(hint)});
}

void DiagnosticList::throw_if_any() const {
  if (!items_.empty()) throw GraphError(items_);
}

size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: insertions, deletions, substitutions and adjacent swaps ("rgab").
  const size_t w = b.size() + 1;
  std::vector<size_t> d((a.size() + 1) * w);
  for (size_t i = 0; i <= a.size(); ++i) d[i * w] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      size_t best =
          std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1, d[(i - 1) * w + j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        best = std::min(best, d[(i - 2) * w + j - 2] + 1);
      }
      d[i * w + j] = best;
    }
  }
  return d[a.size() * w + b.size()];
}

std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::string_view::npos;
  for (const std::string& candidate : candidates) {
    const size_t distance = edit_distance(name, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  // Close enough to be a typo: about a third of the name may differ, at least 2 edits allowed.
  const size_t allowed = std::max<size_t>(2, name.size() / 3);
  if (best.empty() || best_distance == 0 || best_distance > allowed) return {};
  return best;
}

}  // namespace voxgi::graph
