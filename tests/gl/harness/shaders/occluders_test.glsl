#version 450
// Shader unit test: occluder_form_factors.glsl's form factors for a batch of cases, so
// tests/gl/occluders_test.cpp can compare them with closed forms and exact integrals.
// Each case is seven vec4s: the point (xyz; w 1 a sphere, 0 a parallelepiped), its normal,
// the proxy's centre (xyz; w the sphere's radius), the parallelepiped's three pairs of faces
// and their areas.
#include "occluder_form_factors.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  vec4 x = inputs[7 * i], n = inputs[7 * i + 1], c = inputs[7 * i + 2];
  float f = x.w > 0.5 ? sphere_form_factor(x.xyz, n.xyz, c.xyz, c.w)
                      : box_form_factor(x.xyz, n.xyz, c.xyz, inputs[7 * i + 3], inputs[7 * i + 4],
                                        inputs[7 * i + 5], inputs[7 * i + 6].xyz);
  results[i] = vec4(f, 0.0, 0.0, 0.0);
}
