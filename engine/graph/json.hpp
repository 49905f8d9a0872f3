#pragma once
// A small JSON reader for graph files. Unlike general-purpose libraries it keeps the source
// location of every value and key, so that errors can point at the exact spot in the file.
// Accepts // and /* */ comments and trailing commas.

#include <string>
#include <string_view>
#include <vector>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::graph::json {

struct Member;

class Value {
 public:
  enum class Kind { Null, Bool, Number, String, Array, Object };

  Value() = default;
  static Value make_null(SourceLoc loc);
  static Value make_bool(bool b, SourceLoc loc);
  static Value make_number(double n, SourceLoc loc);
  static Value make_string(std::string s, SourceLoc loc);
  static Value make_array(std::vector<Value> items, SourceLoc loc);
  static Value make_object(std::vector<Member> members, SourceLoc loc);

  Kind kind() const { return kind_; }
  const SourceLoc& loc() const { return loc_; }
  bool is_null() const { return kind_ == Kind::Null; }
  bool is_bool() const { return kind_ == Kind::Bool; }
  bool is_number() const { return kind_ == Kind::Number; }
  bool is_string() const { return kind_ == Kind::String; }
  bool is_array() const { return kind_ == Kind::Array; }
  bool is_object() const { return kind_ == Kind::Object; }

  // These throw GraphError ("expected a number, found a string") at this value's location.
  double as_number() const;
  const std::string& as_string() const;
  bool as_bool() const;
  const std::vector<Value>& items() const;     // array
  const std::vector<Member>& members() const;  // object, in file order

  // Object member by key, nullptr when absent (or when this is not an object).
  const Value* find(std::string_view key) const;

 private:
  Kind kind_ = Kind::Null;
  SourceLoc loc_;
  bool bool_ = false;
  double number_ = 0.0;
  std::string string_;
  std::vector<Value> items_;
  std::vector<Member> members_;
};

struct Member {
  std::string key;
  SourceLoc key_loc;
  Value value;
};

const char* kind_name(Value::Kind kind);

// A number as a graph file or --set writes it: integers without a fraction, others so that
// they read back exactly.
std::string number_text(double value);

// Throws GraphError with one diagnostic "file:line:col: error: <what was expected>". Every
// location gets `included_from` (for a fragment: where it was included, innermost first).
Value parse(std::string_view text, const std::string& file_name,
            const std::vector<std::string>& included_from = {});

}  // namespace voxgi::graph::json
