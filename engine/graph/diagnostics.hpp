#pragma once
// Source locations and error reports for graph files. Every problem the graph layer finds is a
// Diagnostic; a GraphError carries all of them so that one run reports every mistake at once.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace voxgi::graph {

struct SourceLoc {
  std::string file;
  int line = 0;
  int column = 0;
  // For a location inside a graph fragment: where it was included from, innermost first
  // ("graphs/vct.json:40:7"), one entry per level of inclusion.
  std::vector<std::string> included_from;
};

// "file:line:col" (as much of it as is known).
std::string format_location(const SourceLoc& loc);

struct Diagnostic {
  SourceLoc loc;
  std::string pass;   // the pass the problem is in, if any
  std::string field;  // e.g. "out.albedo", "params.aperture", "size"
  std::string message;
  std::string hint;  // a did-you-mean suggestion (just the name), if any
};

// A diagnostic with just a message; the catcher adds where it happened.
Diagnostic message_only(std::string message, std::string hint = {});

// "file:line:col: error: pass 'p' field 'f': message (did you mean 'x'?)", followed by one
// "  included from file:line:col" line per level when the location is inside a fragment.
std::string format(const Diagnostic& d);

// Executor::set_param for a parameter that sizes the pass's outputs (ParamSpec::sizes_outputs):
// the change needs the graph compiled again (runtime::GraphInstance::set_param does that).
class ParamNeedsRecompile : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GraphError : public std::runtime_error {
 public:
  explicit GraphError(std::vector<Diagnostic> diagnostics);
  explicit GraphError(Diagnostic diagnostic);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// Collects diagnostics, dropping exact repeats, so each problem is reported once.
class DiagnosticList {
 public:
  void add(Diagnostic d);
  void error(const SourceLoc& loc, std::string pass, std::string field, std::string message,
             std::string hint = {});
  bool empty() const { return items_.empty(); }
  size_t size() const { return items_.size(); }
  const std::vector<Diagnostic>& items() const { return items_; }
  // Throws GraphError with everything collected, if anything was.
  void throw_if_any() const;

 private:
  std::vector<Diagnostic> items_;
};

size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `name` if it is close enough to be a likely typo, else "".
std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace voxgi::graph
