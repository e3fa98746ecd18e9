#version 450
// Shader unit test: display.glsl's display_transform for a batch of linear colours, so
// tests/gl/display_glsl_test.cpp can compare it with the C++ display_transform.
#include "display.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;
uniform float uExposureScale;
uniform int uToneMapper;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  results[i] = vec4(display_transform(inputs[i].rgb, uExposureScale, uToneMapper), 0.0);
}
