// libFuzzer target: glTF files up to the CPU scene (engine/scene/gltf_loader): load_gltf, then
// the scene's instances, bounds, features and one animation step. The loader reads a path, so
// each input is written to a per-process scratch folder ($VOXGI_FUZZ_SCRATCH, else /dev/shm or
// the temp folder). The loader tells GLB from glTF JSON by the "glTF" magic, not by the name,
// so one target covers both: an input is written once, named .glb when it starts with the magic
// and .gltf otherwise, as a user's file would be. Buffers and images an input refers to by
// relative URI are looked up in that folder (data: URIs carry them inside the input).

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "tests/fuzz/fuzz_inputs.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path dir;

  Scratch() {
    fs::path base;
    if (const char* env = std::getenv("VOXGI_FUZZ_SCRATCH"); env && *env) {
      base = env;
    } else if (std::error_code ec; fs::is_directory("/dev/shm", ec)) {
      base = "/dev/shm";
    } else {
      base = fs::temp_directory_path();
    }
    dir = base / ("voxgi-gltf-fuzz-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    if (ec) voxgi::fuzz::unexpected("cannot create " + dir.string() + ": " + ec.message());
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Scratch scratch;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  voxgi::fuzz::accept_or_refuse([&] { voxgi::fuzz::run_gltf(bytes, scratch.dir); });
  return 0;
}
