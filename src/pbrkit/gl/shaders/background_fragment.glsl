#version 450
// The background seen through each pixel: the environment (sharp, from the equirect map
// with equirect.glsl's convention, as the path tracer shows it), the environment blurred
// by a mip of the prefiltered cube, or a solid colour. MODE is a compile-time constant
// (0 equirect environment, 1 blurred cube mip, 2 colour; see pbr_fragment.glsl for why).
#ifndef MODE
#define MODE 0
#endif
#include "equirect.glsl"

in vec2 vNdc;
layout(location = 0) out vec4 outColor;

uniform mat4 uInverseProjection;
uniform mat3 uCameraToWorld;
uniform vec3 uColor;
uniform vec2 uEnvRotation;  // equirect.glsl world_to_env
uniform float uEnvScale;
uniform vec2 uIblRotation;
uniform float uIblScale;
uniform float uBlurLod;
layout(binding = 0) uniform sampler2D uEnvironment;
layout(binding = 1) uniform samplerCube uSpecularCube;

void main() {
#if MODE == 2
  outColor = vec4(uColor, 1.0);
#else
  // The view ray through this pixel, from two points of its line (works for the
  // perspective and the orthographic projections of scene/camera.h).
  vec4 p0 = uInverseProjection * vec4(vNdc, -1.0, 1.0);
  vec4 p1 = uInverseProjection * vec4(vNdc, 0.0, 1.0);
  vec3 d = normalize(uCameraToWorld * normalize(p1.xyz / p1.w - p0.xyz / p0.w));
#if MODE == 1
  outColor = vec4(uIblScale * textureLod(uSpecularCube, world_to_env(d, uIblRotation), uBlurLod).rgb, 1.0);
#else
  outColor = vec4(uEnvScale * textureLod(uEnvironment, equirect_uv(world_to_env(d, uEnvRotation)), 0.0).rgb, 1.0);
#endif
#endif
}
