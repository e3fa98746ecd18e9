// KHR_materials_anisotropy's image-based lighting: ibl/anisotropic_taps.h in GLSL (the
// C++ is the reference; tests/gl/anisotropy_glsl_test.cpp holds them equal). A fixed set
// of kAnisotropicTaps directions drawn from the anisotropic lobe's visible normals (Heitz
// 2018) at a lattice held to the lobe's axes, each looked up in the prefiltered cube at the
// roughness whose lobe covers its share of the solid angle (filtered importance sampling:
// Colbert & Krivanek, GPU Gems 3 ch. 20, 2007), weighted by the VNDF estimator's
// G2 / G1(wo). The taps follow the
// stretched lobe, and their weights give the lobe's own albedo, the one the path tracer
// integrates (the isotropic table at the geometric-mean roughness is far brighter on a
// strongly stretched lobe: 0.88 against 0.53 at alpha 1 x 0.09, normal incidence).
#include "brdf.glsl"
#include "equirect.glsl"

const int kAnisotropicTaps = 8;

// anisotropic_visible_normal: microfacet.h's sample_ggx_visible_normal (Heitz 2018,
// listing 1) with the disk point fixed to the lobe's axes instead of the view's: the
// point's polar angle is measured from the local +X, then expressed in the sampler's frame
// (T1, T2), whose azimuth follows the stretched view and swings by pi across n.v's
// azimuth where the stretched view is near the normal. A fixed lattice turned with it
// creases the image along those lines; held to the lobe, it moves smoothly. Any rotation
// of a uniform disk point is uniform, so the sampler stays Heitz's.
vec3 anisotropic_visible_normal(vec3 wo, vec2 u, float ax, float ay) {
  vec3 Vh = normalize(vec3(ax * wo.x, ay * wo.y, wo.z));
  float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
  float inv_len = lensq > 0.0 ? inversesqrt(lensq) : 0.0;
  vec3 T1 = lensq > 0.0 ? vec3(-Vh.y, Vh.x, 0.0) * inv_len : vec3(1.0, 0.0, 0.0);
  vec3 T2 = cross(Vh, T1);
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  vec2 d = r * vec2(cos(phi), sin(phi));  // on the disk, from the lobe's +X
  vec2 cs = lensq > 0.0 ? vec2(-Vh.y, Vh.x) * inv_len : vec2(1.0, 0.0);  // T1's azimuth
  float t1 = d.x * cs.x + d.y * cs.y;
  float t2 = d.y * cs.x - d.x * cs.y;
  float s = 0.5 * (1.0 + Vh.z);
  t2 = (1.0 - s) * sqrt(max(1.0 - t1 * t1, 0.0)) + s * t2;
  vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(1.0 - t1 * t1 - t2 * t2, 0.0)) * Vh;
  return normalize(vec3(ax * Nh.x, ay * Nh.y, max(Nh.z, 1e-7)));
}

// anisotropic_tap_point: u1 stratified, u2 four arms 90 degrees apart (anisotropic_taps.cpp
// says how the lattice was chosen).
vec2 anisotropic_tap_point(int i) {
  float u2 = float(i) * 0.25 + 0.3125;
  return vec2((float(i) + 0.5) / float(kAnisotropicTaps), u2 - floor(u2));
}

// anisotropic_tap: tap i's reflected direction (local frame), its weight G2 / G1(wo) (0
// below the horizon) and the perceptual roughness of its lookup, from the tap's solid
// angle 1 / (K pdf) = 4 pi alpha^2: alpha^2 = n.v (1 + Lambda_o) / (pi K D(h)).
void anisotropic_tap(vec3 wo, float ax, float ay, int i, out vec3 wi, out float weight,
                     out float roughness) {
  vec3 h = anisotropic_visible_normal(wo, anisotropic_tap_point(i), ax, ay);
  wi = 2.0 * dot(wo, h) * h - wo;
  float lambda_o = SmithLambdaGGXAniso(wo, ax, ay);
  weight = wi.z > 0.0 ? (1.0 + lambda_o) / (1.0 + lambda_o + SmithLambdaGGXAniso(wi, ax, ay)) : 0.0;
  float d = DistributionGGXAniso(h, ax, ay);
  float alpha2 = wo.z * (1.0 + lambda_o) / (kPi * float(kAnisotropicTaps) * max(d, 1e-6));
  roughness = clamp(sqrt(sqrt(alpha2)), kMinRoughness, 1.0);
}

// The anisotropic lobe's environment radiance without Fresnel, integral of
// D G2 / (4 n.v) L dwi ~= sum_i weight_i L(wi_i) / K, from the prefiltered `cube` of
// `levels` levels, each tap at the level nearest its roughness (ibl.glsl's roughness_lod,
// rounded: with no fraction llvmpipe reads one level instead of two, 16% of the anisotropy
// scene's frame with eight taps, and the eight taps' sum hides each one's step). `frame`
// is the local frame's world axes (anisotropy direction, bitangent, normal), `rotation`
// the environment's (world_to_env). A tap below the horizon has weight 0 and is read
// anyway: no branch around the fetch.
vec3 anisotropic_ibl_radiance(samplerCube cube, int levels, mat3 frame, vec2 rotation, vec3 wo,
                              float ax, float ay) {
  wo = normalize(vec3(wo.xy, max(wo.z, 1e-4)));
  vec3 sum = vec3(0.0);
  for (int i = 0; i < kAnisotropicTaps; ++i) {
    vec3 wi;
    float weight, roughness;
    anisotropic_tap(wo, ax, ay, i, wi, weight, roughness);
    sum += weight * textureLod(cube, world_to_env(frame * wi, rotation),
                               floor(roughness * float(levels - 1) + 0.5)).rgb;
  }
  return sum / float(kAnisotropicTaps);
}
