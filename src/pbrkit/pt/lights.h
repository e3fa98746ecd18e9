#pragma once
// Every light the path tracer samples: the environment, KHR_lights_punctual lights and
// emissive triangles, in one list from which one light per shading point is picked, then
// sampled. Two ways to pick (PathTracerSettings::light_sampler):
//  - kPower: with probability proportional to its emitted power (pbrt-v4's
//    PowerLightSampler), the same everywhere;
//  - kBvh: the lights without a position (the environment, directional lights) as one
//    group, chosen with probability phi_infinite / (phi_infinite + phi_bounded) (their
//    share of the power, as kPower gives them, so that scenes lit by the sky and sun lose
//    nothing), and within it by power; otherwise a light of the light BVH (light_bvh.h),
//    by its importance at the shading point and its normal.
// With a single light both pick it with the same probability and the same random numbers.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/environment.h"
#include "pbrkit/pt/environment_sampler.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/light_bvh.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct LightSample {
  glm::vec3 wi{0.0f};           ///< unit direction from the shading point to the light
  float distance = 0.0f;        ///< to the light point (infinity for env / directional)
  glm::vec3 Li{0.0f};           ///< incident radiance (delta lights: irradiance-like value)
  float pdf = 0.0f;             ///< selection x solid-angle pdf (delta: selection only)
  glm::vec3 light_point{0.0f};  ///< for area lights: the sampled point (offset target)
  glm::vec3 light_normal{0.0f};
  bool delta = false;
  bool infinite = false;
};

class LightSet {
 public:
  LightSet(const Scene& scene, const SceneGeometry& geometry, const Environment* env,
           LightSamplerKind kind = LightSamplerKind::kBvh);

  bool empty() const { return entries_.empty(); }
  /// Picks a light with u_select and samples a direction towards it from `p`, a point
  /// whose surface normal is `n` (either orientation; zero: no surface).
  bool sample(glm::vec3 p, glm::vec3 n, float u_select, glm::vec2 u, LightSample& out) const;
  /// Selection x solid-angle pdf with which sample() would have produced direction `d`
  /// towards the environment.
  float environment_pdf(glm::vec3 d) const;
  /// The environment's lookups (null without an environment) and the probability with
  /// which sample() picks it: environment_pdf(d) = environment_probability() x
  /// environment_sampler()->pdf(d).
  const EnvironmentSampler* environment_sampler() const { return env_sampler_.get(); }
  float environment_probability() const { return env_probability_; }
  /// Same for a hit on an emissive triangle, seen from `from`, whose surface normal is
  /// `from_n` (hit.p on the light).
  float triangle_pdf(const SurfaceHit& hit, glm::vec3 from, glm::vec3 from_n) const;

  const Environment* environment() const { return env_; }
  std::size_t size() const { return entries_.size(); }
  /// The sampler in use (kPower whenever there is at most one light: the choice is then
  /// the same, and the power sampler's code makes it).
  LightSamplerKind kind() const { return kind_; }

  /// The probability that sample(p, n, .) picks light `light` (in [0, size())); the lights
  /// are numbered as listed: the environment (if any), then the scene's punctual lights
  /// with a positive intensity in order, then the emissive triangles instance by instance.
  /// For tests.
  float pmf(glm::vec3 p, glm::vec3 n, std::size_t light) const;
  /// The light sample() picked with u_select (its number as in pmf()) and its probability,
  /// or -1. For tests.
  std::int64_t select(glm::vec3 p, glm::vec3 n, float u_select, float& p_select) const;

 private:
  enum class Kind : std::uint8_t { kEnvironment, kPunctual, kTriangle };
  struct Entry {
    Kind kind;
    std::uint32_t index;  ///< punctual: scene light index; triangle: instance (geom)
    std::uint32_t prim = 0;
  };
  const Scene& scene_;
  const SceneGeometry& geometry_;
  const Environment* env_;
  std::unique_ptr<EnvironmentSampler> env_sampler_;
  /// select() for the BVH sampler.
  std::int64_t select_bvh(glm::vec3 p, glm::vec3 n, float u_select, float& p_select) const;

  std::vector<Entry> entries_;
  LightSamplerKind kind_;
  Distribution1D select_;  ///< kPower: over every entry
  // kBvh: the infinite lights (environment, directional) by power, and the others in a BVH
  // indexed by entry.
  std::vector<std::uint32_t> infinite_entries_;
  Distribution1D infinite_select_;
  float p_infinite_ = 0.0f;  ///< the probability of picking the infinite group
  LightBvh bvh_;
  float env_probability_ = 0.0f;
  float single_p_select_ = 0.0f;  ///< with one light: its selection probability
  int env_entry_ = -1;
  std::vector<int> first_light_;  ///< per instance: its first triangle entry, or -1
};

}  // namespace pbrkit
