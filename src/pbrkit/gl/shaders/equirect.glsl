// The project's one environment orientation convention, mirroring src/pbrkit/core/equirect.h:
// +Y up, row 0 (v = 0) the zenith, the image centre faces -Z, u = 0.75 faces +X;
// u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi.

vec2 equirect_uv(vec3 d) {
  float u = 0.5 + atan(d.x, -d.z) * (0.5 * 0.31830988618379067154);
  float v = acos(clamp(d.y, -1.0, 1.0)) * 0.31830988618379067154;
  return vec2(u - floor(u), v);
}

// world_to_env: lookup(d) = map(R(-rotation) d) for a map rotated by `rotation_deg` about +Y.
// `rotation` is (cos a, sin a) with a = -rotation_deg * pi / 180, computed once on the CPU
// (renderer.cpp's env_rotation_cs): a per-pixel cos and sin of a uniform are not free on
// llvmpipe.
vec3 world_to_env(vec3 d, vec2 rotation) {
  float c = rotation.x, s = rotation.y;
  return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}
