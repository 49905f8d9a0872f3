// Parameter values given as text (--set, the viewer), checked against the pass type's spec.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/graph/compiler.hpp"

namespace voxgi::graph {

namespace {

std::string range_text(const ParamSpec& spec) {
  std::string text = "[";
  text += format_number(spec.min);
  text += ", ";
  text += format_number(spec.max);
  text += ']';
  return text;
}

[[noreturn]] void fail(const std::string& key, const std::string& message,
                       const std::string& hint = {}) {
  Diagnostic d = message_only(message, hint);
  d.field = key;
  throw GraphError(std::move(d));
}

}  // namespace

const char* param_type_name(ParamType type) {
  switch (type) {
    case ParamType::Bool:
      return "bool";
    case ParamType::Int:
      return "int";
    case ParamType::Float:
      return "float";
    case ParamType::Enum:
      return "enum";
  }
  return "?";
}

ParamValue parse_param_value(const ParamSpec& spec, const std::string& key,
                             const std::string& text) {
  ParamValue value;
  switch (spec.type) {
    case ParamType::Bool:
      if (text == "true" || text == "1" || text == "on") {
        value.number = 1.0;
      } else if (text == "false" || text == "0" || text == "off") {
        value.number = 0.0;
      } else {
        fail(key, "expected true or false, found '" + text + "'");
      }
      value.text = value.number != 0.0 ? "true" : "false";
      return value;
    case ParamType::Enum:
      for (size_t i = 0; i < spec.choices.size(); ++i) {
        if (spec.choices[i] == text) {
          value.number = static_cast<double>(i);
          value.text = text;
          return value;
        }
      }
      {
        std::string list;
        for (const std::string& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
        fail(key, "expected one of " + list + ", found '" + text + "'",
             did_you_mean(text, spec.choices));
      }
    case ParamType::Int:
    case ParamType::Float: {
      errno = 0;
      char* end = nullptr;
      const double number = std::strtod(text.c_str(), &end);
      const bool parsed =
          !text.empty() && end && *end == '\0' && errno == 0 && std::isfinite(number);
      const bool integer = spec.type == ParamType::Int;
      if (!parsed || (integer && number != std::floor(number))) {
        fail(key, std::string("expected ") + (integer ? "an integer" : "a number") + ", found '" +
                      text + "'");
      }
      return param_from_number(spec, key, number);
    }
  }
  fail(key, "parameter has an unknown type");
}

ParamValue param_from_number(const ParamSpec& spec, const std::string& key, double number) {
  ParamValue value;
  value.number = number;
  switch (spec.type) {
    case ParamType::Bool:
      value.number = number != 0.0 ? 1.0 : 0.0;
      value.text = value.number != 0.0 ? "true" : "false";
      return value;
    case ParamType::Enum: {
      const double index = std::floor(number);
      if (index != number || index < 0 || index >= static_cast<double>(spec.choices.size())) {
        fail(key, "expected a choice name, found the number " + format_number(number));
      }
      value.text = spec.choices[static_cast<size_t>(index)];
      return value;
    }
    case ParamType::Int:
      if (number != std::floor(number)) {
        fail(key, "expected an integer, found " + format_number(number));
      }
      break;
    case ParamType::Float:
      break;
  }
  if (spec.max > spec.min && (number < spec.min || number > spec.max)) {
    fail(key, "value " + format_number(number) + " is out of range " + range_text(spec));
  }
  value.text = format_number(number);
  return value;
}

std::string format_number(double v) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.10g", v);
  return text;
}

}  // namespace voxgi::graph
