// A shared library without the plugin entry points: the loader must name what is missing.
#include <cstdint>

extern "C" __attribute__((visibility("default"))) uint32_t not_a_voxgi_plugin() {
  return 7;
}
