#pragma once
// The path tracer's integrator: the radiance carried by one camera path (Veach's path
// tracer with next-event estimation and multiple importance sampling, in pbrt-v4's
// PathIntegrator form). Private to the path tracer; render_path (path_tracer.cpp) owns
// the film, the schedule and the stopping rules and calls Li once per camera sample.
#include <cstdint>

#include <glm/glm.hpp>

#include "pbrkit/core/bsdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/camera_rays.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/guiding.h"
#include "pbrkit/pt/lights.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/pt/shading.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

// Sampler dimensions, drawn as 4D Sobol blocks: block 0 the pixel filter (dims 0-1, drawn
// by the render loop), then two blocks per bounce: (light choice, light point (2), BSDF
// lobe) and (BSDF direction (2), Russian roulette, spare).
inline constexpr std::uint32_t kPixelFilterBlock = 0;
inline constexpr std::uint32_t kFirstBounceBlock = 1;
inline constexpr std::uint32_t kBlocksPerBounce = 2;

/// The media a path is inside (KHR_materials_volume), innermost last. A closed mesh whose
/// material has a volume is entered when a path is transmitted through a front face
/// (geometric normal, from the winding) and left through a back face; the entry is found
/// by instance, so nested and touching volumes are left in any order. Overlapping volumes
/// are not mixed: the innermost (most recently entered) one is the medium. The camera is
/// in vacuum (ior 1, no absorption).
struct MediumStack {
  struct Entry {
    std::uint32_t geom;  ///< the instance that bounds it
    float ior;           ///< its ior (at the path's wavelength under dispersion)
    glm::vec3 sigma_a;   ///< Beer-Lambert absorption coefficient (core/transmission.h)
  };
  /// Deeper nesting is not tracked: an entry past it is dropped (the path then takes the
  /// enclosing medium's ior and absorption inside it) and `overflowed` records it, so that
  /// the render counts and reports such paths (path_tracer.h, PathTracerStats).
  static constexpr int kCapacity = kMaxNestedVolumes;
  // Left uninitialised: every path starts one, and only `size` entries are ever read
  // (initialising all 8 cost 1% of the instructions of an opaque scene's path).
  Entry entries[kCapacity];
  int size = 0;
  bool overflowed = false;

  float ior() const { return size > 0 ? entries[size - 1].ior : 1.0f; }
  glm::vec3 sigma_a() const { return size > 0 ? entries[size - 1].sigma_a : glm::vec3(0.0f); }
  /// The innermost entry other than `geom`'s (the medium on the other side of `geom`'s
  /// boundary when the path leaves it).
  const Entry* outside_of(std::uint32_t geom) const {
    bool skipped = false;
    for (int k = size - 1; k >= 0; --k) {
      if (!skipped && entries[k].geom == geom) {
        skipped = true;
        continue;
      }
      return &entries[k];
    }
    return nullptr;
  }
  // (Out of line: Li, which calls them, keeps its inlining budget for opaque surfaces.)
  [[gnu::noinline]] void push(const Entry& e) {
    if (size < kCapacity)
      entries[size++] = e;
    else
      overflowed = true;
  }
  [[gnu::noinline]] void remove(std::uint32_t geom) {
    for (int k = size - 1; k >= 0; --k)
      if (entries[k].geom == geom) {
        for (int j = k; j + 1 < size; ++j) entries[j] = entries[j + 1];
        --size;
        return;
      }
  }
};

/// What one camera path brings back: radiance and the first hit's AOVs, and what the path
/// could not represent (counted per render and reported: path_tracer.h, PathTracerStats).
struct PathSample {
  glm::vec3 L{0.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
  float depth = 0.0f;
  /// The radiance came out NaN or infinite (an integrator or material bug, or a degenerate
  /// input the code does not guard): L was set to 0 so the pixel stays usable.
  bool non_finite = false;
  /// The path entered more nested volumes than MediumStack::kCapacity.
  bool medium_overflow = false;
};

/// Whether a vertex is guided (PathTracerSettings::guiding): where the guide can find what
/// BSDF sampling misses, diffuse and rough surfaces. A narrow lobe (smooth metal, smooth
/// glass) is sampled better by itself than by a guide of a few degrees' resolution, and a
/// delta lobe cannot be guided at all. A smooth dielectric over a diffuse base is guided for
/// its diffuse part (its specular lobe then gets half the samples it had). Transmissive
/// dielectrics are not guided, rough ones included: a path inside rough glass reflects
/// internally many times, along directions the guide (learned over the region from both
/// sides of the surface, mostly of light leaving it) thinks dark, and each such bounce
/// drawn from the mixture has twice BSDF sampling's weight, f cos / (a p_bsdf) with
/// a = 0.5: 2^10 after ten internal bounces. On `glass` that made fireflies that put the
/// guided relative MSE far above the unguided one (BENCHMARKS.md, "Path guiding").
inline bool guided_vertex(const SurfaceParams& p, const Bsdf& bsdf) {
  if (bsdf.has_delta_lobe() || p.transmission.weight > 0.0f) return false;
  return p.base.roughness >= 0.3f || p.base.metallic < 0.5f;
}

class Integrator {
 public:
  /// `pixel_cone`: a camera ray's cone (texture level of detail, settings.texture_lod).
  /// `guide`: the path guide to sample from and record into (nullptr: no guiding).
  Integrator(const Scene& scene, const SceneGeometry& geometry, const LightSet& lights,
             const PathTracerSettings& settings, RayCone pixel_cone = {},
             PathGuide* guide = nullptr)
      : scene_(scene),
        geometry_(geometry),
        lights_(lights),
        settings_(settings),
        pixel_cone_(pixel_cone),
        guide_(guide) {}

  /// The radiance arriving along the camera ray (origin, direction) for sample `index` of
  /// pixel `pixel`, whose sequence is `sampler`; `primary` is the ray's intersection,
  /// found with its packet. `rays` counts the rays traced. `time`: the path's time across
  /// the shutter, [0, 1] (motion blur: every ray of the path sees the scene then).
  PathSample Li(glm::vec3 origin, glm::vec3 direction, const SceneGeometry::PacketHit& primary,
                OwenSobolPixel& sampler, std::uint32_t pixel, std::uint32_t index,
                std::uint64_t& rays, float time = 0.0f) const;

 private:
  /// kTransmits: the BSDF has lobes below the surface, so light samples on the far side
  /// count; `sigma_near` / `sigma_far`: the absorption of the media on the viewer's side
  /// and on the far side, applied along the shadow ray. (A template, so that opaque
  /// surfaces run the code they ran before transmission existed.)
  template <bool kTransmits>
  glm::vec3 sample_ld(const SurfaceHit& hit, const Frame& frame, const BoundBsdf& brdf,
                      glm::vec4 u_nee, glm::vec3 beta, std::uint64_t& rays, glm::vec3 sigma_near,
                      glm::vec3 sigma_far, const DirectionalQuadtree* guide,
                      float bsdf_fraction) const;
  /// sample_ld<true>, out of line: Li stays the size it was for opaque surfaces (its
  /// inlining budget otherwise moved other helpers out of line).
  glm::vec3 sample_ld_transmissive(const SurfaceHit& hit, const Frame& frame, const BoundBsdf& brdf,
                                   glm::vec4 u_nee, glm::vec3 beta, std::uint64_t& rays,
                                   glm::vec3 sigma_near, glm::vec3 sigma_far,
                                   const DirectionalQuadtree* guide, float bsdf_fraction) const;
  /// One direction at a guided vertex: from the BSDF (with probability `a`, the region's
  /// PathGuide::bsdf_fraction) or from the guide, weighted f cos / pdf by the mixture's pdf
  /// (one-sample MIS, the balance heuristic); `pdf` the mixture's, what MIS with light
  /// sampling needs. `boost`: p_mixture / p_bsdf for the direction drawn, which Russian
  /// roulette undoes; `p_bsdf`, `p_guide`: the two pdfs of the direction.
  BrdfSample sample_guided(const BoundBsdf& brdf, const Frame& frame,
                           const DirectionalQuadtree& guide, float a, float u_choice, glm::vec2 u,
                           float& boost, float& p_bsdf, float& p_guide) const;
  /// A recorded vertex: where it was, the direction it continued in and that direction's
  /// pdf, the throughput after it and the path's radiance before it; at a vertex whose
  /// region has learned a guide, also f cos of the direction and its BSDF and guide pdfs
  /// (the BSDF share's choice, PathGuide::record_fraction).
  struct GuideVertex {
    glm::vec3 L_before, beta, wi;
    float pdf;
    std::uint32_t region;
    glm::vec3 f_cos{0.0f};
    float p_bsdf = 0.0f, p_guide = 0.0f;
    bool fraction = false;
  };
  static constexpr int kMaxGuideVertices = 32;
  /// Records what each vertex of a finished path received along its continuation: the
  /// radiance the path gathered after it over the throughput up to it.
  void record_path(const GuideVertex* vertices, int count, glm::vec3 L) const;
  /// Resolves a transmissive surface's media (the medium stack, dispersion's channel) and
  /// sets in.params.transmission's eta and thin_walled; returns whether a volume is behind
  /// the surface. Out of line: opaque paths never call it.
  bool resolve_transmission(ShadingInputs& in, const Material& material, const SurfaceHit& hit,
                            bool front_face, const MediumStack& media, int& channel,
                            glm::vec3& beta, float u_channel, float& n_material,
                            glm::vec3& sigma_near, glm::vec3& sigma_far) const;
  bool closest_hit(glm::vec3& origin, glm::vec3 direction, std::uint32_t pixel, std::uint32_t index,
                   int depth, std::uint64_t& rays, SurfaceHit& hit, const Material*& material,
                   const SceneGeometry::PacketHit* first, float time) const;
  // (A template like sample_ld: each instantiation has one caller, so the opaque one is
  // inlined into Li as before.)
  template <bool kTransmits>
  glm::vec3 transmittance(const SurfaceHit& hit, const LightSample& ls, glm::vec3 n_side,
                          std::uint64_t& rays) const;

  const Scene& scene_;
  const SceneGeometry& geometry_;
  const LightSet& lights_;
  const PathTracerSettings& settings_;
  RayCone pixel_cone_;
  PathGuide* guide_;
};

}  // namespace pbrkit
