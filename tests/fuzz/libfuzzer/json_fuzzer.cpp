// libFuzzer target: the JSON reader of graph and bench files (engine/graph/json). Every input
// parses or is refused with a located GraphError; a parsed number written back with
// number_text must read back as the same number (graph files and --set round-trip through it).

#include <cmath>
#include <cstdint>
#include <string>

#include "engine/graph/json.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

namespace {

using voxgi::graph::json::Value;

void check_numbers(const Value& value) {
  if (value.is_number() && std::isfinite(value.as_number())) {
    const std::string text = voxgi::graph::json::number_text(value.as_number());
    const double back = voxgi::graph::json::parse(text, "number_text").as_number();
    if (back != value.as_number()) {
      voxgi::fuzz::unexpected("number_text(" + text + ") does not read back as the same number");
    }
  } else if (value.is_array()) {
    for (const Value& item : value.items()) check_numbers(item);
  } else if (value.is_object()) {
    for (const auto& member : value.members()) check_numbers(member.value);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse(
      [&] { check_numbers(voxgi::graph::json::parse(text, "fuzz.json")); });
  return 0;
}
