#version 460
#extension GL_GOOGLE_include_directive : require
// vct.cone_trace's interleaved average (docs/vct.md, "Interleaved cone sets"). trace.comp
// writes each pixel's gather with its own turn of the cone set to a scratch image (rgb: E / pi,
// a: AO visibility, a < 0 where nothing was traced); here each pixel averages the n x n window
// around it, moved inside the image so that it holds every turn once, over the pixels of its
// own surface. A dispatch of its own, so that windows cross workgroups: averaged inside one
// 8 x 8 workgroup, the windows on either side of a workgroup's edge were disjoint, and the
// indirect light showed 8-pixel blocks.
//   full resolution (HALF 0): writes c_diff x the average to `out_result` and the AO to `out_ao`;
//   half resolution (HALF 1): writes the average (E / pi, a = AO) to the half-resolution
//   scratch that upsample.comp reads, the window's pixels placed at their blocks'
//   representatives as trace.comp traced them.
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "vct/gbuffer_sample.glsl"

#ifndef HALF
#define HALF 0
#endif
#ifndef HAS_AO
#define HAS_AO 0
#endif
#ifndef AO_FORMAT
#define AO_FORMAT r16f
#endif

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 7, rgba16f) writeonly uniform image2D out_result;
#if HAS_AO && !HALF
layout(set = 0, binding = 8, AO_FORMAT) writeonly uniform image2D out_ao;
#endif
layout(set = 0, binding = 9) uniform sampler2D traced;  // one gather per pixel, see above

layout(push_constant) uniform Push {
  uvec2 size;      // of out_result and `traced`
  int interleave;  // n of the n x n window
} pc;

void store(ivec2 pixel, vec3 result, float visibility) {
  imageStore(out_result, pixel, vec4(sanitize_radiance(result), HALF != 0 ? visibility : 1.0));
#if HAS_AO && !HALF
  imageStore(out_ao, pixel, vec4(visibility));
#endif
}

// The G-buffer pixel `pixel`'s gather was traced from.
GbufferSample traced_surface(ivec2 pixel) {
#if HALF
  return gbuffer_sample(gbuffer_block_representative(pixel));
#else
  return gbuffer_sample(pixel);
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(pc.size);
  if (any(greaterThanEqual(pixel, size))) return;
  vec4 own = texelFetch(traced, pixel, 0);
  if (!(own.a >= 0.0)) {  // nothing traced: no surface, or outside the voxel volume
    store(pixel, vec3(0.0), 1.0);
    return;
  }
  GbufferSample g = traced_surface(pixel);
  int n = max(pc.interleave, 1);
  // An odd window is centred on the pixel. An even one has no middle: it spans n + 1 pixels
  // with its first and last rows and columns at half weight, which is centred and still weighs
  // every turn alike (those rows and columns hold the same turns). Moving an n x n window
  // half a pixel back took more from the image's left and top sides than from the others (an
  // image whose light falls off towards one side brightened or darkened with it); moving it
  // back at even coordinates and ahead at odd ones gave each 2 x 2 block of pixels one window,
  // a 2-pixel pattern over the whole indirect image.
  bool even = n > 1 && (n & 1) == 0;
  int span = even ? n + 1 : n;
  ivec2 start = clamp(pixel - ivec2(n / 2), ivec2(0), max(size - span, ivec2(0)));
  ivec2 stop = min(start + span, size);
  // Neighbours count fully on the pixel's own plane and fade with their distance from it
  // (relative to how far apart the two pixels are) and with the angle between the normals, so
  // light does not cross edges.
  vec4 sum = vec4(0.0);
  float weight_sum = 0.0;
  for (int y = start.y; y < stop.y; ++y) {
    float wy = even && (y == start.y || y == start.y + n) ? 0.5 : 1.0;
    for (int x = start.x; x < stop.x; ++x) {
      float wx = even && (x == start.x || x == start.x + n) ? 0.5 : 1.0;
      ivec2 q = ivec2(x, y);
      vec4 value = q == pixel ? own : texelFetch(traced, q, 0);
      if (!(value.a >= 0.0)) continue;
      float w = wx * wy;
      if (q != pixel) {
        GbufferSample t = traced_surface(q);
        vec3 offset = t.position - g.position;
        float off_plane = abs(dot(g.normal, offset)) / (0.1 * length(offset) + 1e-6);
        float facing = max(dot(g.normal, t.normal), 0.0);
        facing *= facing;
        facing *= facing;
        w *= facing * facing / (1.0 + off_plane * off_plane);
      }
      sum += w * value;
      weight_sum += w;
    }
  }
  vec4 average = sum / weight_sum;
#if HALF
  store(pixel, average.rgb, average.a);
#else
  store(pixel, average.rgb * gbuffer_diffuse_reflectance(g), average.a);
#endif
}
