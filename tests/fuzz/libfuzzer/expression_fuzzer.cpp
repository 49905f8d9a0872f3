// libFuzzer target: the expression language of sizes and `when` conditions
// (engine/graph/expression). Every input parses and evaluates or is refused with an
// ExpressionError; the names it may read are those of a graph with two parameters.

#include <cstdint>

#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] { voxgi::fuzz::run_expression(text); });
  return 0;
}
