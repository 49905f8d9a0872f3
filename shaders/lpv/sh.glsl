#ifndef VOXGI_LPV_SH_GLSL
#define VOXGI_LPV_SH_GLSL
// Two-band spherical harmonics of the LPV family (docs/lpv.md derives every constant).
//
// One convention everywhere, sign-free (seed 002's eq. 3 carries -y and -x, its eq. 7 +y and
// +x; mixing the two mirrors light in x and y): a vec4 holds (c0, c_y, c_z, c_x) with basis
//   Y0 = 0.282095, Y1 = 0.488603 * (w.y, w.z, w.x)
// so f(w) = c0 * 0.282095 + 0.488603 * (c_y w.y + c_z w.z + c_x w.x).
// A function of direction w is the direction light travels (an intensity's lobe points away
// from its source).

const float SH_PI = 3.14159265358979323846;
const float SH_Y0 = 0.28209479177387814;  // 1 / (2 sqrt(pi))
const float SH_Y1 = 0.48860251190291992;  // sqrt(3 / (4 pi))
// Projection of the clamped cosine max(0, n.w): (sqrt(pi) / 2, sqrt(pi / 3) n).
const float SH_COSINE_0 = 0.88622692545275801;
const float SH_COSINE_1 = 1.0233267079464885;

// The basis at direction w.
vec4 sh_basis(vec3 w) { return vec4(SH_Y0, SH_Y1 * w.y, SH_Y1 * w.z, SH_Y1 * w.x); }

// Evaluates coefficients c at direction w.
float sh_eval(vec4 c, vec3 w) { return dot(c, sh_basis(w)); }

// Coefficients of max(0, n.w) (n unit).
vec4 sh_clamped_cosine(vec3 n) {
  return vec4(SH_COSINE_0, SH_COSINE_1 * n.y, SH_COSINE_1 * n.z, SH_COSINE_1 * n.x);
}

// The integral of a function over the whole sphere, from its coefficients (only band 0
// contributes): 4 pi Y0 c0 = 2 sqrt(pi) c0.
float sh_integral(vec4 c) { return 4.0 * SH_PI * SH_Y0 * c.x; }

// Integral over a solid angle region of f, given the region's solid angle and its vector
// solid angle V = integral of w over the region: c0 Y0 omega + Y1 (c_y V.y + c_z V.z + c_x V.x).
float sh_integrate_region(vec4 c, float omega, vec3 vector_solid_angle) {
  return c.x * SH_Y0 * omega +
         SH_Y1 * dot(c.yzw, vec3(vector_solid_angle.y, vector_solid_angle.z, vector_solid_angle.x));
}

// Radiant intensity (Phi / pi) max(0, n.w) of a Lambertian emitter of flux Phi facing n: its
// integral over the sphere is Phi.
vec4 sh_lambert_lobe(vec3 n, float flux) { return (flux / SH_PI) * sh_clamped_cosine(n); }

// Irradiance on a surface of normal n from light travelling in direction w with radiance L(w)
// (coefficients of L): the integral of L(w) max(0, -n.w), the clamped cosine around -n.
float sh_irradiance(vec4 radiance, vec3 n) { return dot(radiance, sh_clamped_cosine(-n)); }

// Propagation geometry (seed 002 sec. 3.2.3): a cell B receives from its axial neighbour A
// (light travelling along +d from A's centre) through the five faces of B that do not face A.
// Seen from A's centre (cell edge 1), exactly:
//   far face (normal d), a unit square at distance 1.5:
//     solid angle 4 atan(1 / (6 sqrt(11))) = 0.4006697 sr, vector solid angle 0.3874136 d
//   each side face (normal f, perpendicular to d), at distance 0.5, spanning 0.5..1.5 along d:
//     solid angle 0.4234314 sr, vector solid angle 0.2193731 f + 0.3383565 d
// 0.4006697 + 4 x 0.4234314 = 2 pi / 3, and the 6 x 5 faces cover the sphere around A exactly
// once: every ray from A's centre leaves A through one face into one neighbour and leaves that
// neighbour through one of its five other faces. So the transfer loses and gains nothing.
const float LPV_FAR_FACE_SOLID_ANGLE = 0.40066968464623920;
const float LPV_SIDE_FACE_SOLID_ANGLE = 0.42343135443673896;
const float LPV_FAR_FACE_VECTOR_D = 0.38741363293615560;
const float LPV_SIDE_FACE_VECTOR_F = 0.21937313087900068;
const float LPV_SIDE_FACE_VECTOR_D = 0.33835646744951264;

#endif
