#version 450
// Shader unit test: evaluates brdf.glsl's brdf_eval (with every base-layer extension
// compiled in) for a batch of inputs (one invocation each) so tests/gl/brdf_glsl_test.cpp
// can compare it with the C++ Brdf::eval.
#define BRDF_IRIDESCENCE 1
#define BINDING_ANISOTROPIC_ENERGY 1  // brdf.glsl's anisotropic compensation table
#include "brdf.glsl"

layout(local_size_x = 64) in;

// brdf_eval.cpp's append_brdf_case.
struct BrdfCase {
  vec4 wo;          // xyz
  vec4 wi;          // xyz
  vec4 base_metal;  // base colour rgb, metallic
  vec4 rough;       // roughness, ior, specular, anisotropy
  vec4 spec_irid;   // specular colour rgb, iridescence
  vec4 film;        // iridescence ior, thickness
};
layout(std430, binding = 0) readonly buffer Cases { BrdfCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;
uniform int uGeometry;
uniform bool uMultiscatter;
uniform int uFresnel;
layout(binding = 0) uniform sampler2D uEnergy;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  BrdfCase c = cases[i];
  BaseLayer layer = BaseLayer(c.base_metal.rgb, c.base_metal.a, c.rough.x, c.rough.y, c.rough.z,
                              c.spec_irid.rgb, c.rough.w, c.spec_irid.a, c.film.x, c.film.y);
  Brdf b = brdf_at(make_brdf(layer, uGeometry, uMultiscatter, uFresnel, uEnergy), uEnergy, c.wo.xyz);
  results[i] = vec4(brdf_eval(b, uEnergy, c.wo.xyz, c.wi.xyz), 0.0);
}
