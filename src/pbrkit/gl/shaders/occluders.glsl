// The environment light that transmissive objects (and, with opaque shadows, opaque ones)
// hide from a surface point: each one's proxy (its bounding box as a parallelepiped, or a
// sphere) covers a part of the point's cosine-weighted hemisphere, its form factor F. A
// transmissive one lets through its transmittance T (occluders.h), so the point keeps
// 1 - F (1 - T) of a uniform environment's light, and the product of that over the proxies
// where several cover it. Without it a floor seen through a glass block is lit as though
// the block were not there, where the path tracer's floor under it is lit only through it
// (MODEL.md, "Shadows of transmissive objects"). An opaque one sends the light of its own
// sides in the place of the environment's it hides (OCCLUDER_BOUNCE: MODEL.md, "Shadows of
// opaque objects").
#include "occluder_form_factors.glsl"

// The occluders (occluders.h's select_occluders), spheres first, their numbers and geometry
// compiled in (OCCLUDER_SPHERES, OCCLUDER_BOXES, OCCLUDER_GEOMETRY: occluder_geometry_define's
// five vec4 each: centre and slot; three pairs of faces; the faces' areas and a sphere's
// radius), and each one's term written out from the lists of their indices by kind and role
// (OCCLUDER_TRANSMISSIVE_SPHERES etc., "OCCLUDER_TERM(0) OCCLUDER_TERM(1)"), so that every
// read is of a constant at a constant index: a software rasteriser (llvmpipe) reads a
// uniform buffer lane by lane, runs a parallelepiped's form factor for a sphere (it runs
// both sides of a branch that differs across lanes), and does not unroll a loop over many
// proxies (a frame of 24 glass spheres, 16 of them proxies, 11-16% slower as loops). Their
// transmittances, which change with the materials, are in a uniform block.
const int kMaxOccluders = 16;  // occluders.h's
#ifndef OCCLUDER_SPHERES
#define OCCLUDER_SPHERES 0
#define OCCLUDER_BOXES 0
#define OCCLUDER_GEOMETRY vec4[](vec4(0.0))
#define OCCLUDER_TRANSMISSIVE_SPHERES
#define OCCLUDER_OPAQUE_SPHERES
#define OCCLUDER_TRANSMISSIVE_BOXES
#define OCCLUDER_OPAQUE_BOXES
#endif
#ifndef OCCLUDER_BOUNCE
#define OCCLUDER_BOUNCE 0
#endif
const vec4 kOccluderGeometry[] = OCCLUDER_GEOMETRY;
layout(std140, binding = BINDING_OCCLUDERS) uniform Occluders {
  vec4 uOccluderTransmittance[2 * kMaxOccluders];  // rgb
  vec4 uOccluderAlbedo[2 * kMaxOccluders];         // rgb: an opaque proxy's, else 0
  vec4 uOccluderEmission[2 * kMaxOccluders];       // rgb: an opaque proxy's, else 0
};

// The environment's irradiance at world normal n, as the surface's own diffuse lobe gets it
// (pbr_fragment.glsl's: the nine SH terms', or the irradiance cube's).
vec3 environment_irradiance(vec3 n);

// The radiance opaque proxy i sends towards a point from its side of outward normal n: its
// albedo times the whole environment's light there, albedo E(n) / pi, plus its own emission
// (occluders.h).
vec3 side_radiance(int i, vec3 n) {
  return uOccluderAlbedo[i].rgb * environment_irradiance(n) * kInvPi + uOccluderEmission[i].rgb;
}

// Occluder i's form factor from (x, n), 0 where it is the surface's own (`slot`).
float sphere_factor(int i, vec3 x, vec3 n, int slot) {
  vec4 centre = kOccluderGeometry[5 * i];
  float f = sphere_form_factor(x, n, centre.xyz, kOccluderGeometry[5 * i + 4].w);
  return int(centre.w) == slot ? 0.0 : f;
}
float box_factor(int i, vec3 x, vec3 n, int slot) {
  vec4 centre = kOccluderGeometry[5 * i];
  float f = box_form_factor(x, n, centre.xyz, kOccluderGeometry[5 * i + 1],
                            kOccluderGeometry[5 * i + 2], kOccluderGeometry[5 * i + 3],
                            kOccluderGeometry[5 * i + 4].xyz);
  return int(centre.w) == slot ? 0.0 : f;
}

#if OCCLUDER_BOUNCE
// Opaque sphere i's F (L - L_hidden) at (x, n) (occluder_visibility's bounce): seen from x,
// a sphere shows the side facing it, its normal the direction to x.
vec3 opaque_sphere_bounce(int i, vec3 x, vec3 n, int slot) {
  vec3 to_x = normalize(x - kOccluderGeometry[5 * i].xyz);
  return sphere_factor(i, x, n, slot) *
         (side_radiance(i, to_x) - environment_irradiance(-to_x) * kInvPi);
}

// Opaque parallelepiped i's F (L - L_hidden) at (x, n): seen from x, it shows the sides whose
// planes x lies beyond (a point on the floor beside a box resting on it sees the box's side,
// not its base: a point in a side's plane, to 1e-3 of the extent, is not beyond it); their
// normals weighted by their projected areas, area_k |u.N_k|, give the side's.
vec3 opaque_box_bounce(int i, vec3 x, vec3 n, int slot) {
  vec4 N0 = kOccluderGeometry[5 * i + 1], N1 = kOccluderGeometry[5 * i + 2],
       N2 = kOccluderGeometry[5 * i + 3];
  vec3 d = x - kOccluderGeometry[5 * i].xyz;
  vec3 u = vec3(dot(d, N0.xyz), dot(d, N1.xyz), dot(d, N2.xyz));
  vec3 w = step(1.001 * vec3(N0.w, N1.w, N2.w), abs(u)) * kOccluderGeometry[5 * i + 4].xyz * u;
  vec3 side = w.x * N0.xyz + w.y * N1.xyz + w.z * N2.xyz;
  float len = length(side);
  vec3 to_x = normalize(d);
  return box_factor(i, x, n, slot) *
         (side_radiance(i, len > 0.0 ? side / len : to_x) -
          environment_irradiance(-to_x) * kInvPi);
}
#endif

// The share of a uniform environment's light that reaches (x, n) past every transmissive
// occluder but the surface's own (`slot`); and in `bounce` what the opaque ones change (0
// without OCCLUDER_BOUNCE): each replaces the environment light it hides, F L_hidden, by its
// own, F L (L the radiance of the side x sees, side_radiance's), sum F (L - L_hidden).
// L_hidden is the environment's cosine-weighted mean radiance about the direction to the
// proxy, E(d) / pi, not its mean over x's hemisphere: a wall hides the horizon behind it,
// not the zenith.
vec3 occluder_visibility(vec3 x, vec3 n, int slot, out vec3 bounce) {
  vec3 vis = vec3(1.0);
  bounce = vec3(0.0);
  // Each kind's transmissive proxies, then its opaque ones, as lists of their own: a
  // software rasteriser would run a branch on the kind for all of them.
#define OCCLUDER_TERM(i) vis *= 1.0 - sphere_factor(i, x, n, slot) * (1.0 - uOccluderTransmittance[i].rgb);
  OCCLUDER_TRANSMISSIVE_SPHERES
#undef OCCLUDER_TERM
#define OCCLUDER_TERM(i) vis *= 1.0 - box_factor(i, x, n, slot) * (1.0 - uOccluderTransmittance[i].rgb);
  OCCLUDER_TRANSMISSIVE_BOXES
#undef OCCLUDER_TERM
#if OCCLUDER_BOUNCE
#define OCCLUDER_TERM(i) bounce += opaque_sphere_bounce(i, x, n, slot);
  OCCLUDER_OPAQUE_SPHERES
#undef OCCLUDER_TERM
#define OCCLUDER_TERM(i) bounce += opaque_box_bounce(i, x, n, slot);
  OCCLUDER_OPAQUE_BOXES
#undef OCCLUDER_TERM
#endif
  return vis;
}
