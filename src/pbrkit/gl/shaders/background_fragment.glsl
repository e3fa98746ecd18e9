#version 450
// The background seen through each pixel: the environment (sharp, from the equirect map
// with equirect.glsl's convention, as the path tracer shows it), the environment blurred
// by a mip of the prefiltered cube, or a solid colour. MODE is a compile-time constant
// (0 equirect environment, 1 blurred cube mip, 2 colour; see pbr_fragment.glsl for why).
#ifndef MODE
#define MODE 0
#endif
#include "equirect.glsl"

in vec3 vDirection;  // background_vertex.glsl
layout(location = 0) out vec4 outColor;

uniform vec3 uColor;
uniform vec2 uEnvRotation;  // equirect.glsl world_to_env
uniform float uEnvScale;
uniform vec2 uIblRotation;
uniform float uIblScale;
uniform float uBlurLod;
layout(binding = BINDING_ENVIRONMENT) uniform sampler2D uEnvironment;
layout(binding = BINDING_SPECULAR_CUBE) uniform samplerCube uSpecularCube;

void main() {
#if MODE == 2
  outColor = vec4(uColor, 1.0);
#else
  // The view ray through this pixel (background_vertex.glsl).
  vec3 d = normalize(vDirection);
#if MODE == 1
  outColor = vec4(uIblScale * textureLod(uSpecularCube, world_to_env(d, uIblRotation), uBlurLod).rgb, 1.0);
#else
  outColor = vec4(uEnvScale * textureLod(uEnvironment, equirect_uv(world_to_env(d, uEnvRotation)), 0.0).rgb, 1.0);
#endif
#endif
}
