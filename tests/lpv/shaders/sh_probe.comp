#version 460
#extension GL_GOOGLE_include_directive : require
// The LPV family's two-band SH (shaders/lpv/sh.glsl) on the device, for each input direction n:
//   out[5i]     sh_clamped_cosine(n)
//   out[5i + 1] sh_basis(n), the projection of a direction
//   out[5i + 2] x: the projection of n evaluated at n, y: at -n, z: the irradiance of a
//               uniform unit radiance on a surface of normal n, w: the integral of the clamped
//               cosine over the sphere
//   out[5i + 3] the propagation constants: far and side face solid angles, far-face vector
//               solid angle along d, side-face vector solid angle along f
//   out[5i + 4] x: side-face vector solid angle along d; y: the flux of a Lambertian lobe of
//               unit flux facing n summed over the 30 faces around a cell; z, w: 0
#include "lpv/sh.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = 0, std430) readonly buffer Directions { vec4 directions[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Results { vec4 results[]; };

layout(push_constant) uniform Push { uint count; } pc;

const ivec3 AXES[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
                               ivec3(0, 0, 1), ivec3(0, 0, -1));

void main() {
  for (uint i = 0u; i < pc.count; ++i) {
    vec3 n = normalize(directions[i].xyz);
    vec4 direction = sh_basis(n);
    // Radiance 1 in every direction: c0 = integral of Y0 over the sphere.
    vec4 uniform_radiance = vec4(4.0 * SH_PI * SH_Y0, 0.0, 0.0, 0.0);
    vec4 lobe = sh_lambert_lobe(n, 1.0);
    float flux = 0.0;
    for (int a = 0; a < 6; ++a) {
      ivec3 d = AXES[a];
      for (int b = 0; b < 6; ++b) {
        ivec3 f = AXES[b];
        if (f == -d) continue;
        if (f == d) {
          flux += sh_integrate_region(lobe, LPV_FAR_FACE_SOLID_ANGLE, LPV_FAR_FACE_VECTOR_D * vec3(d));
        } else {
          flux += sh_integrate_region(lobe, LPV_SIDE_FACE_SOLID_ANGLE,
                                      LPV_SIDE_FACE_VECTOR_F * vec3(f) + LPV_SIDE_FACE_VECTOR_D * vec3(d));
        }
      }
    }
    results[5u * i] = sh_clamped_cosine(n);
    results[5u * i + 1u] = direction;
    results[5u * i + 2u] = vec4(sh_eval(direction, n), sh_eval(direction, -n),
                                sh_irradiance(uniform_radiance, n), sh_integral(sh_clamped_cosine(n)));
    results[5u * i + 3u] = vec4(LPV_FAR_FACE_SOLID_ANGLE, LPV_SIDE_FACE_SOLID_ANGLE,
                                LPV_FAR_FACE_VECTOR_D, LPV_SIDE_FACE_VECTOR_F);
    results[5u * i + 4u] = vec4(LPV_SIDE_FACE_VECTOR_D, flux, 0.0, 0.0);
  }
}
