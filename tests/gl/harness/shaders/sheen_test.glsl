#version 450
// Shader unit test: sheen.glsl's sheen_sh_radiance and sheen_E for a batch of inputs (one
// invocation each) so tests/gl/sheen_glsl_test.cpp can compare them with the C++
// pbrkit::sheen_sh_radiance and SheenTable::E.
#include "brdf.glsl"
#include "sheen.glsl"

layout(local_size_x = 64) in;

struct SheenLobeCase {
  vec4 n_roughness;  // n, sheen roughness
  vec4 v;            // v
};
layout(std430, binding = 0) readonly buffer Cases { SheenLobeCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
layout(binding = 0) uniform sampler2D uSheenLut;

uniform int uCount;
uniform vec3 uSH[9];

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  SheenLobeCase c = cases[i];
  vec3 n = c.n_roughness.xyz, v = c.v.xyz;
  float r = c.n_roughness.w;
  results[i] = vec4(sheen_sh_radiance(uSheenLut, uSH, n, v, r), sheen_E(uSheenLut, dot(n, v), r));
}
