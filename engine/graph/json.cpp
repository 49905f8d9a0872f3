#include "engine/graph/json.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace voxgi::graph::json {

Value Value::make_null(SourceLoc loc) {
  Value v;
  v.loc_ = std::move(loc);
  return v;
}

Value Value::make_bool(bool b, SourceLoc loc) {
  Value v = make_null(std::move(loc));
  v.kind_ = Kind::Bool;
  v.bool_ = b;
  return v;
}

Value Value::make_number(double n, SourceLoc loc) {
  Value v = make_null(std::move(loc));
  v.kind_ = Kind::Number;
  v.number_ = n;
  return v;
}

Value Value::make_string(std::string s, SourceLoc loc) {
  Value v = make_null(std::move(loc));
  v.kind_ = Kind::String;
  v.string_ = std::move(s);
  return v;
}

Value Value::make_array(std::vector<Value> items, SourceLoc loc) {
  Value v = make_null(std::move(loc));
  v.kind_ = Kind::Array;
  v.items_ = std::move(items);
  return v;
}

Value Value::make_object(std::vector<Member> members, SourceLoc loc) {
  Value v = make_null(std::move(loc));
  v.kind_ = Kind::Object;
  v.members_ = std::move(members);
  return v;
}

std::string number_text(double value) {
  char text[32];
  if (std::floor(value) == value && std::fabs(value) < 1e15) {
    std::snprintf(text, sizeof text, "%.0f", value);
  } else {
    std::snprintf(text, sizeof text, "%.17g", value);
  }
  return text;
}

const char* kind_name(Value::Kind kind) {
  switch (kind) {
    case Value::Kind::Null:
      return "null";
    case Value::Kind::Bool:
      return "a boolean";
    case Value::Kind::Number:
      return "a number";
    case Value::Kind::String:
      return "a string";
    case Value::Kind::Array:
      return "an array";
    case Value::Kind::Object:
      return "an object";
  }
  return "?";
}

static GraphError wrong_kind(const Value& v, const char* expected) {
  Diagnostic d =
      message_only(std::string("expected ") + expected + ", found " + kind_name(v.kind()));
  d.loc = v.loc();
  return GraphError(std::move(d));
}

double Value::as_number() const {
  if (kind_ != Kind::Number) throw wrong_kind(*this, "a number");
  return number_;
}

const std::string& Value::as_string() const {
  if (kind_ != Kind::String) throw wrong_kind(*this, "a string");
  return string_;
}

bool Value::as_bool() const {
  if (kind_ != Kind::Bool) throw wrong_kind(*this, "a boolean");
  return bool_;
}

const std::vector<Value>& Value::items() const {
  if (kind_ != Kind::Array) throw wrong_kind(*this, "an array");
  return items_;
}

const std::vector<Member>& Value::members() const {
  if (kind_ != Kind::Object) throw wrong_kind(*this, "an object");
  return members_;
}

const Value* Value::find(std::string_view key) const {
  for (const Member& m : members_) {
    if (m.key == key) return &m.value;
  }
  return nullptr;
}

namespace {

// Recursive descent over the text; line and column are tracked as it advances.
class Parser {
 public:
  Parser(std::string_view text, const std::string& file,
         const std::vector<std::string>& included_from)
      : text_(text), file_(file), included_from_(included_from) {}

  Value parse_document() {
    skip_space();
    if (at_end()) fail("expected a JSON value, found end of file");
    Value v = parse_value(0);
    skip_space();
    if (!at_end()) fail("unexpected text after the top-level value");
    return v;
  }

 private:
  static constexpr int kMaxDepth = 256;

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  SourceLoc here() const { return SourceLoc{file_, line_, column_, included_from_}; }

  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

  [[noreturn]] void fail(const std::string& message) const { fail_at(here(), message); }
  [[noreturn]] void fail_at(const SourceLoc& loc, const std::string& message) const {
    Diagnostic d = message_only(message);
    d.loc = loc;
    throw GraphError(std::move(d));
  }

  void skip_space() {
    while (!at_end()) {
      const char c = peek();
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        advance();
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
        while (!at_end() && peek() != '\n') advance();
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
        const SourceLoc start = here();
        advance();
        advance();
        while (!(peek() == '*' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/')) {
          if (at_end()) fail_at(start, "unterminated /* comment");
          advance();
        }
        advance();
        advance();
      } else {
        break;
      }
    }
  }

  std::string describe_next() const {
    if (at_end()) return "end of file";
    return std::string("'") + peek() + "'";
  }

  Value parse_value(int depth) {
    if (depth > kMaxDepth) fail("values nested too deeply");
    const char c = peek();
    if (c == '{') return parse_object(depth);
    if (c == '[') return parse_array(depth);
    if (c == '"') {
      const SourceLoc loc = here();
      return Value::make_string(parse_string(), loc);
    }
    if (c == '-' || (c >= '0' && c <= '9')) return parse_number();
    if (c == 't' || c == 'f' || c == 'n') return parse_word();
    fail("expected a value (object, array, string, number, true, false or null), found " +
         describe_next());
  }

  Value parse_word() {
    const SourceLoc loc = here();
    std::string word;
    while (!at_end() && std::isalpha(static_cast<unsigned char>(peek()))) {
      word += peek();
      advance();
    }
    if (word == "true") return Value::make_bool(true, loc);
    if (word == "false") return Value::make_bool(false, loc);
    if (word == "null") return Value::make_null(loc);
    fail_at(loc, "expected a value, found '" + word + "' (strings need double quotes)");
  }

  Value parse_number() {
    const SourceLoc loc = here();
    const size_t start = pos_;
    if (peek() == '-') advance();
    if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a digit");
    while (std::isdigit(static_cast<unsigned char>(peek()))) advance();
    if (peek() == '.') {
      advance();
      if (!std::isdigit(static_cast<unsigned char>(peek())))
        fail("expected a digit after the decimal point");
      while (std::isdigit(static_cast<unsigned char>(peek()))) advance();
    }
    if (peek() == 'e' || peek() == 'E') {
      advance();
      if (peek() == '+' || peek() == '-') advance();
      if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a digit in exponent");
      while (std::isdigit(static_cast<unsigned char>(peek()))) advance();
    }
    const std::string digits(text_.substr(start, pos_ - start));
    errno = 0;
    const double value = std::strtod(digits.c_str(), nullptr);
    if (errno == ERANGE) fail_at(loc, "number out of range: " + digits);
    return Value::make_number(value, loc);
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  unsigned parse_hex4() {
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = peek();
      code <<= 4;
      if (h >= '0' && h <= '9') {
        code |= static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        code |= static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        code |= static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("expected 4 hex digits after \\u");
      }
      advance();
    }
    return code;
  }

  std::string parse_string() {
    const SourceLoc start = here();
    advance();  // opening quote
    std::string out;
    while (true) {
      if (at_end() || peek() == '\n') fail_at(start, "unterminated string");
      const char c = peek();
      if (c == '"') {
        advance();
        return out;
      }
      if (c == '\\') {
        advance();
        const char e = peek();
        switch (e) {
          case '"':
            out += '"';
            break;
          case '\\':
            out += '\\';
            break;
          case '/':
            out += '/';
            break;
          case 'b':
            out += '\b';
            break;
          case 'f':
            out += '\f';
            break;
          case 'n':
            out += '\n';
            break;
          case 'r':
            out += '\r';
            break;
          case 't':
            out += '\t';
            break;
          case 'u': {
            advance();
            append_utf8(out, parse_hex4());
            continue;
          }
          default:
            fail("invalid escape sequence in string");
        }
        advance();
        continue;
      }
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      out += c;
      advance();
    }
  }

  Value parse_array(int depth) {
    const SourceLoc loc = here();
    advance();
    std::vector<Value> items;
    skip_space();
    while (peek() != ']') {
      if (at_end()) fail_at(loc, "unterminated array: expected ']'");
      items.push_back(parse_value(depth + 1));
      skip_space();
      if (peek() == ',') {
        advance();
        skip_space();
      } else if (peek() != ']') {
        fail("expected ',' or ']' after array element, found " + describe_next());
      }
    }
    advance();
    return Value::make_array(std::move(items), loc);
  }

  Value parse_object(int depth) {
    const SourceLoc loc = here();
    advance();
    std::vector<Member> members;
    skip_space();
    while (peek() != '}') {
      if (at_end()) fail_at(loc, "unterminated object: expected '}'");
      if (peek() != '"') fail("expected a string key or '}', found " + describe_next());
      Member m;
      m.key_loc = here();
      m.key = parse_string();
      for (const Member& other : members) {
        if (other.key == m.key) {
          fail_at(m.key_loc, "duplicate key '" + m.key + "' (first at line " +
                                 std::to_string(other.key_loc.line) + ")");
        }
      }
      skip_space();
      if (peek() != ':') fail("expected ':' after object key, found " + describe_next());
      advance();
      skip_space();
      m.value = parse_value(depth + 1);
      members.push_back(std::move(m));
      skip_space();
      if (peek() == ',') {
        advance();
        skip_space();
      } else if (peek() != '}') {
        fail("expected ',' or '}' after object member, found " + describe_next());
      }
    }
    advance();
    return Value::make_object(std::move(members), loc);
  }

  std::string_view text_;
  const std::string& file_;
  const std::vector<std::string>& included_from_;
  size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

}  // namespace

Value parse(std::string_view text, const std::string& file_name,
            const std::vector<std::string>& included_from) {
  return Parser(text, file_name, included_from).parse_document();
}

}  // namespace voxgi::graph::json
