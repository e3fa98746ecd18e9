#version 450
// Shader unit test: evaluates bsdf.glsl's bsdf_eval (clearcoat over sheen over the base)
// for a batch of inputs so tests/gl/bsdf_glsl_test.cpp can compare it with the C++
// Bsdf::eval.
#define BRDF_IRIDESCENCE 1
#define BINDING_ANISOTROPIC_ENERGY 3  // brdf.glsl's anisotropic compensation table
#include "bsdf.glsl"

layout(local_size_x = 64) in;

// bsdf_eval.cpp's record: brdf_eval.cpp's append_brdf_case, then the layers.
struct BsdfCase {
  vec4 wo;
  vec4 wi;
  vec4 base_metal;
  vec4 rough;      // roughness, ior, specular, anisotropy
  vec4 spec_irid;  // specular colour rgb, iridescence
  vec4 film;       // iridescence ior, thickness
  vec4 layers;     // coat weight, coat roughness, sheen roughness
  vec4 coat_normal;
  vec4 sheen_color;
};
layout(std430, binding = 0) readonly buffer Cases { BsdfCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;
uniform int uGeometry;
uniform bool uMultiscatter;
layout(binding = 0) uniform sampler2D uEnergy;
layout(binding = 1) uniform sampler2D uEnergyCoat;
layout(binding = 2) uniform sampler2D uSheenLut;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  BsdfCase c = cases[i];
  BaseLayer layer = BaseLayer(c.base_metal.rgb, c.base_metal.a, c.rough.x, c.rough.y, c.rough.z,
                              c.spec_irid.rgb, c.rough.w, c.spec_irid.a, c.film.x, c.film.y);
  Brdf base = brdf_at(make_brdf(layer, uGeometry, uMultiscatter, FRESNEL_SCHLICK, uEnergy), uEnergy,
                      c.wo.xyz);
  Bsdf s = bsdf_at(make_bsdf(base, c.layers.x, c.layers.y, c.coat_normal.xyz, c.sheen_color.rgb,
                             c.layers.z, uEnergyCoat),
                   uSheenLut, c.wo.xyz);
  results[i] = vec4(bsdf_eval(s, uEnergy, uEnergyCoat, uSheenLut, c.wo.xyz, c.wi.xyz), 0.0);
}
