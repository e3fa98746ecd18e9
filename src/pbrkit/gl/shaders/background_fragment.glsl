#version 450
// The background seen through each pixel: the environment (sharp, from the equirect map
// with equirect.glsl's convention, as the path tracer shows it), the environment blurred
// by a mip of the prefiltered cube, or a solid colour.
#include "equirect.glsl"

in vec2 vNdc;
layout(location = 0) out vec4 outColor;

uniform mat4 uInverseProjection;
uniform mat3 uCameraToWorld;
uniform int uMode;  // 0 equirect environment, 1 blurred (cube mip), 2 colour
uniform vec3 uColor;
uniform float uEnvRotation;  // degrees
uniform float uEnvScale;
uniform float uIblRotation;
uniform float uIblScale;
uniform float uBlurLod;
layout(binding = 0) uniform sampler2D uEnvironment;
layout(binding = 1) uniform samplerCube uSpecularCube;

void main() {
  if (uMode == 2) {
    outColor = vec4(uColor, 1.0);
    return;
  }
  // The view ray through this pixel, from two points of its line (works for the
  // perspective and the orthographic projections of scene/camera.h).
  vec4 p0 = uInverseProjection * vec4(vNdc, -1.0, 1.0);
  vec4 p1 = uInverseProjection * vec4(vNdc, 0.0, 1.0);
  vec3 d = normalize(uCameraToWorld * normalize(p1.xyz / p1.w - p0.xyz / p0.w));
  if (uMode == 1) {
    outColor = vec4(uIblScale * textureLod(uSpecularCube, world_to_env(d, uIblRotation), uBlurLod).rgb, 1.0);
  } else {
    outColor = vec4(uEnvScale * textureLod(uEnvironment, equirect_uv(world_to_env(d, uEnvRotation)), 0.0).rgb, 1.0);
  }
}
