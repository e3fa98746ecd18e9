#version 450
// Scene geometry: object-space attributes to world space for pbr_fragment.glsl.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;  // xyz + handedness (glTF)
layout(location = 3) in vec2 aTexcoord0;
layout(location = 4) in vec2 aTexcoord1;
#ifndef HAS_COLOR_0
#define HAS_COLOR_0 1
#endif
layout(location = 5) in vec4 aColor;  // COLOR_0 (HAS_COLOR_0)
#ifndef DEFORM
#define DEFORM 0
#endif
#if DEFORM
// A deforming mesh reads its positions, normals and tangents from its rest data by
// gl_VertexID (the index the element buffer gives), not from the attributes above.
#include "deformation.glsl"
#endif

// Every instance's model matrix and normal matrix (the inverse transpose of the model's
// upper 3x3, in a mat4's columns), two per slot (gpu_scene.h, GpuScene::instance_buffer);
// a draw of n instances (glDrawElementsInstanced) reads slots uInstanceBase ... + n - 1.
layout(std430, binding = BINDING_INSTANCE_TRANSFORMS) readonly buffer InstanceTransforms { mat4 uInstanceMatrices[]; };
uniform int uInstanceBase;
uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vTexcoord0;
out vec2 vTexcoord1;
#if HAS_COLOR_0
out vec4 vColor;
#endif
// The instance's slot, for a surface under occluders (occluders.glsl skips its own proxy).
#if defined(IBL_OCCLUDERS)
#if IBL_OCCLUDERS
#define OWN_SLOT 1
flat out int vSlot;
#endif
#endif

void main() {
  int slot = uInstanceBase + gl_InstanceID;
  mat4 model = uInstanceMatrices[2 * slot];
  mat3 normal_matrix = mat3(uInstanceMatrices[2 * slot + 1]);
#if DEFORM
  DeformedVertex d = deformed_vertex(gl_VertexID);
  vec3 position = d.position, normal = d.normal;
  vec4 tangent = d.tangent;
#else
  vec3 position = aPosition, normal = aNormal;
  vec4 tangent = aTangent;
#endif
  vec4 world = model * vec4(position, 1.0);
  vPosition = world.xyz;
  vNormal = normal_matrix * normal;
  vTangent = vec4(mat3(model) * tangent.xyz, tangent.w);
  vTexcoord0 = aTexcoord0;
  vTexcoord1 = aTexcoord1;
#if HAS_COLOR_0
  vColor = aColor;
#endif
#ifdef OWN_SLOT
  vSlot = slot;
#endif
  gl_Position = uViewProjection * world;
}
