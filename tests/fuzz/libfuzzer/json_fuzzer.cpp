// libFuzzer target: the JSON reader of graph and bench files (engine/graph/json). Every input
// parses or is refused with a located GraphError; a parsed number written back with
// number_text must read back as the same number (graph files and --set round-trip through it).

#include <cstdint>

#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] { voxgi::fuzz::run_json(text); });
  return 0;
}
