#pragma once
// A 64-bit FNV-1a hash for cache keys: stable across runs and machines, not cryptographic.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace voxgi::cli {

class Hasher {
 public:
  Hasher& add_bytes(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      state_ ^= bytes[i];
      state_ *= 0x100000001b3ull;
    }
    return *this;
  }
  // Strings are length-prefixed so that ("ab", "c") and ("a", "bc") differ.
  Hasher& add(std::string_view text) {
    const uint64_t size = text.size();
    add_bytes(&size, sizeof size);
    return add_bytes(text.data(), text.size());
  }
  template <typename T>
  Hasher& add_value(const T& value) {
    return add_bytes(&value, sizeof value);
  }
  // The file's bytes; false (and nothing added but a marker) when it cannot be read.
  bool add_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      add("<unreadable>");
      return false;
    }
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
      add_bytes(buffer, static_cast<size_t>(in.gcount()));
    }
    return true;
  }
  uint64_t value() const { return state_; }
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
    return text;
  }

 private:
  uint64_t state_ = 0xcbf29ce484222325ull;
};

}  // namespace voxgi::cli
