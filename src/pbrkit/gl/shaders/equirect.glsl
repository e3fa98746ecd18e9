// The project's one environment orientation convention, mirroring src/pbrkit/core/equirect.h:
// +Y up, row 0 (v = 0) the zenith, the image centre faces -Z, u = 0.75 faces +X;
// u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi.

vec2 equirect_uv(vec3 d) {
  float u = 0.5 + atan(d.x, -d.z) * (0.5 * 0.31830988618379067154);
  float v = acos(clamp(d.y, -1.0, 1.0)) * 0.31830988618379067154;
  return vec2(u - floor(u), v);
}

// world_to_env: lookup(d) = map(R(-rotation) d) for a map rotated by `rotation_deg` about +Y.
vec3 world_to_env(vec3 d, float rotation_deg) {
  float a = -rotation_deg * (3.14159265358979323846 / 180.0);
  float c = cos(a), s = sin(a);
  return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}
