// The environment light that transmissive objects hide from a surface point: each one's
// proxy (its bounding box as a parallelepiped, or a sphere) covers a part of the point's
// cosine-weighted hemisphere, its form factor F, and lets through its transmittance T
// (occluders.h), so the point keeps 1 - F (1 - T) of a uniform environment's light, and the
// product of that over the proxies where several cover it. Without it a floor seen through
// a glass block is lit as though the block were not there, where the path tracer's floor
// under it is lit only through it (MODEL.md, "Shadows of transmissive objects").
#include "occluder_form_factors.glsl"

// The occluders (occluders.h's select_occluders), spheres first, their numbers and geometry
// compiled in (OCCLUDER_SPHERES, OCCLUDER_BOXES, OCCLUDER_GEOMETRY: occluder_geometry_define's
// five vec4 each: centre and slot; three pairs of faces; the faces' areas and a sphere's
// radius), so that the loops unroll over constants: a software rasteriser (llvmpipe) would
// read a uniform buffer lane by lane, and run a parallelepiped's form factor for a sphere
// (it runs both sides of a branch that differs across lanes). Their transmittances, which
// change with the materials, are in a uniform block.
const int kMaxOccluders = 16;  // occluders.h's
#ifndef OCCLUDER_SPHERES
#define OCCLUDER_SPHERES 0
#define OCCLUDER_BOXES 0
#define OCCLUDER_GEOMETRY vec4[](vec4(0.0))
#endif
const vec4 kOccluderGeometry[] = OCCLUDER_GEOMETRY;
layout(std140, binding = BINDING_OCCLUDERS) uniform Occluders {
  vec4 uOccluderTransmittance[2 * kMaxOccluders];  // rgb
};

// The share of a uniform environment's light that reaches (x, n) past every occluder but
// the surface's own (`slot`).
vec3 occluder_visibility(vec3 x, vec3 n, int slot) {
  vec3 vis = vec3(1.0);
  for (int i = 0; i < OCCLUDER_SPHERES; ++i) {
    vec4 centre = kOccluderGeometry[5 * i];
    float f = sphere_form_factor(x, n, centre.xyz, kOccluderGeometry[5 * i + 4].w);
    vis *= 1.0 - (int(centre.w) == slot ? 0.0 : f) * (1.0 - uOccluderTransmittance[i].rgb);
  }
  for (int i = OCCLUDER_SPHERES; i < OCCLUDER_SPHERES + OCCLUDER_BOXES; ++i) {
    vec4 centre = kOccluderGeometry[5 * i];
    float f = box_form_factor(x, n, centre.xyz, kOccluderGeometry[5 * i + 1],
                              kOccluderGeometry[5 * i + 2], kOccluderGeometry[5 * i + 3],
                              kOccluderGeometry[5 * i + 4].xyz);
    vis *= 1.0 - (int(centre.w) == slot ? 0.0 : f) * (1.0 - uOccluderTransmittance[i].rgb);
  }
  return vis;
}
