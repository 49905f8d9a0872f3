#include "tests/fuzz/input_mutator.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace voxgi::test {

namespace {

// Tokens that reach the parsers' edge cases: structure, strings, escapes, numbers at and past
// the limits of their types, expressions, references.
const std::vector<std::string> kTokens = {"{",
                                          "}",
                                          "[",
                                          "]",
                                          ",",
                                          ":",
                                          "\"",
                                          "\\",
                                          "\\u0000",
                                          "\\ud800",
                                          "/*",
                                          "*/",
                                          "//",
                                          "\n",
                                          "null",
                                          "true",
                                          "false",
                                          "-",
                                          "0",
                                          "-0",
                                          "1e309",
                                          "-1e309",
                                          "1e-400",
                                          "4294967296",
                                          "2147483647",
                                          "-2147483648",
                                          "9223372036854775808",
                                          "99999999999999999999999",
                                          "0.5",
                                          "NaN",
                                          "Infinity",
                                          "((((((((",
                                          "))))",
                                          "${",
                                          "}",
                                          "${voxel.resolution}",
                                          "scene.light_count",
                                          "max(",
                                          "min(",
                                          "&&",
                                          "||",
                                          "!",
                                          "/ 0",
                                          "* 1e300",
                                          "\"type\"",
                                          "\"size\"",
                                          "\"in\"",
                                          "\"out\"",
                                          "\"when\"",
                                          "\"persistent\"",
                                          "\"mips\"",
                                          "\"uri\"",
                                          "\"bufferView\"",
                                          "\"count\"",
                                          "\"byteLength\"",
                                          "\"byteStride\"",
                                          "\"nodes\"",
                                          "\"children\"",
                                          "\"sweep\"",
                                          "\"scenes\"",
                                          "\xff",
                                          "\xc3\x28",
                                          "\t"};

const std::vector<std::string> kNumbers = {
    "0",      "-1",    "1e309", "-1e309", "4294967296", "2147483647",
    "1e-400", "65536", "3.5",   "-0.0",   "1000000",    "18446744073709551616"};

}  // namespace

size_t InputMutator::position(const std::string& text) {
  return text.empty() ? 0 : std::uniform_int_distribution<size_t>(0, text.size())(rng_);
}

std::string InputMutator::mutate(std::string text) {
  const int count = std::uniform_int_distribution<int>(1, 4)(rng_);
  for (int m = 0; m < count; ++m) {
    const int kind = std::uniform_int_distribution<int>(0, 6)(rng_);
    const size_t at = position(text);
    switch (kind) {
      case 0:  // change one byte
        if (at < text.size())
          text[at] = static_cast<char>(std::uniform_int_distribution<int>(1, 255)(rng_));
        break;
      case 1:  // insert a token
        text.insert(at,
                    kTokens[std::uniform_int_distribution<size_t>(0, kTokens.size() - 1)(rng_)]);
        break;
      case 2: {  // delete a span
        const size_t length = std::uniform_int_distribution<size_t>(1, 16)(rng_);
        if (at < text.size()) text.erase(at, length);
        break;
      }
      case 3: {  // repeat a span
        const size_t length = std::uniform_int_distribution<size_t>(1, 64)(rng_);
        const std::string span = text.substr(at, length);
        const int times = std::uniform_int_distribution<int>(1, 8)(rng_);
        for (int i = 0; i < times; ++i) text.insert(at, span);
        break;
      }
      case 4: {  // replace the next number with an extreme one
        const size_t digit = text.find_first_of("0123456789", at);
        if (digit == std::string::npos) break;
        size_t end = digit;
        while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) ||
                                     text[end] == '.' || text[end] == 'e')) {
          ++end;
        }
        text.replace(digit, end - digit,
                     kNumbers[std::uniform_int_distribution<size_t>(0, kNumbers.size() - 1)(rng_)]);
        break;
      }
      case 5:  // cut off the end
        text.resize(at);
        break;
      default: {  // swap two spans' order (moves fields, brackets)
        const size_t other = position(text);
        if (at < text.size() && other < text.size()) std::swap(text[at], text[other]);
        break;
      }
    }
  }
  return text;
}

std::string keep_failing_input(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::current_path() / ("fuzz-failure-" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

}  // namespace voxgi::test
