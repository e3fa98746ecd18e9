#version 450
// Shader unit test: anisotropy_ibl.glsl's functions for a batch of inputs (one invocation
// each; uFunction picks which) so tests/gl/anisotropy_glsl_test.cpp can compare them with
// ibl/anisotropic_taps.h.
#include "anisotropy_ibl.glsl"

layout(local_size_x = 64) in;

// anisotropy_eval.cpp's AnisotropyCase record.
struct AnisotropyCase {
  vec4 wo_tap;     // wo (local), tap index
  vec4 alpha;      // alpha_x, alpha_y
  vec4 frame_t;    // the frame's world axes: anisotropy direction,
  vec4 frame_b;    // bitangent,
  vec4 frame_n;    // normal
};
layout(std430, binding = 0) readonly buffer Cases { AnisotropyCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;
uniform int uFunction;  // anisotropy_eval.h's AnisotropyFunction
uniform vec2 uRotation;
layout(binding = 0) uniform samplerCube uCube;
layout(binding = 1) uniform sampler3D uAlbedo;  // gl/energy_texture.h's anisotropic albedo

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  AnisotropyCase c = cases[i];
  vec4 r = vec4(0.0);
  if (uFunction == 0) {
    r.xy = anisotropic_tap_point(int(c.wo_tap.w));
  } else if (uFunction == 1) {
    float weight, roughness;
    anisotropic_tap(c.wo_tap.xyz, c.alpha.x, c.alpha.y, int(c.wo_tap.w), r.xyz, weight, roughness);
  } else if (uFunction == 2) {
    vec3 wi;
    anisotropic_tap(c.wo_tap.xyz, c.alpha.x, c.alpha.y, int(c.wo_tap.w), wi, r.x, r.y);
  } else if (uFunction == 3) {
    mat3 frame = mat3(c.frame_t.xyz, c.frame_b.xyz, c.frame_n.xyz);
    r.rgb = anisotropic_ibl_radiance(uCube, 1, uAlbedo, frame, uRotation, c.wo_tap.xyz, c.alpha.x,
                                     c.alpha.y);
  } else {
    r.x = anisotropic_albedo(uAlbedo, c.wo_tap.xyz, c.alpha.x, c.alpha.y);
  }
  results[i] = r;
}
