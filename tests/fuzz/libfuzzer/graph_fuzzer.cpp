// libFuzzer target: graph files, parsed (includes resolved next to the shipped graphs) and
// compiled against the real pass types of the plugins for the built-in Cornell box at 64 x 64,
// as `voxgi graph check` does; no GPU. Every input compiles or is refused with a GraphError.

#include <cstdint>
#include <exception>
#include <memory>
#include <string>

#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

namespace {

const voxgi::fuzz::GraphInput& graph_input() {
  static const std::unique_ptr<voxgi::fuzz::GraphInput> input = [] {
    try {
      return std::make_unique<voxgi::fuzz::GraphInput>();
    } catch (const std::exception& e) {
      voxgi::fuzz::unexpected(std::string("cannot load the pass plugins: ") + e.what());
    }
  }();
  return *input;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const voxgi::fuzz::GraphInput& input = graph_input();
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] { input.run(text); });
  return 0;
}
