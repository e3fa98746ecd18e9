// Deforming meshes in the vertex shader (DEFORM 1 and 2; gpu_deformation.h uploads the
// data): a vertex's rest attributes morphed, then skinned, exactly as scene/pose.cpp's
// deform() computes them on the CPU, so that a mesh posed here and one posed there and
// uploaded as it is give the same image.

// The mesh's data, in words of four 32-bit values (floats by their bits): per vertex v its
// rest position, normal and tangent at 3v, 3v + 1, 3v + 2; from uInfluenceOffset, per vertex
// (uInfluences + 1) / 2 words of (joint, weight, joint, weight); from uCornerOffset (DEFORM
// 2), per vertex its triangle's three corners and 1 (0: in no triangle); from uTargetOffset,
// per morph target t and vertex v the position, normal and tangent displacements at
// uTargetOffset + 3 (t uDeformVertexCount + v).
layout(std430, binding = BINDING_DEFORM_VERTICES) readonly buffer DeformVertices { uvec4 uDeform[]; };
// Every skin's joint matrices (world of the joint times its inverse bind matrix), the mesh's
// skin's from uJointBase (-1: not skinned); every deforming mesh's morph weights, this one's
// uMorphTargets from uMorphWeightBase. Both change with the pose (Renderer::set_pose).
layout(std430, binding = BINDING_JOINT_MATRICES) readonly buffer JointMatrices { mat4 uJointMatrices[]; };
layout(std430, binding = BINDING_MORPH_WEIGHTS) readonly buffer MorphWeights { float uMorphWeights[]; };
uniform int uDeformVertexCount;
uniform int uInfluences;
uniform int uMorphTargets;
uniform int uJointBase;
uniform int uMorphWeightBase;
uniform int uInfluenceOffset;
uniform int uCornerOffset;
uniform int uTargetOffset;
// Bit 0: the mesh has normals, bit 1: tangents (without them the attribute's GL default, as
// a mesh uploaded without the array reads).
uniform int uDeformAttributes;

struct DeformedVertex {
  vec3 position;
  vec3 normal;
  vec4 tangent;
};

vec4 deform_word(int i) {
  return uintBitsToFloat(uDeform[i]);
}

vec3 unit_or(vec3 v, vec3 fallback) {
  float len = length(v);
  return len > 0.0 && !isinf(len) && !isnan(len) ? v / len : fallback;
}

// Vertex v morphed (glTF 2.0 section 3.7.2.2: the rest attribute plus the weighted sum of the
// targets' displacements; a tangent's handedness stays) and then skinned (section 3.7.3.1:
// linear blend skinning by the joint matrices, which leaves the vertex in world space, the
// skinned node's own transform ignored). Normals transform by the inverse transpose of the
// blended matrix, tangents, which lie in the surface, by the matrix itself.
DeformedVertex morphed_and_skinned(int v) {
  DeformedVertex d;
  d.position = deform_word(3 * v).xyz;
  d.normal = deform_word(3 * v + 1).xyz;
  d.tangent = deform_word(3 * v + 2);
  for (int t = 0; t < uMorphTargets; ++t) {
    float w = uMorphWeights[uMorphWeightBase + t];
    if (w == 0.0) continue;
    int at = uTargetOffset + 3 * (t * uDeformVertexCount + v);
    d.position += w * deform_word(at).xyz;
    d.normal += w * deform_word(at + 1).xyz;
    d.tangent.xyz += w * deform_word(at + 2).xyz;
  }
  if (uJointBase >= 0) {
    mat4 m = mat4(0.0);
    int first = uInfluenceOffset + v * ((uInfluences + 1) / 2);
    for (int c = 0; c < uInfluences; ++c) {
      uvec4 word = uDeform[first + c / 2];
      uvec2 influence = (c & 1) == 0 ? word.xy : word.zw;
      float w = uintBitsToFloat(influence.y);
      if (w != 0.0) m += w * uJointMatrices[uJointBase + int(influence.x)];
    }
    d.position = vec3(m * vec4(d.position, 1.0));
    mat3 linear = mat3(m);
    d.normal = transpose(inverse(linear)) * d.normal;
    d.tangent.xyz = linear * d.tangent.xyz;
  }
  d.normal = (uDeformAttributes & 1) != 0 ? unit_or(d.normal, vec3(0.0, 0.0, 1.0)) : vec3(0.0);
  d.tangent = (uDeformAttributes & 2) != 0 ? vec4(unit_or(d.tangent.xyz, vec3(1.0, 0.0, 0.0)), d.tangent.w)
                                          : vec4(0.0, 0.0, 0.0, 1.0);
  return d;
}

// Vertex v at the pose.
DeformedVertex deformed_vertex(int v) {
  DeformedVertex d = morphed_and_skinned(v);
#if DEFORM == 2
  // Flat normals (the file has none; section 3.7.2.1): the loader unwelded the triangles, so
  // the vertex has one triangle, whose deformed corners give its normal.
  uvec4 corners = uDeform[uCornerOffset + v];
  d.normal = vec3(0.0, 0.0, 1.0);
  if (corners.w != 0u) {
    vec3 p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = int(corners[k]) == v ? d.position : morphed_and_skinned(int(corners[k])).position;
    d.normal = unit_or(cross(p[1] - p[0], p[2] - p[0]), vec3(0.0, 0.0, 1.0));
  }
#endif
  return d;
}
