#version 450
// A full-screen triangle at the far plane for the background pass, drawn after the opaque
// geometry with the depth test (LEQUAL against the cleared 1.0), so only the pixels no
// surface covers are shaded.
out vec2 vNdc;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  vNdc = p;
  gl_Position = vec4(p, 1.0, 1.0);
}
