#include <gtest/gtest.h>

#include "engine/graph/expression.hpp"

namespace voxgi::graph {
namespace {

ExpressionEnv env() {
  ExpressionEnv e;
  e.params = {{"res", 64}, {"on", 1}, {"off", 0}};
  e.identifiers = {{"viewport", 800},
                   {"viewport.width", 800},
                   {"viewport.height", 600},
                   {"scene.has_glossy", 1},
                   {"scene.light_count", 3}};
  e.identifier_kind = "scene feature";
  return e;
}

double eval(const std::string& text) {
  return evaluate_expression(text, env());
}

ExpressionError error_of(const std::string& text) {
  try {
    eval(text);
  } catch (const ExpressionError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << text;
  return ExpressionError(0, "");
}

TEST(Expression, ArithmeticAndPrecedence) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9);
  EXPECT_DOUBLE_EQ(eval("10 - 4 - 3"), 3);
  EXPECT_DOUBLE_EQ(eval("64 / 4 / 2"), 8);
  EXPECT_DOUBLE_EQ(eval("-2 * -3"), 6);
  EXPECT_DOUBLE_EQ(eval("6 * 4"), 24);
  EXPECT_DOUBLE_EQ(eval("0.5 * 3"), 1.5);
}

TEST(Expression, ViewportAndParameters) {
  EXPECT_DOUBLE_EQ(eval("viewport/2"), 400);
  EXPECT_DOUBLE_EQ(eval("viewport.height / 2 + viewport.width"), 1100);
  EXPECT_DOUBLE_EQ(eval("${res} * 2"), 128);
}

TEST(Expression, MinAndMaxFollowTheScene) {
  EXPECT_DOUBLE_EQ(eval("6 * max(1, min(scene.light_count, ${res}))"), 18);
  EXPECT_DOUBLE_EQ(eval("max(1, scene.light_count - 5)"), 1);
  EXPECT_DOUBLE_EQ(eval("min ( 2 + 2 , 3 )"), 3);
  ExpressionError e = error_of("mx(1, 2)");
  EXPECT_EQ(e.column(), 1);
  EXPECT_STREQ(e.what(), "unknown function 'mx'");
  EXPECT_EQ(e.hint(), "max");
  e = error_of("min(1 2)");
  EXPECT_EQ(e.column(), 7);
  e = error_of("max(1, 2");
  EXPECT_EQ(e.column(), 9);
}

TEST(Expression, Conditions) {
  EXPECT_DOUBLE_EQ(eval("scene.has_glossy && ${on}"), 1);
  EXPECT_DOUBLE_EQ(eval("scene.has_glossy && ${off}"), 0);
  EXPECT_DOUBLE_EQ(eval("!scene.has_glossy || ${on}"), 1);
  EXPECT_DOUBLE_EQ(eval("!(scene.has_glossy || ${on})"), 0);
  EXPECT_DOUBLE_EQ(eval("scene.light_count >= 3"), 1);
  EXPECT_DOUBLE_EQ(eval("scene.light_count > 3"), 0);
  EXPECT_DOUBLE_EQ(eval("scene.light_count <= 2"), 0);
  EXPECT_DOUBLE_EQ(eval("scene.light_count < 4"), 1);
  EXPECT_DOUBLE_EQ(eval("scene.light_count == 3 && ${res} != 32"), 1);
  EXPECT_DOUBLE_EQ(eval("1 + 1 == 2"), 1);   // arithmetic binds tighter than comparison
  EXPECT_DOUBLE_EQ(eval("0 || 1 && 0"), 0);  // && binds tighter than ||
  EXPECT_DOUBLE_EQ(eval("true && !false"), 1);
}

TEST(Expression, ErrorsGiveColumns) {
  ExpressionError e = error_of("1 + scene.has_glosy");
  EXPECT_EQ(e.column(), 5);
  EXPECT_STREQ(e.what(), "unknown scene feature 'scene.has_glosy'");
  EXPECT_EQ(e.hint(), "scene.has_glossy");

  e = error_of("${re} * 2");
  EXPECT_EQ(e.column(), 1);
  EXPECT_STREQ(e.what(), "unknown parameter '${re}'");
  EXPECT_EQ(e.hint(), "res");

  e = error_of("(1 + 2");
  EXPECT_EQ(e.column(), 7);
  EXPECT_STREQ(e.what(), "expected ')' to close '(' at column 1");

  e = error_of("1 + * 2");
  EXPECT_EQ(e.column(), 5);

  e = error_of("4 / (2 - 2)");
  EXPECT_EQ(e.column(), 3);
  EXPECT_STREQ(e.what(), "division by zero");

  e = error_of("2 3");
  EXPECT_EQ(e.column(), 3);

  e = error_of("$res");
  EXPECT_EQ(e.column(), 1);

  e = error_of("${res");
  EXPECT_EQ(e.column(), 1);

  e = error_of("   ");
  EXPECT_EQ(e.column(), 1);
  EXPECT_STREQ(e.what(), "empty expression");

  e = error_of("1 # 2");
  EXPECT_EQ(e.column(), 3);
}

// Expressions recurse when parsed, evaluated and destroyed: nesting and length are bounded
// with a located error instead of overflowing the stack.
TEST(Expression, HugeExpressionsAreRefusedNotCrashed) {
  const std::string parentheses = std::string(5000, '(') + "1" + std::string(5000, ')');
  ExpressionError e = error_of(parentheses);
  EXPECT_EQ(e.column(), 257);
  EXPECT_STREQ(e.what(), "expression nested too deeply: more than 256 levels");

  EXPECT_STREQ(error_of(std::string(100000, '-') + "1").what(),
               "expression nested too deeply: more than 256 levels");
  EXPECT_STREQ(error_of(std::string(100000, '!') + "1").what(),
               "expression nested too deeply: more than 256 levels");

  std::string sum = "1";
  for (int i = 0; i < 50000; ++i) sum += "+1";
  e = error_of(sum);
  EXPECT_STREQ(e.what(), "expression too long: more than 4096 values and operators");
  EXPECT_GT(e.column(), 1);

  // Within the bounds, deep and long expressions still evaluate.
  EXPECT_EQ(eval(std::string(200, '(') + "2" + std::string(200, ')')), 2.0);
  std::string long_sum = "0";
  for (int i = 0; i < 1000; ++i) long_sum += " + 1";
  EXPECT_EQ(eval(long_sum), 1000.0);
}

TEST(Expression, UnknownNameOfAClosedFamilyListsTheKnownOnes) {
  ExpressionEnv env;
  env.identifiers = {{"device.ray_query", 1}, {"device.shader_int64", 0}, {"scene.has_sky", 0}};
  env.identifier_kind = "scene feature";
  env.identifier_families["device."] = "device feature";
  try {
    evaluate_expression("scene.has_sky || device.ray_quey", env);
    FAIL() << "expected an error";
  } catch (const ExpressionError& e) {
    EXPECT_EQ(e.column(), 18);
    EXPECT_STREQ(e.what(),
                 "unknown device feature 'device.ray_quey' (known: device.ray_query, "
                 "device.shader_int64)");
    EXPECT_EQ(e.hint(), "device.ray_query");
  }
}

TEST(Expression, IdentifiersAreListedOnceInOrder) {
  const Expression e =
      Expression::parse("device.ray_query && (${res} > 2 || !device.ray_query) && scene.has_sky");
  EXPECT_EQ(e.identifiers(), (std::vector<std::string>{"device.ray_query", "scene.has_sky"}));
}

}  // namespace
}  // namespace voxgi::graph
