// libFuzzer target: bench files (apps/voxgi/bench_spec), parsed as if they lay in graphs/ and
// expanded into their configurations, as `voxgi bench --check` does. Every input expands or is
// refused with a GraphError.

#include <cstdint>
#include <filesystem>
#include <string>

#include "apps/voxgi/bench_spec.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path repo = VOXGI_SOURCE_DIR;
  static const std::filesystem::path file = repo / "graphs" / "fuzz-bench.json";
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] {
    const voxgi::cli::BenchSpec spec = voxgi::cli::parse_bench(text, file, repo);
    voxgi::cli::expand_configurations(spec);
  });
  return 0;
}
