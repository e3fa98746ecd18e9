// The path tracer's integrator (integrator.h). Li is written in the order of the
// estimator, one path vertex per iteration: the light the ray finds (emission or the
// environment, MIS-weighted against light sampling), direct lighting by light sampling
// (sample_ld), then the BSDF sample and Russian roulette that continue the path.
#include "pbrkit/pt/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pbrkit/core/dispersion.h"
#include "pbrkit/core/transmission.h"
#include "pbrkit/pt/environment_sampler.h"
#include "pbrkit/pt/ray_offset.h"
#include "pbrkit/pt/shading.h"

namespace pbrkit {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Power heuristic with beta = 2 (Veach 1997, eq. 9.13).
inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  if (!std::isfinite(f2)) return 1.0f;
  return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
}

// A uniform float from a hash of its arguments: decisions that need more random numbers
// than the sampler's fixed dimensions (repeated stochastic-transparency tests along one
// ray). Deterministic, so renders stay reproducible. (PCG hash, Jarzynski & Olano 2020.)
// Not inlined: the compiler would otherwise hoist the rounds that depend on the pixel and
// sample only out of the path loop and pay for them on every path, with or without alpha.
[[gnu::noinline]] float hash_float(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                   std::uint32_t d) {
  std::uint32_t h = a * 747796405u + 2891336453u;
  for (std::uint32_t x : {b, c, d}) {
    h ^= x + 0x9e3779b9u + (h << 6) + (h >> 2);
    h = h * 747796405u + 2891336453u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
  }
  return float(h >> 8) * 0x1p-24f;
}

// The denoiser's features (albedo, normal, depth) are those of the first vertex that is
// not near-specular, as denoisers expect: seen in a mirror, the mirrored surface's texture
// and edges are what the image shows. A vertex is near-specular when it is a smooth metal
// or smooth glass (its reflection or refraction is a sharp image of what it faces). The first
// vertex records its own features; a later one replaces them when every vertex before it was
// near-specular (its albedo tinted by the path throughput, its depth the length of the path to it).
// A path that escapes records the environment it sees (AovTracker::escape).
constexpr float kAovSpecularRoughness = 0.1f;

inline bool near_specular_for_aovs(const ShadingInputs& in) {
  if (in.params.base.roughness >= kAovSpecularRoughness) return false;
  return in.params.base.metallic >= 0.5f || in.params.transmission.weight >= 0.5f;
}

struct AovTracker {
  bool through_specular = true;  // every vertex so far was near-specular
  float distance = 0.0f;         // path length to the current vertex

  // Called at each surface vertex with its features; `specular` says whether the path
  // would continue through it for the AOVs.
  void record(PathSample& out, int depth, glm::vec3 albedo, glm::vec3 beta, glm::vec3 normal,
              float t, bool specular) {
    distance += t;
    if (depth == 0 || through_specular) {
      out.albedo = depth == 0 ? albedo : glm::clamp(beta * albedo, 0.0f, 1.0f);
      out.normal = normal * 0.5f + 0.5f;
      out.depth = distance;
    }
    through_specular = through_specular && specular;
  }

  // Called when the ray escapes to the environment, whose radiance `Le` it sees: the
  // features of the sky are its radiance compressed to [0, 1) (Le / (1 + Le)), as an
  // albedo, and a normal facing the ray, so that the denoiser keeps the environment's
  // detail as it keeps a texture's.
  void escape(PathSample& out, int depth, glm::vec3 Le, glm::vec3 beta, glm::vec3 direction) {
    if (depth == 0 || through_specular) {
      const glm::vec3 a = Le / (1.0f + Le);
      out.albedo = depth == 0 ? a : glm::clamp(beta * a, 0.0f, 1.0f);
      out.normal = -direction * 0.5f + 0.5f;
      out.depth = distance;
    }
  }
};

// Beer-Lambert over `distance` (infinite for a ray that escapes): exp(-sigma_a d) per
// channel; no NaN for sigma_a = inf or d = inf.
// (Out of line: only paths inside volumes call it, and Li's other helpers must stay inline.)
[[gnu::noinline]] glm::vec3 absorb(glm::vec3 sigma_a, float distance) {
  glm::vec3 tr;
  for (int c = 0; c < 3; ++c) tr[c] = sigma_a[c] > 0.0f ? std::exp(-sigma_a[c] * distance) : 1.0f;
  return tr;
}

}  // namespace

// Li's helpers below are defined `inline` (they are used in this file only) so that the
// compiler inlines them into Li as it did when they were in-class definitions: out of
// line, the sampling loop executed 2% more instructions (callgrind, spheres at 96x96,
// 16 spp).

PathSample Integrator::Li(glm::vec3 origin, glm::vec3 direction,
                          const SceneGeometry::PacketHit& primary, OwenSobolPixel& sampler,
                          std::uint32_t pixel, std::uint32_t index, std::uint64_t& rays,
                          float time) const {
  PathSample out;
  glm::vec3 beta(1.0f);
  float prev_pdf = 0.0f;  // BSDF pdf of the direction that led here (for MIS)
  glm::vec3 prev_p(0.0f);
  glm::vec3 prev_n(0.0f);  // its geometric normal (the light sampler's choice depends on it)
  const EnvironmentSampler* env = lights_.environment_sampler();
  EnvironmentSampler::Location env_at;  // where `direction` meets the map (depth > 0)
  const LightStrategy strategy = settings_.strategy;
  AovTracker aov;
  MediumStack media;  // the volumes the path is inside (empty: vacuum)
  int channel = -1;   // the colour channel chosen at the first dispersive surface
  // The ray cone's width at the ray's origin (texture level of detail). It grows by the
  // pixel's spread over each segment and passes through specular bounces unchanged, as off
  // a plane (the paper's curvature term is left out); after any other bounce it is -1 and
  // textures are read at level 0, unfiltered: a rough lobe's spread is no cone, and level 0
  // keeps indirect lighting unbiased.
  float cone = settings_.texture_lod && !scene_.textures.empty() ? pixel_cone_.width : -1.0f;
  // One hit for the whole path: each bounce's closest_hit overwrites it where it finds one,
  // and a fresh one per bounce cost a 112-byte zero fill (2% of the render on `spheres`).
  SurfaceHit hit;
  // Path guiding: the vertices whose continuation is recorded once the path is done.
  GuideVertex guide_vertices[kMaxGuideVertices];
  int guide_count = 0;
  float rr_boost = 1.0f;  // the product of p_mixture / p_bsdf over the guided bounces
  for (int depth = 0;; ++depth) {
    const Material* material = nullptr;
    const glm::vec3 segment_start = origin;
    const bool found = closest_hit(origin, direction, pixel, index, depth, rays, hit, material,
                                   depth == 0 ? &primary : nullptr, time);
    // Beer-Lambert absorption along the segment inside a volume (KHR_materials_volume).
    if (media.size > 0) {
      beta *= absorb(media.sigma_a(), found ? glm::length(hit.p - segment_start)
                                            : std::numeric_limits<float>::infinity());
      if (beta == glm::vec3(0.0f)) break;
    }
    if (!found) {
      // The environment, weighted against the light sample that could have found it.
      if (env && (depth > 0 || settings_.env_visible)) {
        const bool mis = depth > 0 && strategy == LightStrategy::kMis;
        float env_pdf = 0.0f;
        const glm::vec3 Le =
            env->eval(depth > 0 ? env_at : env->locate(direction), mis ? &env_pdf : nullptr);
        float w = 1.0f;
        if (depth > 0) {
          if (strategy == LightStrategy::kLightOnly) w = 0.0f;
          if (mis) w = power_heuristic(prev_pdf, lights_.environment_probability() * env_pdf);
        }
        out.L += beta * Le * w;
        if (std::isfinite(Le.x + Le.y + Le.z)) aov.escape(out, depth, Le, beta, direction);
      }
      break;
    }
    const glm::vec3 wo = -direction;
    // Double-sided materials shade the side they are seen from; single-sided back
    // faces were culled in closest_hit.
    // (shade_inputs turns the shading normal to the same side.)
    const bool front_face = glm::dot(hit.ng, wo) >= 0.0f;  // the ray arrives from outside
    if (!front_face) hit.ng = -hit.ng;
    if (cone >= 0.0f) {
      cone += pixel_cone_.spread * glm::length(hit.p - segment_start);
      hit.footprint = cone / std::max(glm::dot(hit.ng, wo), 1e-6f);
    }
    // Emission (glTF emission is seen from the front, or from both sides when
    // double-sided; a culled back face never gets here), weighted like the environment's.
    const glm::vec3 Le = material_emission(scene_, *material, hit);
    if (Le != glm::vec3(0.0f)) {
      float w = 1.0f;
      if (depth > 0) {
        if (strategy == LightStrategy::kLightOnly) w = 0.0f;
        if (strategy == LightStrategy::kMis)
          w = power_heuristic(prev_pdf, lights_.triangle_pdf(hit, prev_p, prev_n));
      }
      out.L += beta * Le * w;
    }

    ShadingInputs in = shade_inputs(scene_, *material, hit);
    if (in.unlit) {
      // KHR_materials_unlit: the base colour is what the surface shows, from every
      // direction; it reflects nothing (as Blender imports it, an emitter of its colour).
      aov.record(out, depth, in.params.base.base_color, beta, hit.ng, hit.t, false);
      out.L += beta * in.params.base.base_color;
      break;
    }
    // A shading normal facing away from the viewer (interpolation or normal maps at
    // silhouettes) would make the BRDF zero; tilt it just enough towards wo.
    const float ndotv = glm::dot(in.ns, wo);
    if (ndotv < 1e-4f) in.ns = glm::normalize(in.ns + (1e-4f - ndotv) * wo);
    aov.record(out, depth, in.params.base.base_color, beta, in.ns, hit.t,
               near_specular_for_aovs(in));
    if (depth >= settings_.max_bounces) break;

    // The local frame: +X along the anisotropy direction when there is one.
    const Frame frame = in.tangent != glm::vec3(0.0f)
                            ? Frame(in.tangent, glm::cross(in.ns, in.tangent), in.ns)
                            : Frame(in.ns);
    in.params.coat.normal = frame.to_local(in.coat_normal);
    const std::uint32_t block = kFirstBounceBlock + std::uint32_t(depth) * kBlocksPerBounce;
    const glm::vec4 u_nee = sampler.sample_block(index, block);
    const glm::vec4 u_bsdf = sampler.sample_block(index, block + 1);

    // Transmission: the media on both sides of the surface (MODEL.md, "Volumes and the
    // medium stack"). A volume is behind the surface when the material has a
    // non-zero thickness and the mesh is closed; otherwise the surface is a thin wall.
    const bool transmits =
        in.params.transmission.weight > 0.0f || in.params.diffuse_transmission.weight > 0.0f;
    bool volume = false;
    float n_material = 1.0f;
    glm::vec3 sigma_near(0.0f), sigma_far(0.0f);
    if (transmits) [[unlikely]]
      volume = resolve_transmission(in, *material, hit, front_face, media, channel, beta, u_bsdf.w,
                                    n_material, sigma_near, sigma_far);
    const Bsdf bsdf(in.params, settings_.brdf);
    const BoundBsdf brdf = bsdf.at(frame.to_local(wo));
    // Path guiding (guiding.h): every vertex without a delta lobe records what it receives;
    // a diffuse or rough one whose region has learned something also samples from it.
    // The region's BSDF share of the mixture (guiding.h) may turn its guide off; the vertex
    // still records for the share's next choice.
    const DirectionalQuadtree* guide = nullptr;    // sampled from
    const DirectionalQuadtree* learned = nullptr;  // the region's, for the share's records
    float bsdf_fraction = 1.0f;
    std::uint32_t region = 0;
    const bool recorded = guide_ && !bsdf.has_delta_lobe();
    if (recorded) {
      region = guide_->region_at(hit.p);
      if (guided_vertex(in.params, bsdf) && guide_->distribution(region).total() > 0.0f) {
        learned = &guide_->distribution(region);
        bsdf_fraction = guide_->bsdf_fraction(region);
        if (bsdf_fraction < 1.0f) guide = learned;
      }
    }

    // Direct lighting: one light sample, weighted against BSDF sampling.
    if (transmits) [[unlikely]]
      out.L += sample_ld_transmissive(hit, frame, brdf, u_nee, beta, rays, sigma_near, sigma_far,
                                      guide, bsdf_fraction);
    else
      out.L += sample_ld<false>(hit, frame, brdf, u_nee, beta, rays, sigma_near, sigma_far, guide,
                                bsdf_fraction);

    // Continue the path by sampling the BSDF (visible-normal GGX, cosine, the dielectric),
    // or at a guided vertex the mixture of the BSDF and the guide.
    float guided_boost = 1.0f, p_bsdf = 0.0f, p_guide = 0.0f;
    const BrdfSample bs =
        guide ? sample_guided(brdf, frame, *guide, bsdf_fraction, u_nee.w,
                              glm::vec2(u_bsdf.x, u_bsdf.y), guided_boost, p_bsdf, p_guide)
              : brdf.sample(u_nee.w, glm::vec2(u_bsdf.x, u_bsdf.y));
    if (!bs.valid) break;
    const glm::vec3 wi = frame.to_world(bs.wi);
    if (learned && !guide && !bs.delta) {
      p_bsdf = bs.pdf;
      p_guide = learned->pdf(wi);
    }
    // The shading frame's side must agree with the geometric one: a direction on the other
    // side of the triangle than its lobe meant would leak light.
    const bool transmitted = bs.wi.z < 0.0f;
    if (transmitted ? !(glm::dot(wi, hit.ng) < 0.0f) : !(glm::dot(wi, hit.ng) > 0.0f)) break;
    beta *= bs.weight;
    if (transmitted && volume) {
      if (front_face)
        media.push({hit.geom, n_material, sigma_far});
      else
        media.remove(hit.geom);
    }
    // Russian roulette (pbrt-v4): survive with probability max(beta), at most 1. After
    // guided bounces, with the throughput BSDF sampling alone would have given the same
    // vertices (beta times the product of p_mixture / p_bsdf): a guided bounce towards
    // bright light has a small f cos / p, and roulette on that would end most of the paths
    // the guide sent where the light is and multiply the survivors (the variance guiding
    // removed, back as fireflies; Vorba & Krivanek 2016, "Adjoint-Driven Russian Roulette
    // and Splitting", make the same point for roulette against a learned radiance).
    // Only raised: a guided bounce into light the guide thinks dim keeps the plain
    // throughput's roulette (lowering its survival made fireflies where the guide is wrong).
    rr_boost = std::min(rr_boost * std::max(guided_boost, 1.0f), 1e6f);
    if (depth + 1 >= settings_.rr_start) {
      const float q = rr_boost * std::max(beta.x, std::max(beta.y, beta.z));
      if (!(q > 0.0f) || (q < 1.0f && u_bsdf.z >= q)) break;
      if (q < 1.0f) beta /= q;
    }
    // Should the next ray escape, the environment texels it reads are fetched while it is
    // traced.
    if (env) {
      env_at = env->locate(wi);
      env->prefetch(env_at);
    }
    if (recorded && !bs.delta && guide_count < kMaxGuideVertices)
      guide_vertices[guide_count++] = {
          out.L, beta, wi, bs.pdf, region, bs.weight * bs.pdf, p_bsdf, p_guide, learned != nullptr};
    prev_pdf = bs.pdf;  // infinite after a delta lobe: MIS gives it all the weight
    // A bounce is specular for the cone when its lobe is narrower than a pixel's cone (the
    // sampled direction's solid angle 1 / pdf below pi spread^2): smooth glass's delta lobe,
    // a mirror-smooth metal's. A wider lobe blurs over more than a pixel by itself.
    const float spread = pixel_cone_.spread;
    if (!(std::isinf(bs.pdf) || kPi * spread * spread * bs.pdf >= 1.0f)) cone = -1.0f;
    prev_p = hit.p;
    prev_n = hit.ng;
    origin = offset_ray_origin(hit.p, transmitted ? -hit.ng : hit.ng);
    direction = wi;
  }
  // A non-finite contribution would poison the pixel's mean (and a NaN every later sum):
  // it is dropped, and flagged so that the render counts and reports it rather than
  // showing it only as darkening.
  if (!std::isfinite(out.L.x + out.L.y + out.L.z)) [[unlikely]] {
    out.L = glm::vec3(0.0f);
    out.non_finite = true;
  } else if (guide_count > 0) {
    record_path(guide_vertices, guide_count, out.L);
  }
  out.medium_overflow = media.overflowed;
  return out;
}

// Next-event estimation (pbrt-v4's SampleLd): a light picked by the light sampler from the
// point and its normal (lights.h) and a point or direction on it, the BRDF for that
// direction and a shadow ray. Area lights and the environment are weighted against the
// BSDF sampling that could have found them (power heuristic); delta lights, which only this
// strategy reaches, have weight 1. Returns the contribution to the path's radiance,
// beta f Li tr w / pdf.
[[gnu::noinline]] glm::vec3 Integrator::sample_ld_transmissive(
    const SurfaceHit& hit, const Frame& frame, const BoundBsdf& brdf, glm::vec4 u_nee,
    glm::vec3 beta, std::uint64_t& rays, glm::vec3 sigma_near, glm::vec3 sigma_far,
    const DirectionalQuadtree* guide, float bsdf_fraction) const {
  return sample_ld<true>(hit, frame, brdf, u_nee, beta, rays, sigma_near, sigma_far, guide,
                         bsdf_fraction);
}

BrdfSample Integrator::sample_guided(const BoundBsdf& brdf, const Frame& frame,
                                     const DirectionalQuadtree& guide, float a, float u_choice,
                                     glm::vec2 u, float& boost, float& p_bsdf,
                                     float& p_guide) const {
  // One-sample MIS (Veach 1997, section 9.2.4) with the balance heuristic: whichever
  // strategy drew the direction, its weight is f cos / (a p_bsdf + (1 - a) p_guide), the
  // mixture's pdf (Mueller et al. 2017 mix the two so, with a = 0.5; here a is learned per
  // region, guiding.h). The choice reuses the BSDF's lobe number, rescaled to [0, 1) for the
  // BSDF when it is chosen.
  if (u_choice < a) {
    BrdfSample s = brdf.sample(std::min(u_choice / a, 0x1.fffffep-1f), u);
    if (!s.valid || s.delta) return s;
    p_bsdf = s.pdf;
    p_guide = guide.pdf(frame.to_world(s.wi));
    const float p = a * s.pdf + (1.0f - a) * p_guide;
    boost = p / s.pdf;
    s.weight *= s.pdf / p;
    s.pdf = p;
    return s;
  }
  BrdfSample s;
  s.wi = frame.to_local(guide.sample(u, p_guide));
  const glm::vec3 f = brdf.eval(s.wi, &p_bsdf);
  const float p = a * p_bsdf + (1.0f - a) * p_guide;
  if (!(p > 0.0f) || f == glm::vec3(0.0f)) return s;
  // Where BSDF sampling could not have drawn it, roulette takes the path as it is.
  boost = p_bsdf > 0.0f ? p / p_bsdf : 1.0f;
  s.weight = f * (std::abs(s.wi.z) / p);
  s.pdf = p;
  s.valid = true;
  return s;
}

void Integrator::record_path(const GuideVertex* vertices, int count, glm::vec3 L) const {
  // The radiance arriving at vertex i along its continuation is what the path gathered
  // after it divided by the throughput up to it (the product of f cos / pdf and Russian
  // roulette's 1 / q on the way), per channel; the guide learns its mean over the channels,
  // divided by the direction's pdf (Mueller et al. 2017 record L_i / p).
  for (int i = 0; i < count; ++i) {
    const GuideVertex& v = vertices[i];
    const glm::vec3 after = L - v.L_before;
    float sum = 0.0f;
    int channels = 0;
    for (int c = 0; c < 3; ++c)
      if (v.beta[c] > 0.0f) {
        sum += std::max(after[c], 0.0f) / v.beta[c];
        ++channels;
      }
    if (channels > 0 && v.pdf > 0.0f) guide_->record(v.region, v.wi, sum / float(channels) / v.pdf);
    // The BSDF share's record: the integrand F = f cos L along the direction, L the
    // radiance found after the vertex (the same over-the-throughput estimate), mean over
    // the channels.
    if (v.fraction && channels > 0) {
      float F = 0.0f;
      for (int c = 0; c < 3; ++c)
        if (v.beta[c] > 0.0f) F += v.f_cos[c] * (std::max(after[c], 0.0f) / v.beta[c]);
      guide_->record_fraction(v.region, F / float(channels), v.p_bsdf, v.p_guide, v.pdf);
    }
  }
}

[[gnu::noinline]] bool Integrator::resolve_transmission(ShadingInputs& in, const Material& material,
                                                        const SurfaceHit& hit, bool front_face,
                                                        const MediumStack& media, int& channel,
                                                        glm::vec3& beta, float u_channel,
                                                        float& n_material, glm::vec3& sigma_near,
                                                        glm::vec3& sigma_far) const {
  TransmissionLayer& tl = in.params.transmission;
  const bool volume =
      !tl.thin_walled && material.volume && geometry_.meshes()[hit.geom].mesh->closed;
  tl.thin_walled = !volume;
  n_material = material.ior;
  sigma_near = sigma_far = media.sigma_a();
  if (volume && tl.weight > 0.0f && material.dispersion && material.dispersion->dispersion > 0.0f) {
    // KHR_materials_dispersion: the path takes one channel's wavelength from here on
    // (core/dispersion.h); paths that never meet dispersion pay nothing, nor do those
    // through a diffuse transmitter only (nothing refracts there).
    if (channel < 0) {
      const ChannelSample cs = sample_channel(u_channel);
      channel = cs.channel;
      beta *= cs.weight;
    }
    n_material = dispersion_iors(material.ior, material.dispersion->dispersion)[channel];
  }
  if (!volume) {
    tl.eta = n_material / media.ior();
  } else if (front_face) {
    tl.eta = n_material / media.ior();
    sigma_far = volume_absorption(material.volume->attenuation_color,
                                  material.volume->attenuation_distance);
  } else {
    const MediumStack::Entry* beyond = media.outside_of(hit.geom);
    // The near side is the innermost medium, which is not this volume where another was
    // entered inside it (overlapping volumes: a liquid reaching into its glass's wall).
    tl.eta = (beyond ? beyond->ior : 1.0f) / media.ior();
    sigma_far = beyond ? beyond->sigma_a : glm::vec3(0.0f);
  }
  return volume;
}

// Through a transmissive surface the light may be on either side; a refractive (delta)
// interface has no lobe a light sample can meet, and a shadow ray through glass is blocked
// by it: light through glass arrives by BSDF sampling only (caustics; MODEL.md).
template <bool kTransmits>
inline glm::vec3 Integrator::sample_ld(const SurfaceHit& hit, const Frame& frame,
                                       const BoundBsdf& brdf, glm::vec4 u_nee, glm::vec3 beta,
                                       std::uint64_t& rays, glm::vec3 sigma_near,
                                       glm::vec3 sigma_far, const DirectionalQuadtree* guide,
                                       float bsdf_fraction) const {
  LightSample ls;
  // (The light choice needs no random number when there is a single light.)
  const float u_light = lights_.size() > 1 ? u_nee.x : 0.5f;
  if (!lights_.sample(hit.p, hit.ng, u_light, glm::vec2(u_nee.y, u_nee.z), ls))
    return glm::vec3(0.0f);
  // Area lights and the environment are left to BSDF sampling when it is asked for alone.
  const LightStrategy strategy = settings_.strategy;
  if (!ls.delta && strategy == LightStrategy::kBsdfOnly) return glm::vec3(0.0f);
  if (ls.Li == glm::vec3(0.0f)) return glm::vec3(0.0f);
  const bool above = glm::dot(ls.wi, hit.ng) > 0.0f;
  if (!above && !kTransmits) return glm::vec3(0.0f);
  const glm::vec3 wi_local = frame.to_local(ls.wi);
  const bool mis = !ls.delta && strategy == LightStrategy::kMis;
  float bsdf_pdf = 0.0f;
  const float cos_i = kTransmits ? std::abs(wi_local.z) : std::max(wi_local.z, 0.0f);
  const glm::vec3 f = brdf.eval(wi_local, mis ? &bsdf_pdf : nullptr) * cos_i;
  if (f == glm::vec3(0.0f)) return glm::vec3(0.0f);
  // At a guided vertex the other strategy is the mixture of the BSDF and the guide.
  if (mis && guide)
    bsdf_pdf = bsdf_fraction * bsdf_pdf + (1.0f - bsdf_fraction) * guide->pdf(ls.wi);
  float w = 1.0f;
  if (mis) w = power_heuristic(ls.pdf, bsdf_pdf);
  glm::vec3 tr = transmittance<kTransmits>(hit, ls, above ? hit.ng : -hit.ng, rays);
  if constexpr (kTransmits) {
    const glm::vec3 sigma = above ? sigma_near : sigma_far;
    if (sigma != glm::vec3(0.0f))
      tr *= absorb(sigma, ls.infinite ? std::numeric_limits<float>::infinity()
                                      : glm::length(ls.light_point - hit.p));
  }
  return beta * f * ls.Li * tr * (w / ls.pdf);
}

// Closest hit, skipping culled back faces, alpha-masked and stochastically transparent
// surfaces (glTF alphaMode MASK: alpha < cutoff is a hole; BLEND: transparent with
// probability 1 - alpha, an unbiased stand-in for blending).
// `first`, when given, is the intersection of the first pass (from a packet).
inline bool Integrator::closest_hit(glm::vec3& origin, glm::vec3 direction, std::uint32_t pixel,
                                    std::uint32_t index, int depth, std::uint64_t& rays,
                                    SurfaceHit& hit, const Material*& material,
                                    const SceneGeometry::PacketHit* first, float time) const {
  for (std::uint32_t pass = 0; pass < 256; ++pass) {
    std::uint32_t geom = 0, prim = 0;
    float t = 0.0f, u = 0.0f, v = 0.0f;
    ++rays;
    if (pass == 0 && first) {
      if (first->geom == SceneGeometry::kNoHit) return false;
      geom = first->geom;
      prim = first->prim;
      t = first->t;
      u = first->u;
      v = first->v;
    } else if (!geometry_.intersect(origin, direction, kInfinity, 0xffffffffu, geom, prim, t, u, v,
                                    time)) {
      return false;
    }
    hit = geometry_.resolve(geom, prim, t, u, v, time);
    const WorldMesh& wm = geometry_.meshes()[geom];
    material = wm.material;
    // Back faces of single-sided materials are culled (glTF), except where light goes
    // through the surface: a glass's inside is seen through its back faces.
    bool skip = !material->double_sided && glm::dot(hit.ng, direction) > 0.0f &&
                !material->transmission && !material->diffuse_transmission;
    if (!skip && wm.has_alpha) {
      const float alpha = material_alpha(scene_, *material, hit);
      if (material->alpha_mode == AlphaMode::kMask)
        skip = alpha < material->alpha_cutoff;
      else
        skip = hash_float(pixel, index, std::uint32_t(depth), pass) >= alpha;
    }
    if (!skip) return true;
    origin = offset_ray_origin(hit.p, glm::dot(hit.ng, direction) > 0.0f ? hit.ng : -hit.ng);
  }
  return false;
}

// Visibility of a light sample: 0 or 1 through opaque geometry; through alpha-tested
// and blended surfaces the expected transmittance (MASK: 0 or 1, BLEND: 1 - alpha).
template <bool kTransmits>
inline glm::vec3 Integrator::transmittance(const SurfaceHit& hit, const LightSample& ls,
                                           glm::vec3 n_side, std::uint64_t& rays) const {
  const glm::vec3 o = offset_ray_origin(hit.p, n_side);
  float tfar;
  if (ls.infinite) {
    tfar = kInfinity;
  } else {
    // Stop just short of the light point (offset towards us for area lights).
    const glm::vec3 target =
        ls.delta ? ls.light_point : offset_ray_origin(ls.light_point, ls.light_normal);
    tfar = glm::length(target - o) * (1.0f - 1e-4f);
  }
  ++rays;
  if (geometry_.occluded(o, ls.wi, tfar, hit.time)) return glm::vec3(0.0f);
  if (!geometry_.has_alpha()) return glm::vec3(1.0f);
  float tr = 1.0f;
  glm::vec3 origin = o;
  float remaining = tfar;
  for (int pass = 0; pass < 256 && tr > 0.0f; ++pass) {
    std::uint32_t geom = 0, prim = 0;
    float t = 0.0f, u = 0.0f, v = 0.0f;
    ++rays;
    if (!geometry_.intersect(origin, ls.wi, remaining, kMaskAlpha, geom, prim, t, u, v, hit.time))
      break;
    const SurfaceHit h = geometry_.resolve(geom, prim, t, u, v, hit.time);
    const Material& m = *geometry_.meshes()[geom].material;
    const float alpha = material_alpha(scene_, m, h);
    if (m.alpha_mode == AlphaMode::kMask)
      tr *= alpha < m.alpha_cutoff ? 1.0f : 0.0f;
    else
      tr *= 1.0f - saturate(alpha);
    const glm::vec3 next = offset_ray_origin(h.p, glm::dot(h.ng, ls.wi) > 0.0f ? h.ng : -h.ng);
    if (std::isfinite(remaining)) remaining -= glm::length(next - origin);
    origin = next;
    if (!(remaining > 0.0f)) break;
  }
  return glm::vec3(tr);
}

}  // namespace pbrkit
