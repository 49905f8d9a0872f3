#pragma once
// A graph file's number-or-expression field evaluated, and the diagnostic when its expression
// fails: one message for the graph compiler and for the readers of a graph's metadata (the
// bench's `indirect` declaration).

#include <string>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/expression.hpp"
#include "engine/graph/graph_desc.hpp"

namespace voxgi::graph {

// The diagnostic for `error`, raised by the expression of `f`: placed at the failing column in
// the file, with the expression quoted around that column and the error's did-you-mean hint.
Diagnostic expression_field_diagnostic(const ExprField& f, std::string pass, std::string field,
                                       const ExpressionError& error);

// The field's number, or its expression evaluated in `env`; a failing expression throws
// GraphError with the diagnostic above (no pass; `field` names it).
double evaluate_field(const ExprField& f, const std::string& field, const ExpressionEnv& env);

}  // namespace voxgi::graph
