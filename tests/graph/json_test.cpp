#include <gtest/gtest.h>

#include "engine/graph/json.hpp"

namespace voxgi::graph {
namespace {

std::string parse_error(const std::string& text) {
  try {
    json::parse(text, "f.json");
  } catch (const GraphError& e) {
    EXPECT_EQ(e.diagnostics().size(), 1u);
    return e.what();
  }
  ADD_FAILURE() << "no error for: " << text;
  return {};
}

TEST(Json, ParsesValuesInFileOrderWithLocations) {
  const json::Value v = json::parse(R"({
  "b": 1.5e2, "a": [true, false, null],
  "s": "x\"y\u00e9\n",
  "n": -3
})",
                                    "f.json");
  ASSERT_TRUE(v.is_object());
  const auto& m = v.members();
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].key, "b");
  EXPECT_EQ(m[1].key, "a");
  EXPECT_DOUBLE_EQ(m[0].value.as_number(), 150.0);
  EXPECT_EQ(m[0].key_loc.line, 2);
  EXPECT_EQ(m[0].key_loc.column, 3);
  EXPECT_EQ(m[0].value.loc().column, 8);
  EXPECT_EQ(m[0].value.loc().file, "f.json");
  const auto& items = v.find("a")->items();
  ASSERT_EQ(items.size(), 3u);
  EXPECT_TRUE(items[0].as_bool());
  EXPECT_FALSE(items[1].as_bool());
  EXPECT_TRUE(items[2].is_null());
  EXPECT_EQ(items[2].loc().line, 2);
  EXPECT_EQ(items[2].loc().column, 34);
  EXPECT_EQ(v.find("s")->as_string(), "x\"y\xc3\xa9\n");
  EXPECT_DOUBLE_EQ(v.find("n")->as_number(), -3.0);
  EXPECT_EQ(v.find("missing"), nullptr);
}

TEST(Json, AcceptsCommentsAndTrailingCommas) {
  const json::Value v = json::parse(R"(// leading comment
{
  /* block
     comment */ "a": [1, 2,], // trailing
  "b": {"c": 3,},
})",
                                    "f.json");
  EXPECT_EQ(v.find("a")->items().size(), 2u);
  EXPECT_DOUBLE_EQ(v.find("b")->find("c")->as_number(), 3.0);
  EXPECT_EQ(v.find("a")->loc().line, 4);
}

TEST(Json, WrongKindAccessNamesLocation) {
  const json::Value v = json::parse("{\n  \"a\": \"text\"\n}", "f.json");
  try {
    v.find("a")->as_number();
    FAIL();
  } catch (const GraphError& e) {
    EXPECT_STREQ(e.what(), "f.json:2:8: error: expected a number, found a string");
  }
}

TEST(Json, ParseErrorsGiveLineAndColumn) {
  EXPECT_EQ(parse_error("{\n  \"a\": 1\n  \"b\": 2\n}"),
            "f.json:3:3: error: expected ',' or '}' after object member, found '\"'");
  EXPECT_EQ(parse_error("[1 2]"),
            "f.json:1:4: error: expected ',' or ']' after array element, found '2'");
  EXPECT_EQ(parse_error("{\"a\" 1}"),
            "f.json:1:6: error: expected ':' after object key, found '1'");
  EXPECT_EQ(parse_error("{a: 1}"), "f.json:1:2: error: expected a string key or '}', found 'a'");
  EXPECT_EQ(parse_error("{\"a\": tru}"),
            "f.json:1:7: error: expected a value, found 'tru' (strings need double quotes)");
  EXPECT_EQ(parse_error("{\"a\": \"abc"), "f.json:1:7: error: unterminated string");
  EXPECT_EQ(parse_error("{\"a\": 1"),
            "f.json:1:8: error: expected ',' or '}' after object member, found end of file");
  EXPECT_EQ(parse_error("{"), "f.json:1:1: error: unterminated object: expected '}'");
  EXPECT_EQ(parse_error("[1,"), "f.json:1:1: error: unterminated array: expected ']'");
  EXPECT_EQ(parse_error("/* open"), "f.json:1:1: error: unterminated /* comment");
  EXPECT_EQ(parse_error(""), "f.json:1:1: error: expected a JSON value, found end of file");
  EXPECT_EQ(parse_error("{} x"), "f.json:1:4: error: unexpected text after the top-level value");
  EXPECT_EQ(parse_error("{\"a\": 1, \"a\": 2}"),
            "f.json:1:10: error: duplicate key 'a' (first at line 1)");
  EXPECT_EQ(parse_error("[\"\\q\"]"), "f.json:1:4: error: invalid escape sequence in string");
  EXPECT_EQ(parse_error("[-]"), "f.json:1:3: error: expected a digit");
  EXPECT_EQ(parse_error("[1e999]"), "f.json:1:2: error: number out of range: 1e999");
}

TEST(Json, DeepNestingIsAnErrorNotACrash) {
  const std::string deep(100000, '[');
  EXPECT_NE(parse_error(deep).find("nested too deeply"), std::string::npos);
}

}  // namespace
}  // namespace voxgi::graph
