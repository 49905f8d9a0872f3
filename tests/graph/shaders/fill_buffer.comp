#version 460
// Test pass "exec.fill": values[i] = value + i.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) writeonly buffer Values { float values[]; };
layout(push_constant) uniform Push { float value; uint count; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < count) values[i] = value + float(i);
}
