#version 450
// Shader unit test: transmission.glsl's and thick_refraction.glsl's functions for a batch of inputs (one invocation
// each; uFunction picks which) so tests/gl/transmission_glsl_test.cpp can compare them
// with their C++ references.
#include "transmission.glsl"
#include "thick_refraction.glsl"

layout(local_size_x = 64) in;

// transmission_eval.cpp's TransmissionCase record.
struct TransmissionCase {
  vec4 n_ior;             // normal, ior
  vec4 v_thickness;       // towards the viewer, thickness
  vec4 scale_dispersion;  // model scale, dispersion
  vec4 attenuation;       // attenuation colour, attenuation distance
  vec4 rough;             // roughness, frame width, distance through the medium
  vec4 base;              // base colour, metallic
  vec4 back_point;        // a point of the back face
  vec4 back_normal;       // the back face's outward normal
};
layout(std430, binding = 0) readonly buffer Cases { TransmissionCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform int uCount;
uniform int uFunction;  // transmission_eval.h's TransmissionFunction
uniform mat4 uViewProjection;
uniform mat4 uInverseViewProjection;
layout(binding = 0) uniform sampler2D uEnergy;      // make_brdf's argument; not read
layout(binding = 1) uniform sampler2D uFrameDepth;  // the frame's depth (functions 9-11)
layout(binding = 2) uniform sampler2D uFrame;       // reflected_frame's colours (function 10)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uCount)) return;
  TransmissionCase c = cases[i];
  vec4 r = vec4(0.0);
  if (uFunction == 0) {
    r.xyz = volume_transmission_ray(c.n_ior.xyz, c.v_thickness.xyz, c.v_thickness.w, c.n_ior.w,
                                    c.scale_dispersion.xyz);
  } else if (uFunction == 1) {
    r.xyz = dispersion_iors(c.n_ior.w, c.scale_dispersion.w);
  } else if (uFunction == 2) {
    r.xyz = volume_attenuation(c.rough.z, c.attenuation.rgb, c.attenuation.w);
  } else if (uFunction == 3) {
    r.x = transmission_roughness(c.rough.x, c.n_ior.w);
    r.y = transmission_lod(c.rough.x, c.n_ior.w, c.rough.y);
  } else if (uFunction == 5) {
    // n is wo, v the mirrored wi (local frame); no compensation: make_brdf reads no table.
    BaseLayer layer = base_layer(c.base.rgb, c.base.a, c.rough.x);
    layer.ior = c.n_ior.w;
    Brdf b = make_brdf(layer, GEOMETRY_REFERENCE, false, FRESNEL_SCHLICK, uEnergy);
    r.xyz = punctual_transmission(b, c.n_ior.xyz, c.v_thickness.xyz, c.n_ior.w);
  } else if (uFunction == 6) {
    bool tir;
    r.xyz = refract_twice(c.v_thickness.xyz, c.n_ior.xyz, c.back_normal.xyz, c.n_ior.w, tir);
    r.w = tir ? 1.0 : 0.0;
  } else if (uFunction == 7) {
    r.x = wyman_distance(c.rough.z, c.v_thickness.w, dot(c.n_ior.xyz, c.v_thickness.xyz), c.n_ior.w);
  } else if (uFunction == 8) {
    r.x = back_plane_distance(c.n_ior.xyz, c.v_thickness.xyz, c.rough.z, c.back_point.xyz,
                              c.back_normal.xyz);
  } else if (uFunction == 9) {
    vec3 origin = c.n_ior.xyz, dir = c.v_thickness.xyz;
    vec2 uv;
    float d;
    bool hit = frame_hit(origin, uViewProjection * vec4(origin, 1.0),
                         uViewProjection * vec4(dir, 0.0), uInverseViewProjection, uFrameDepth,
                         kFrameHitIterations, uv, d);
    r = vec4(uv, d, hit ? 1.0 : 0.0);
  } else if (uFunction == 11) {
    vec2 uv;
    float d;
    bool hit = frame_march(uViewProjection * vec4(c.n_ior.xyz, 1.0),
                           uViewProjection * vec4(c.v_thickness.xyz, 0.0), uFrameDepth, true, uv, d);
    r = vec4(uv, d, hit ? 1.0 : 0.0);
  } else if (uFunction == 10) {
    vec3 seen;
    bool found = reflected_frame(c.n_ior.xyz, c.v_thickness.xyz, uViewProjection,
                                 uInverseViewProjection, uFrameDepth, uFrame, 0.0, seen);
    r = vec4(seen, found ? 1.0 : 0.0);
  } else {
    vec2 uv;
    r.z = project_to_screen(uViewProjection, c.n_ior.xyz, uv) ? 1.0 : 0.0;
    r.xy = uv;
  }
  results[i] = r;
}
