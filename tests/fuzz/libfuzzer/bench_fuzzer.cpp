// libFuzzer target: bench files (apps/voxgi/bench_spec), parsed as if they lay in graphs/ and
// expanded into their configurations, as `voxgi bench --check` does. Every input expands or is
// refused with a GraphError.

#include <cstdint>

#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] { voxgi::fuzz::run_bench(text); });
  return 0;
}
