#pragma once
// Reading the text files a user hands voxgi (graph and bench files) with a size bound: a path
// to a device or a huge file ends in a located error instead of reading forever or exhausting
// memory.

#include <cstddef>
#include <filesystem>
#include <string>

namespace voxgi::graph {

// Larger than any hand-written graph or bench file by far.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{16} << 20;

// The whole file as text. Throws GraphError located at `path` when it cannot be opened, is a
// directory, or holds more than `max_bytes`; `what` names the file's role ("graph file").
std::string read_input_file(const std::filesystem::path& path, const std::string& what,
                            std::size_t max_bytes = kMaxInputFileBytes);

}  // namespace voxgi::graph
