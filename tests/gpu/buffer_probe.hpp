#pragma once
// Runs a one-invocation compute probe on the test device: storage buffers `input` (binding 0)
// and `output` (binding 1) and a uint push constant (the element count). GLSL libraries are
// tested this way: the probe includes them and writes what they return.

#include <cstdint>
#include <string>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/shader_compiler.hpp"

namespace voxgi::test {

void run_buffer_probe(gpu::ShaderCompiler& compiler, const std::string& probe, gpu::Buffer& input,
                      gpu::Buffer& output, uint32_t count);

}  // namespace voxgi::test
