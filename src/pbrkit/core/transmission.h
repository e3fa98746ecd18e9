#pragma once
// KHR_materials_transmission's specular_btdf and the dielectric interface it belongs to, in
// the exact form the path tracer uses (MODEL.md, "The dielectric interface"):
//
//   f(wo, wi) = F(wo.h) D(h) G(wo, wi) / (4 |n.wo| |n.wi|)                       reflection
//   f(wo, wi) = (1 - F(wo.h)) D(h) G(wo, wi) |wi.h| |wo.h| / (|n.wo| |n.wi| denom^2)
//               (/ eta^2 for radiance)                                           transmission
//
// with denom = wi.h + (wo.h) / eta and h the generalised half vector
// h = normalize(wo + eta wi) (Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces", eqs. 16, 20-21; pbrt-v4's DielectricBxDF), GGX D, height-correlated
// Smith G (Heitz 2014, eq. 99; Lambda depends on tan^2 only, so it is the same on both
// sides), F the exact dielectric Fresnel (unpolarised, with total internal reflection).
// Reflection or refraction is chosen with probability F / (1 - F) at the visible-normal
// sample h (Heitz 2018), so the sampler's weight is G2 / G1 for rough and exactly 1 (or
// 1 / eta^2 for radiance) for smooth interfaces.
//
// Local shading frame: n = +Z, both directions point away from the surface; the +Z side is
// the side the normal points to ("above"), the -Z side the other. `eta` is the ior of the
// -Z side over the +Z side (n_below / n_above); when wo is below (wo.z < 0) the functions
// use 1 / eta themselves, so one Dielectric describes the interface from both sides.
//
// Thin-walled interfaces (KHR_materials_volume thickness 0, or an open mesh) are a slab of
// zero thickness (the Khronos Sample Viewer's and Enterprise PBR's thin-walled mode): the
// light that enters leaves again at once, so the transmitted direction is the reflected
// one mirrored through the surface plane (-wo for a smooth wall), with no bending and no
// eta^2 scaling (the two interfaces' factors cancel), weighted by 1 - F of the first
// interface (the slab's inner reflections are not followed).
#include <glm/glm.hpp>

#include "pbrkit/core/math.h"

namespace pbrkit {

/// Below this alpha an interface is a delta lobe (pbrt-v4's EffectivelySmooth): a perfect
/// mirror and a perfect refraction. kMinRoughness (0.02, alpha 4e-4) is below it, so glTF
/// roughness 0 glass is smooth.
inline constexpr float kSmoothDielectricAlpha = 1e-3f;

/// Exact Fresnel reflectance of unpolarised light at a dielectric interface (the average of
/// the s and p reflectances; Born & Wolf, section 1.5.2; pbrt-v4 FrDielectric).
/// `cos_i` is the cosine between the incident direction and the normal, `eta` the ior of
/// the side the normal points away from over the side it points to. A negative `cos_i`
/// (the direction on the other side) is the same interface seen with 1 / eta.
/// Returns 1 under total internal reflection; 0 for eta = 1.
float fresnel_dielectric(float cos_i, float eta);

/// Snell's refraction of `w` (unit, on the side `n` points to: dot(w, n) > 0) through an
/// interface with `eta` = n_t / n_i (the ior of the far side over w's side). Sets `wt` to
/// the unit refracted direction (on the far side, pointing away from the surface) and
/// returns true, or returns false under total internal reflection.
bool refract(glm::vec3 w, glm::vec3 n, float eta, glm::vec3& wt);

/// Which quantity a path carries through a transmission (Veach 1997, section 5.2; pbrt-v4
/// TransportMode): radiance is scaled by 1 / eta^2 as it crosses into a denser medium,
/// importance is not.
enum class TransportMode { kRadiance, kImportance };

/// Multiple-scattering compensation of a rough interface (Kulla & Conty 2017, "Revisiting
/// Physically Based Shading at Imageworks", the dielectric part): a diffuse-like lobe on
/// each side holds the energy the single-scattering lobe loses, per side s (+Z: 0, -Z: 1)
///
///   f_ms(wo, wi) = (1 - E_s(mu_o)) (1 - E_s'(mu_i)) / (pi (1 - E_avg_s')) * share
///
/// with s' the side of wi, share = reflect[s] for a reflection and 1 - reflect[s] for a
/// transmission (/ eta'^2 for radiance), E the tabulated single-scattering albedo of the
/// interface (DielectricEnergyTable) seen from that side. Its albedo is 1 - E_s(mu_o), so
/// a non-absorbing interface conserves energy from both sides. The shares obey the
/// interface's reciprocity, (1 - reflect[0]) / (1 - E_avg_1) = eta^2 (1 - reflect[1]) /
/// (1 - E_avg_0) (the transmission lobe's f(wo, wi) = eta'^2 f(wi, wo) in importance
/// transport, as the single-scattering BTDF's); the rarer side's transmitted share is its
/// single-scattering one, T_avg / E_avg, and the denser side's follows (clamped to [0, 1],
/// where reciprocity gives way). Thin walls: the white GGX mirror's E (the thin wall's
/// exact single-scattering albedo) on both sides, transmitted share 1 - R_avg / E_avg.
struct DielectricCompensation {
  bool on = false;
  float roughness = 0.0f;  ///< the tables' roughness, sqrt(sqrt(alpha_x alpha_y))
  float E_avg[2] = {1.0f, 1.0f};
  float reflect[2] = {0.0f, 0.0f};
};

/// A dielectric interface at one shading point.
struct Dielectric {
  float eta = 1.5f;      ///< ior below / ior above (n_-Z / n_+Z)
  float alpha_x = 0.0f;  ///< GGX alpha along +X (roughness^2)
  float alpha_y = 0.0f;  ///< GGX alpha along +Y
  bool thin_walled = false;
  DielectricCompensation ms;  ///< off unless enable_dielectric_multiscatter is called
};

/// Turns on the multiple-scattering compensation of a rough interface (a no-op for a smooth
/// one); builds the albedo tables at first use.
void enable_dielectric_multiscatter(Dielectric& d);

/// True when the interface is a delta lobe (alpha below kSmoothDielectricAlpha or eta = 1,
/// where nothing reflects and the light passes straight on).
bool dielectric_is_smooth(const Dielectric& d);

/// The generalised half vector of Walter et al. 2007 (eq. 16), normalize(wo + eta' wi) with
/// eta' = eta when wi is below (a refraction; eta' = 1 for a reflection and 1 / eta seen
/// from below), turned to +Z. Zero when it is undefined (wo + eta' wi = 0).
glm::vec3 dielectric_half_vector(glm::vec3 wo, glm::vec3 wi, float eta);

/// f(wo, wi) without the cosine: reflection when wo and wi are on the same side, else
/// transmission. 0 for smooth interfaces (their lobes are deltas: dielectric_sample).
float dielectric_eval(const Dielectric& d, glm::vec3 wo, glm::vec3 wi,
                      TransportMode mode = TransportMode::kRadiance);
/// The pdf of dielectric_sample for wi (solid angle); 0 for smooth interfaces.
float dielectric_pdf(const Dielectric& d, glm::vec3 wo, glm::vec3 wi);

struct DielectricSample {
  glm::vec3 wi{0.0f};
  float f = 0.0f;       ///< f(wo, wi) (for a delta lobe: its weight times the pdf, with pdf 1)
  float pdf = 0.0f;     ///< solid-angle pdf; for a delta lobe the discrete probability
  float weight = 0.0f;  ///< f |wi.z| / pdf (for a delta lobe: F / P(R) or (1 - F) / P(T), / eta^2)
  bool transmitted = false;  ///< wi is on the other side of the surface from wo
  bool delta = false;        ///< a smooth interface's mirror or refraction
  bool valid = false;        ///< false: no sample (below the horizon, or a degenerate h)
};

/// Samples the interface from `wo` (either side): a visible normal h (Heitz 2018) with
/// `u`, then reflection with probability F(wo.h) chosen by `u_lobe`, else refraction
/// (thin-walled: the mirrored reflection). Smooth interfaces: the mirror with probability
/// F(wo.z), else the refraction (thin-walled: -wo).
DielectricSample dielectric_sample(const Dielectric& d, glm::vec3 wo, float u_lobe, glm::vec2 u,
                                   TransportMode mode = TransportMode::kRadiance);

// ---- KHR_materials_volume: Beer-Lambert absorption in the medium a closed mesh bounds. ----

/// The absorption coefficient sigma_a = -ln(attenuationColor) / attenuationDistance, per
/// channel (KHR_materials_volume README, "Attenuation"): 0 for an infinite distance (no
/// absorption) or a white colour; infinite for a black channel or a distance <= 0.
glm::vec3 volume_absorption(glm::vec3 attenuation_color, float attenuation_distance);

/// The fraction of radiance left after `distance` in the medium:
/// exp(-sigma_a distance) = attenuationColor^(distance / attenuationDistance), per channel,
/// in [0, 1] for every input (1 for distance <= 0 or an infinite attenuation distance).
glm::vec3 volume_transmittance(glm::vec3 attenuation_color, float attenuation_distance,
                               float distance);

}  // namespace pbrkit
