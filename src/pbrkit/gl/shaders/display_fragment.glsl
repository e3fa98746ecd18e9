#version 450
// The display pass: the renderer's linear float frame through display.glsl's transform
// into the bound (8-bit, non-sRGB) framebuffer, pixel for pixel, as the viewer shows it.
// TONE_MAPPER is a compile-time constant (pbr_fragment.glsl says why).
#ifndef TONE_MAPPER
#define TONE_MAPPER 1
#endif
#include "display.glsl"

layout(binding = BINDING_FRAME) uniform sampler2D uFrame;
uniform float uExposureScale;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 linear = texelFetch(uFrame, ivec2(gl_FragCoord.xy), 0).rgb;
  outColor = vec4(display_transform(linear, uExposureScale, TONE_MAPPER), 1.0);
}
