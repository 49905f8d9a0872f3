#pragma once
// What every libFuzzer target of tests/fuzz/libfuzzer shares: an input must either be accepted
// or refused with the project's located error (GraphError from the JSON reader, graph files and
// bench files, ExpressionError, SceneError). Any other exception aborts, so libFuzzer keeps the
// input as a crash artifact; its type and message are printed first. With VOXGI_FUZZ_VERBOSE
// set, every refusal's message is printed too (to see why a seed is refused).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include <cxxabi.h>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/expression.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::fuzz {

inline std::string type_name(const std::type_info& type) {
  int status = 0;
  char* name = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  std::string text = status == 0 && name ? name : type.name();
  std::free(name);
  return text;
}

[[noreturn]] inline void unexpected(const std::string& what) {
  std::fprintf(stderr, "voxgi fuzz: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs `body`; returns normally when it succeeds or throws a located error.
template <typename Body>
void accept_or_refuse(Body&& body) {
  static const bool verbose = std::getenv("VOXGI_FUZZ_VERBOSE") != nullptr;
  try {
    body();
  } catch (const graph::GraphError& e) {
    if (verbose) std::fprintf(stderr, "refused: %s\n", e.what());
  } catch (const graph::ExpressionError& e) {
    if (verbose) std::fprintf(stderr, "refused: %s\n", e.what());
  } catch (const scene::SceneError& e) {
    if (verbose) std::fprintf(stderr, "refused: %s\n", e.what());
  } catch (const std::exception& e) {
    unexpected("unexpected exception " + type_name(typeid(e)) + ": " + e.what());
  } catch (...) {
    unexpected("unexpected exception of a type not derived from std::exception");
  }
}

inline std::string text_of(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace voxgi::fuzz
