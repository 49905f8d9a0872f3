#version 460
#extension GL_GOOGLE_include_directive : require
// Test probe of contracts/cone_trace.glsl: diffuse irradiance + AO at a point with a normal, or the
// radiance and opacity of one cone.
#include "contracts/voxel_clipmap.glsl"
#define VCT_VOLUME_BINDING 1
#include "contracts/cone_trace.glsl"

layout(local_size_x = 64) in;

struct ProbeIn {
  vec4 position;
  vec4 direction;
};
layout(set = 0, binding = 2, std430) readonly buffer Probes { ProbeIn probes[]; };
layout(set = 0, binding = 3, std430) writeonly buffer Results { vec4 results[]; };

layout(push_constant) uniform Push {
  int single_cone;  // 1: one free cone; 2: the lane layout of diffuse cones (no volume read)
  int diffuse_cones;
  float tan_half_angle;
  float step_factor;
  float max_distance;
  float ao_falloff;
  float normal_offset;
  float start_distance;
  uint count;
  int lanes;  // of a capped cone; 1: the library's cones as the source documents trace them
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec3 p = voxel_relative(probes[i].position.xyz);
  vec3 d = normalize(probes[i].direction.xyz);
  VctTraceSettings s;
  s.step_factor = pc.step_factor;
  s.max_distance = pc.max_distance;
  s.start_distance = pc.start_distance;
  s.ao_falloff = pc.ao_falloff;
  s.lanes = pc.lanes;
  s.lane_rows = VCT_LANE_ROWS_APERTURE;
  if (pc.single_cone == 2) {
    // One lane of diffuse cone (int) position.z of pc.diffuse_cones, turned by position.x and
    // at ring position position.y, over a receiver whose normal is +z.
    vec3 d;
    float weight, tan_half;
    vec2 cell_rows;
    int count = clamp(pc.diffuse_cones, 1, VCT_MAX_DIFFUSE_CONES);
    vct_diffuse_cone(int(probes[i].position.z), count, probes[i].position.x,
                     probes[i].position.y, d, weight, tan_half, cell_rows);
    VctCone cone = vct_cone_from_surface(p, d, tan_half, vec3(0.0, 0.0, 1.0), 0.0);
    cone.cell_rows = cell_rows;
    VctConeFrame frame = vct_cone_frame(cone);
    vec3 lanes[VCT_MAX_LANES];
    int lane_count = clamp(pc.lanes, 1, VCT_MAX_LANES);
    vct_lane_directions(cone, frame, lane_count, lanes);
    int lane = clamp(int(probes[i].direction.x), 0, lane_count - 1);
    results[i] = vec4(lanes[lane], weight / float(lane_count));
  } else if (pc.single_cone != 0) {
    // A free cone in a medium: no receiver surface.
    VctCone cone = vct_cone_from_surface(p, d, pc.tan_half_angle, vec3(0.0), 0.0);
    VctConeResult r = vct_trace_cone(cone, s);
    results[i] = vec4(r.radiance, 1.0 - r.opacity);
  } else {
    float visibility;
    // One fixed cone set (no turn, ring middles): probes compare single gathers with closed forms.
    vec3 e = vct_diffuse_irradiance(p, d, pc.diffuse_cones, 0.0, 0.5, pc.normal_offset, s,
                                    visibility);
    results[i] = vec4(e, visibility);
  }
}
