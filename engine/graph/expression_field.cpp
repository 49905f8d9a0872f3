#include "engine/graph/expression_field.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace voxgi::graph {
namespace {

// An expression as quoted in a message: whole when short, otherwise the part around `column`
// (1-based) with "..." where text was left out, so a huge expression does not flood the error.
std::string quoted_expression(const std::string& text, int column) {
  constexpr size_t kShown = 60;
  if (text.size() <= 2 * kShown) return text;
  const size_t at = static_cast<size_t>(std::max(column, 1) - 1);
  const size_t begin = at > kShown ? at - kShown : 0;
  const size_t end = std::min(text.size(), at + kShown);
  return (begin > 0 ? "..." : "") + text.substr(begin, end - begin) +
         (end < text.size() ? "..." : "");
}

}  // namespace

Diagnostic expression_field_diagnostic(const ExprField& f, std::string pass, std::string field,
                                       const ExpressionError& error) {
  SourceLoc loc = f.loc;
  loc.column += error.column();  // past the opening quote
  return Diagnostic{std::move(loc), std::move(pass), std::move(field),
                    "in expression \"" + quoted_expression(f.text, error.column()) +
                        "\" at column " + std::to_string(error.column()) + ": " + error.what(),
                    error.hint()};
}

double evaluate_field(const ExprField& f, const std::string& field, const ExpressionEnv& env) {
  if (f.is_number) return f.number;
  try {
    return evaluate_expression(f.text, env);
  } catch (const ExpressionError& e) {
    throw GraphError(expression_field_diagnostic(f, {}, field, e));
  }
}

}  // namespace voxgi::graph
