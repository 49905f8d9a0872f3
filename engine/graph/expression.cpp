#include "engine/graph/expression.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::graph {

struct Expression::Node {
  enum class Op { Number, Param, Identifier, Negate, Not, Binary, Call };
  Op op = Op::Number;
  std::string binary_op;  // "+", "&&", "<=", ...; Call: "min" or "max"
  double number = 0.0;
  std::string name;
  int column = 1;
  std::unique_ptr<Node> lhs, rhs;
};

namespace {

using Node = Expression::Node;

// Bounds on what one expression may hold. Parsing, evaluation and destruction recurse over the
// tree, so a file with thousands of nested parentheses or summed terms must be refused, not
// overflow the stack. Graph expressions are a few terms long.
constexpr int kMaxNesting = 256;  // parentheses, unary operators and calls inside each other
constexpr int kMaxNodes = 4096;   // numbers, names, operators and calls

// Precedence climbing, lowest first: || && (== !=) (< <= > >=) (+ -) (* /) unary.
class ExprParser {
 public:
  explicit ExprParser(std::string_view text) : text_(text) {}

  std::unique_ptr<Node> parse_all() {
    skip_space();
    if (at_end()) throw ExpressionError(1, "empty expression");
    auto node = parse_binary(0);
    skip_space();
    if (!at_end()) {
      throw ExpressionError(column(), "unexpected '" + std::string(1, text_[pos_]) +
                                          "': expected an operator or the end");
    }
    return node;
  }

 private:
  static const std::vector<std::vector<std::string>>& levels() {
    static const std::vector<std::vector<std::string>> table = {
        {"||"}, {"&&"}, {"==", "!="}, {"<=", ">=", "<", ">"}, {"+", "-"}, {"*", "/"}};
    return table;
  }

  // A counted node; refuses expressions beyond kMaxNodes.
  std::unique_ptr<Node> make_node() {
    if (++nodes_ > kMaxNodes) {
      throw ExpressionError(column(), "expression too long: more than " +
                                          std::to_string(kMaxNodes) + " values and operators");
    }
    auto node = std::make_unique<Node>();
    node->column = column();
    return node;
  }

  // Counts one level of nesting while alive; refuses more than kMaxNesting.
  class NestingGuard {
   public:
    explicit NestingGuard(ExprParser& parser) : parser_(parser) {
      if (++parser_.nesting_ > kMaxNesting) {
        throw ExpressionError(parser_.column(), "expression nested too deeply: more than " +
                                                    std::to_string(kMaxNesting) + " levels");
      }
    }
    ~NestingGuard() { --parser_.nesting_; }
    NestingGuard(const NestingGuard&) = delete;
    NestingGuard& operator=(const NestingGuard&) = delete;

   private:
    ExprParser& parser_;
  };

  bool at_end() const { return pos_ >= text_.size(); }
  int column() const { return static_cast<int>(pos_) + 1; }
  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  std::unique_ptr<Node> parse_binary(size_t level) {
    if (level == levels().size()) return parse_unary();
    auto lhs = parse_binary(level + 1);
    while (true) {
      skip_space();
      const std::string* matched = nullptr;
      for (const std::string& op : levels()[level]) {
        if (text_.substr(pos_, op.size()) == op) {
          matched = &op;
          break;
        }
      }
      if (!matched) return lhs;
      auto node = make_node();
      node->op = Node::Op::Binary;
      node->binary_op = *matched;
      pos_ += matched->size();
      node->lhs = std::move(lhs);
      node->rhs = parse_binary(level + 1);
      lhs = std::move(node);
    }
  }

  std::unique_ptr<Node> parse_unary() {
    skip_space();
    if (at_end()) throw ExpressionError(column(), "expected a value, found the end");
    const char c = text_[pos_];
    const NestingGuard nesting(*this);
    auto node = make_node();
    if (c == '-' || c == '!') {
      // "!=" never starts a value, so a '!' here is always logical not.
      ++pos_;
      node->op = c == '-' ? Node::Op::Negate : Node::Op::Not;
      node->lhs = parse_unary();
      return node;
    }
    if (c == '(') {
      const int open_column = column();
      ++pos_;
      auto inner = parse_binary(0);
      skip_space();
      if (at_end() || text_[pos_] != ')') {
        throw ExpressionError(column(),
                              "expected ')' to close '(' at column " + std::to_string(open_column));
      }
      ++pos_;
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      char* end = nullptr;
      // A number is short; copy a bounded prefix for strtod rather than the rest of the text.
      const std::string copy(text_.substr(pos_, 64));
      node->number = std::strtod(copy.c_str(), &end);
      const size_t used = static_cast<size_t>(end - copy.c_str());
      if (used == 0) throw ExpressionError(column(), "malformed number");
      pos_ += used;
      node->op = Node::Op::Number;
      return node;
    }
    if (c == '$') {
      if (pos_ + 1 >= text_.size() || text_[pos_ + 1] != '{') {
        throw ExpressionError(column(), "expected '{' after '$' (parameters are written ${name})");
      }
      const size_t close = text_.find('}', pos_);
      if (close == std::string_view::npos) {
        throw ExpressionError(column(), "unterminated ${...}: expected '}'");
      }
      node->op = Node::Op::Param;
      node->name = std::string(text_.substr(pos_ + 2, close - pos_ - 2));
      if (node->name.empty()) throw ExpressionError(column(), "empty parameter name in ${}");
      pos_ = close + 1;
      return node;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const size_t start = pos_;
      while (!at_end() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) ||
                           text_[pos_] == '_' || text_[pos_] == '.')) {
        ++pos_;
      }
      node->name = std::string(text_.substr(start, pos_ - start));
      skip_space();
      if (!at_end() && text_[pos_] == '(') return parse_call(std::move(node));
      if (node->name == "true" || node->name == "false") {
        node->op = Node::Op::Number;
        node->number = node->name == "true" ? 1.0 : 0.0;
      } else {
        node->op = Node::Op::Identifier;
      }
      return node;
    }
    throw ExpressionError(column(), "unexpected '" + std::string(1, c) + "': expected a value");
  }

  // min(a, b) and max(a, b): sizes that follow the scene, e.g. max(1, scene.light_count).
  std::unique_ptr<Node> parse_call(std::unique_ptr<Node> node) {
    if (node->name != "min" && node->name != "max") {
      throw ExpressionError(node->column, "unknown function '" + node->name + "'",
                            did_you_mean(node->name, {"min", "max"}));
    }
    node->op = Node::Op::Call;
    node->binary_op = node->name;
    ++pos_;  // '('
    node->lhs = parse_binary(0);
    skip_space();
    if (at_end() || text_[pos_] != ',') {
      throw ExpressionError(column(), "expected ',' between the two arguments of " + node->name);
    }
    ++pos_;
    node->rhs = parse_binary(0);
    skip_space();
    if (at_end() || text_[pos_] != ')') {
      throw ExpressionError(column(), "expected ')' after the arguments of " + node->name);
    }
    ++pos_;
    return node;
  }

  std::string_view text_;
  size_t pos_ = 0;
  int nodes_ = 0;
  int nesting_ = 0;
};

std::vector<std::string> keys_of(const std::map<std::string, double>& map) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : map) keys.push_back(key);
  return keys;
}

double eval(const Node& n, const ExpressionEnv& env) {
  switch (n.op) {
    case Node::Op::Number:
      return n.number;
    case Node::Op::Param: {
      auto it = env.params.find(n.name);
      if (it == env.params.end()) {
        throw ExpressionError(n.column, "unknown parameter '${" + n.name + "}'",
                              did_you_mean(n.name, keys_of(env.params)));
      }
      return it->second;
    }
    case Node::Op::Identifier: {
      auto it = env.identifiers.find(n.name);
      if (it == env.identifiers.end()) {
        for (const auto& [prefix, kind] : env.identifier_families) {
          if (n.name.compare(0, prefix.size(), prefix) != 0) continue;
          std::vector<std::string> known;
          for (const auto& [name, value] : env.identifiers) {
            if (name.compare(0, prefix.size(), prefix) == 0) known.push_back(name);
          }
          std::string list;
          for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
          throw ExpressionError(n.column,
                                "unknown " + kind + " '" + n.name + "' (known: " + list + ")",
                                did_you_mean(n.name, known));
        }
        throw ExpressionError(
            n.column,
            "unknown " + env.identifier_kind + " '" + n.name + "'" +
                (env.identifier_help.empty() ? std::string() : " (" + env.identifier_help + ")"),
            did_you_mean(n.name, keys_of(env.identifiers)));
      }
      return it->second;
    }
    case Node::Op::Negate:
      return -eval(*n.lhs, env);
    case Node::Op::Not:
      return eval(*n.lhs, env) == 0.0 ? 1.0 : 0.0;
    case Node::Op::Call: {
      const double a = eval(*n.lhs, env);
      const double b = eval(*n.rhs, env);
      return n.binary_op == "min" ? std::min(a, b) : std::max(a, b);
    }
    case Node::Op::Binary:
      break;
  }
  const std::string& op = n.binary_op;
  // No short-circuit: a misspelt name must be reported even when the other side decides.
  const double a = eval(*n.lhs, env);
  const double b = eval(*n.rhs, env);
  if (op == "||") return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
  if (op == "&&") return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
  if (op == "==") return a == b ? 1.0 : 0.0;
  if (op == "!=") return a != b ? 1.0 : 0.0;
  if (op == "<") return a < b ? 1.0 : 0.0;
  if (op == "<=") return a <= b ? 1.0 : 0.0;
  if (op == ">") return a > b ? 1.0 : 0.0;
  if (op == ">=") return a >= b ? 1.0 : 0.0;
  if (op == "+") return a + b;
  if (op == "-") return a - b;
  if (op == "*") return a * b;
  if (b == 0.0) throw ExpressionError(n.column, "division by zero");
  return a / b;
}

void collect_identifiers(const Node& n, std::vector<std::string>& names) {
  if (n.op == Node::Op::Identifier &&
      std::find(names.begin(), names.end(), n.name) == names.end()) {
    names.push_back(n.name);
  }
  if (n.lhs) collect_identifiers(*n.lhs, names);
  if (n.rhs) collect_identifiers(*n.rhs, names);
}

}  // namespace

std::vector<std::string> Expression::identifiers() const {
  std::vector<std::string> names;
  if (root_) collect_identifiers(*root_, names);
  return names;
}

Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;
Expression::~Expression() = default;

Expression Expression::parse(std::string_view text) {
  Expression e;
  e.text_ = std::string(text);
  e.root_ = ExprParser(e.text_).parse_all();
  return e;
}

double Expression::evaluate(const ExpressionEnv& env) const {
  const double value = eval(*root_, env);
  if (!std::isfinite(value)) throw ExpressionError(1, "the result is not a finite number");
  return value;
}

double evaluate_expression(std::string_view text, const ExpressionEnv& env) {
  return Expression::parse(text).evaluate(env);
}

}  // namespace voxgi::graph
