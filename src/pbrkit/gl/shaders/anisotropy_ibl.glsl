// KHR_materials_anisotropy's image-based lighting: ibl/anisotropic_taps.h and
// ibl/anisotropic_albedo.h in GLSL (the C++ is the reference; tests/gl/anisotropy_glsl_test.cpp
// holds them equal). Three directions drawn from the anisotropic lobe's visible normals
// (Heitz 2018) at fixed points of its disk held to the lobe's axes (the centre and two
// points along the long axis), each looked up in the prefiltered cube at the roughness of
// the isotropic lobe with the whole lobe's solid angle at normal incidence (filtered
// importance sampling: Colbert & Krivanek, GPU Gems 3 ch. 20, 2007); their mean, weighted by
// the VNDF estimator's G2 / G1(wo), is scaled by the lobe's albedo from the tabulated
// integral. The taps follow the stretched lobe, and the scale is the lobe's own albedo, the
// one the path tracer integrates (the isotropic table at the geometric-mean roughness is far
// brighter on a strongly stretched lobe: 0.88 against 0.53 at alpha 1 x 0.09, normal
// incidence).
#include "brdf.glsl"
#include "equirect.glsl"

const int kAnisotropicTaps = 3;

// The visible-normal sampler's frame for wo, which every tap of a pixel shares: the
// stretched view Vh, its (T1, T2), T1's azimuth cs and the warp's s.
struct VisibleNormalFrame {
  vec3 Vh, T1, T2;
  vec2 cs;
  float s;
};

VisibleNormalFrame visible_normal_frame(vec3 wo, float ax, float ay) {
  VisibleNormalFrame f;
  f.Vh = normalize(vec3(ax * wo.x, ay * wo.y, wo.z));
  float lensq = f.Vh.x * f.Vh.x + f.Vh.y * f.Vh.y;
  float inv_len = lensq > 0.0 ? inversesqrt(lensq) : 0.0;
  f.T1 = lensq > 0.0 ? vec3(-f.Vh.y, f.Vh.x, 0.0) * inv_len : vec3(1.0, 0.0, 0.0);
  f.T2 = cross(f.Vh, f.T1);
  f.cs = lensq > 0.0 ? vec2(-f.Vh.y, f.Vh.x) * inv_len : vec2(1.0, 0.0);  // T1's azimuth
  f.s = 0.5 * (1.0 + f.Vh.z);
  return f;
}

// anisotropic_visible_normal: microfacet.h's sample_ggx_visible_normal (Heitz 2018,
// listing 1) for the disk point d given in the lobe's axes (its polar angle measured from the
// local +X) instead of the view's, then expressed in the sampler's frame (T1, T2), whose
// azimuth follows the stretched view and swings by pi across n.v's azimuth where the
// stretched view is near the normal. A fixed point turned with it creases the image along
// those lines; held to the lobe, it moves smoothly.
vec3 visible_normal_at(VisibleNormalFrame f, vec2 d, float ax, float ay) {
  float t1 = d.x * f.cs.x + d.y * f.cs.y;
  float t2 = d.y * f.cs.x - d.x * f.cs.y;
  t2 = (1.0 - f.s) * sqrt(max(1.0 - t1 * t1, 0.0)) + f.s * t2;
  vec3 Nh = t1 * f.T1 + t2 * f.T2 + sqrt(max(1.0 - t1 * t1 - t2 * t2, 0.0)) * f.Vh;
  return normalize(vec3(ax * Nh.x, ay * Nh.y, max(Nh.z, 1e-7)));
}

vec3 anisotropic_visible_normal(vec3 wo, vec2 d, float ax, float ay) {
  return visible_normal_at(visible_normal_frame(wo, ax, ay), d, ax, ay);
}

// anisotropic_tap_point: the centre, then (+-sqrt(3/8), 0) along the lobe's long axis
// (anisotropic_taps.h says why).
const float kTapRadius = 0.61237244;  // sqrt(3/8)
vec2 anisotropic_tap_point(int i) {
  return vec2(i == 0 ? 0.0 : (i == 1 ? kTapRadius : -kTapRadius), 0.0);
}

// What every tap of a pixel shares: the sampler's frame, Lambda(wo) and the perceptual
// roughness of the lookups, that of the isotropic lobe with the whole lobe's solid angle at
// normal incidence, 1 / pdf = 4 pi alpha^2 with pdf = D(n) / 4 = 1 / (4 pi alpha_x alpha_y):
// alpha^2 = alpha_x alpha_y (the energy tables' roughness, Brdf's table_roughness). Each
// tap so blurs across the short axis more than the lobe does, and the three spread it along
// the long one; a third of that solid angle each left ghosts of hard edges between the taps.
// It depends on the material alone, so llvmpipe reads each tap at one level for the whole
// draw (a per-pixel level costs it 4% of the frame).
struct AnisotropicTaps {
  VisibleNormalFrame frame;
  float lambda_o;
  float roughness;
};

AnisotropicTaps anisotropic_taps(vec3 wo, float ax, float ay) {
  AnisotropicTaps t;
  t.frame = visible_normal_frame(wo, ax, ay);
  t.lambda_o = SmithLambdaGGXAniso(wo, ax, ay);
  t.roughness = clamp(sqrt(sqrt(ax * ay)), kMinRoughness, 1.0);
  return t;
}

// Tap i's reflected direction (local frame) and its weight G2 / G1(wo) (0 below the horizon).
void anisotropic_tap_of(AnisotropicTaps t, vec3 wo, float ax, float ay, int i, out vec3 wi,
                        out float weight) {
  vec3 h = visible_normal_at(t.frame, anisotropic_tap_point(i), ax, ay);
  wi = 2.0 * dot(wo, h) * h - wo;
  weight = wi.z > 0.0 ? (1.0 + t.lambda_o) / (1.0 + t.lambda_o + SmithLambdaGGXAniso(wi, ax, ay))
                      : 0.0;
}

// anisotropic_taps.h's anisotropic_tap: tap i's direction, weight and lookup roughness.
void anisotropic_tap(vec3 wo, float ax, float ay, int i, out vec3 wi, out float weight,
                     out float roughness) {
  AnisotropicTaps t = anisotropic_taps(wo, ax, ay);
  anisotropic_tap_of(t, wo, ax, ay, i, wi, weight);
  roughness = t.roughness;
}

// AnisotropicAlbedoTable::lookup (ibl/anisotropic_albedo.h): `table` is its nodes as a 3D
// texture with linear filtering (gl/energy_texture.h), which interpolates sqrt(n.v), p and
// r (node i of n at the texel centre (i + 0.5) / n); block l of kR slices holds the nodes
// s = l and l + 1 in .r and .g, interpolated here (the r coordinate held inside the block,
// so the filter never blends two blocks).
const vec3 kAlbedoNodes = vec3(16.0, 8.0, 16.0);  // kMu, kPhi, kR
const float kAlbedoS = 8.0;                          // kS
float anisotropic_albedo(sampler3D table, vec3 wo, float ax, float ay) {
  vec2 xy = abs(wo.xy);
  if (ay > ax) {
    float t = ax;
    ax = ay;
    ay = t;
    xy = xy.yx;
  }
  float p = xy.x + xy.y > 0.0 ? xy.y / (xy.x + xy.y) : 0.0;
  float s = ay < 1.0 ? sqrt(clamp((ax - ay) / (1.0 - ay), 0.0, 1.0)) : 0.0;
  vec3 c = vec3(sqrt(clamp(wo.z, 0.0, 1.0)), p, sqrt(ay)) * (kAlbedoNodes - 1.0) + 0.5;
  float x = s * (kAlbedoS - 1.0);
  float l = min(floor(x), kAlbedoS - 2.0);
  c.z += l * kAlbedoNodes.z;
  vec2 a = textureLod(table, c / vec3(kAlbedoNodes.xy, kAlbedoNodes.z * (kAlbedoS - 1.0)), 0.0).rg;
  return mix(a.x, a.y, x - l);
}

// The anisotropic lobe's environment radiance without Fresnel, integral of D G2 / (4 n.v) L
// dwi ~= albedo sum_i weight_i L(wi_i) / sum_i weight_i, from the prefiltered `cube` of
// `levels` levels, every tap at the level nearest their roughness (ibl.glsl's roughness_lod,
// rounded: with no fraction llvmpipe reads one level instead of two), and the albedo from
// `albedo_table`. `frame` is the local frame's world axes (anisotropy direction, bitangent,
// normal), `rotation` the environment's (world_to_env). A tap below the horizon has weight 0
// and is read anyway: no branch around the fetch.
vec3 anisotropic_ibl_radiance(samplerCube cube, int levels, sampler3D albedo_table, mat3 frame,
                              vec2 rotation, vec3 wo, float ax, float ay) {
  wo = normalize(vec3(wo.xy, max(wo.z, 1e-4)));
  AnisotropicTaps taps = anisotropic_taps(wo, ax, ay);
  float lod = floor(taps.roughness * float(levels - 1) + 0.5);
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < kAnisotropicTaps; ++i) {
    vec3 wi;
    float weight;
    anisotropic_tap_of(taps, wo, ax, ay, i, wi, weight);
    sum += weight * textureLod(cube, world_to_env(frame * wi, rotation), lod).rgb;
    weights += weight;
  }
  return weights > 0.0 ? anisotropic_albedo(albedo_table, wo, ax, ay) / weights * sum : vec3(0.0);
}
