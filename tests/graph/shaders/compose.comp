#version 460
// Test pass "exec.compose": dst = (values[i] * scale, history.g, frame index, 1).
#include "lib/frame.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, std430) readonly buffer Values { float values[]; };
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D history;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D dst;
layout(set = 0, binding = 3) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { float scale; };
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(dst);
  if (any(greaterThanEqual(p, size))) return;
  float v = values[p.y * size.x + p.x] * scale;
  imageStore(dst, p, vec4(v, imageLoad(history, p).g, frame.clip.w, 1.0));
}
