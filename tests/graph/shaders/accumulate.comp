#version 460
// Test pass "exec.accumulate": adds 1 to every texel of a persistent image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform image2D acc;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(acc)))) return;
  imageStore(acc, p, imageLoad(acc, p) + vec4(1.0));
}
