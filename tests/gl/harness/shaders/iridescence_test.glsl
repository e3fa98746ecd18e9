#version 450
// Shader unit test: iridescence.glsl's iridescence_fresnel for a batch of inputs (one
// invocation each) so tests/gl/iridescence_glsl_test.cpp can compare it with the C++
// pbrkit::iridescence_fresnel.
#include "iridescence.glsl"

layout(local_size_x = 64) in;

struct IridescenceCase {
  vec4 angle_film;  // cos_theta, film ior, thickness (nm)
  vec4 base;        // base F0 rgb
};
layout(std430, binding = 0) readonly buffer Cases { IridescenceCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  IridescenceCase c = cases[i];
  vec3 F = iridescence_fresnel(c.angle_film.x, c.angle_film.y, c.angle_film.z, c.base.rgb);
  results[i] = vec4(F, 0.0);
}
