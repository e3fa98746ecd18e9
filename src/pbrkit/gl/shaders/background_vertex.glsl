#version 450
// A full-screen triangle at the far plane for the background pass, drawn after the opaque
// geometry with the depth test (LEQUAL against the cleared 1.0), so only the pixels no
// surface covers are shaded.
//
// vDirection is the world-space direction of the pixel's primary ray, unnormalised: the
// difference of the view-space points at NDC depth 0 and -1 is affine in the NDC (x, y)
// for perspective and orthographic projections alike, and w = 1 at every vertex, so
// interpolating it is exact; the fragment shader only normalises it.
uniform mat4 uInverseProjection;
uniform mat3 uCameraToWorld;
out vec3 vDirection;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  vec4 p0 = uInverseProjection * vec4(p, -1.0, 1.0);
  vec4 p1 = uInverseProjection * vec4(p, 0.0, 1.0);
  vDirection = uCameraToWorld * (p1.xyz / p1.w - p0.xyz / p0.w);
  gl_Position = vec4(p, 1.0, 1.0);
}
