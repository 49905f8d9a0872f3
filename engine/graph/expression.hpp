#pragma once
// The one expression language of graph files, used for sizes ("viewport/2", "${res} * 2") and
// for `when` conditions ("scene.has_glossy && ${vct.specular}"). Values are doubles; a
// comparison or logical operator yields 1 or 0 and any non-zero value is true.

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace voxgi::graph {

// A parse or evaluation error; column is 1-based inside the expression text.
class ExpressionError : public std::runtime_error {
 public:
  ExpressionError(int column, const std::string& message, std::string hint = {})
      : std::runtime_error(message), column_(column), hint_(std::move(hint)) {}
  int column() const { return column_; }
  const std::string& hint() const { return hint_; }  // did-you-mean, may be empty

 private:
  int column_;
  std::string hint_;
};

// What names mean while evaluating.
struct ExpressionEnv {
  std::map<std::string, double> params;       // ${name}
  std::map<std::string, double> identifiers;  // bare names: "viewport.width", "scene.has_sky"
  // Shown in "unknown identifier" errors, e.g. "scene feature", and what is allowed instead.
  std::string identifier_kind = "identifier";
  std::string identifier_help;
  // Names under a prefix that form a closed set, e.g. "device." → "device feature": an unknown
  // name under the prefix is reported as that kind, with every known name of the prefix listed.
  std::map<std::string, std::string> identifier_families;
};

class Expression {
 public:
  struct Node;

  // Throws ExpressionError.
  static Expression parse(std::string_view text);

  // Throws ExpressionError for unknown names, division by zero and non-finite results.
  double evaluate(const ExpressionEnv& env) const;
  const std::string& text() const { return text_; }
  // The bare names the expression reads, each once, in order of appearance.
  std::vector<std::string> identifiers() const;

  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;
  ~Expression();

 private:
  Expression() = default;
  std::string text_;
  std::unique_ptr<Node> root_;
};

// Parses and evaluates in one go.
double evaluate_expression(std::string_view text, const ExpressionEnv& env);

}  // namespace voxgi::graph
