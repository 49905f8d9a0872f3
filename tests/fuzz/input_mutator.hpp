#pragma once
// A deterministic mutator for text inputs (graph, bench and glTF JSON, expressions): the
// mutations a hand-edited or machine-written file goes through when it breaks (a byte changed,
// a token inserted, a span deleted or repeated, an extreme number, a cut-off end). Seeded, so
// a failure reproduces with the same seed and iteration.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace voxgi::test {

class InputMutator {
 public:
  explicit InputMutator(uint32_t seed) : rng_(seed) {}

  // `text` with 1 to 4 mutations applied.
  std::string mutate(std::string text);

 private:
  size_t position(const std::string& text);
  std::mt19937 rng_;
};

// Writes an input that broke a parser next to the test's working directory, so it can be
// replayed; returns the file's path.
std::string keep_failing_input(const std::string& name, const std::string& text);

}  // namespace voxgi::test
