#include "engine/graph/input_file.hpp"

#include <fstream>
#include <system_error>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::graph {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
  throw GraphError(Diagnostic{SourceLoc{path.string(), 0, 0}, {}, {}, message});
}

}  // namespace

std::string read_input_file(const std::filesystem::path& path, const std::string& what,
                            std::size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail(path, "is a directory, expected a " + what + " (JSON)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the " + what + " (expected a readable JSON file)");
  // Read in pieces and stop one byte past the bound: a device such as /dev/urandom never ends.
  std::string text;
  char buffer[1 << 16];
  while (in && text.size() <= max_bytes) {
    in.read(buffer, sizeof buffer);
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (text.size() > max_bytes) {
    const std::string bound = max_bytes % (std::size_t{1} << 20) == 0
                                  ? std::to_string(max_bytes >> 20) + " MiB"
                                  : std::to_string(max_bytes) + " bytes";
    fail(path, "larger than " + bound + ": not a " + what);
  }
  if (in.bad()) fail(path, "could not be read to the end");
  return text;
}

}  // namespace voxgi::graph
