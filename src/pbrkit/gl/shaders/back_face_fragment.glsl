#version 450
// The back-face pass of thick transmissive objects (thick_refraction.glsl; Wyman 2005): the
// world position (w = 1: a back face is here) and the outward normal of the nearest back
// face of the object about to be drawn, per pixel. Drawn with pbr_vertex.glsl, front faces
// culled.
in vec3 vPosition;
in vec3 vNormal;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;

void main() {
  outPosition = vec4(vPosition, 1.0);
  outNormal = vec4(normalize(vNormal), 0.0);
}
