#version 460
// Test pass "example.mark", dispatched indirectly with one group per hit: marks the group.
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) buffer Marks { uint marks[64]; };
void main() {
  marks[gl_WorkGroupID.x] = gl_WorkGroupID.x + 1u;
}
