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
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/lights.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

// Sampler dimensions, drawn as 4D Sobol blocks: block 0 the pixel filter (dims 0-1, drawn
// by the render loop), then two blocks per bounce: (light choice, light point (2), BSDF
// lobe) and (BSDF direction (2), Russian roulette, spare).
inline constexpr std::uint32_t kPixelFilterBlock = 0;
inline constexpr std::uint32_t kFirstBounceBlock = 1;
inline constexpr std::uint32_t kBlocksPerBounce = 2;

/// What one camera path brings back: radiance and the first hit's AOVs.
struct PathSample {
  glm::vec3 L{0.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
  float depth = 0.0f;
};

class Integrator {
 public:
  Integrator(const Scene& scene, const SceneGeometry& geometry, const LightSet& lights,
             const PathTracerSettings& settings)
      : scene_(scene), geometry_(geometry), lights_(lights), settings_(settings) {}

  /// The radiance arriving along the camera ray (origin, direction) for sample `index` of
  /// pixel `pixel`, whose sequence is `sampler`; `primary` is the ray's intersection,
  /// found with its packet. `rays` counts the rays traced.
  PathSample Li(glm::vec3 origin, glm::vec3 direction, const SceneGeometry::PacketHit& primary,
                OwenSobolPixel& sampler, std::uint32_t pixel, std::uint32_t index,
                std::uint64_t& rays) const;

 private:
  glm::vec3 sample_ld(const SurfaceHit& hit, const Frame& frame, const BoundBsdf& brdf,
                      glm::vec4 u_nee, glm::vec3 beta, std::uint64_t& rays) const;
  bool closest_hit(glm::vec3& origin, glm::vec3 direction, std::uint32_t pixel, std::uint32_t index,
                   int depth, std::uint64_t& rays, SurfaceHit& hit, const Material*& material,
                   const SceneGeometry::PacketHit* first = nullptr) const;
  glm::vec3 transmittance(const SurfaceHit& hit, const LightSample& ls, std::uint64_t& rays) const;

  const Scene& scene_;
  const SceneGeometry& geometry_;
  const LightSet& lights_;
  const PathTracerSettings& settings_;
};

}  // namespace pbrkit
