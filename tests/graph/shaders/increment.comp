#version 460
// Test pass "exec.increment": dst = previous + 1 (previous: the frame before's dst).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D previous;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D dst;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(dst)))) return;
  imageStore(dst, p, imageLoad(previous, p) + vec4(1.0));
}
