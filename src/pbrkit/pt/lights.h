#pragma once
// Every light the path tracer samples: the environment, KHR_lights_punctual lights and
// emissive triangles, in one list from which a light is picked with probability
// proportional to its emitted power (pbrt-v4's PowerLightSampler), then sampled.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/environment.h"
#include "pbrkit/pt/environment_sampler.h"
#include "pbrkit/pt/geometry.h"
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
  LightSet(const Scene& scene, const SceneGeometry& geometry, const Environment* env);

  bool empty() const { return entries_.empty(); }
  /// Picks a light with u_select and samples a direction towards it from `p`.
  bool sample(glm::vec3 p, float u_select, glm::vec2 u, LightSample& out) const;
  /// Selection x solid-angle pdf with which sample() would have produced direction `d`
  /// towards the environment.
  float environment_pdf(glm::vec3 d) const;
  /// The environment's lookups (null without an environment) and the probability with
  /// which sample() picks it: environment_pdf(d) = environment_probability() x
  /// environment_sampler()->pdf(d).
  const EnvironmentSampler* environment_sampler() const { return env_sampler_.get(); }
  float environment_probability() const {
    return env_entry_ < 0 ? 0.0f : select_.probability(std::size_t(env_entry_));
  }
  /// Same for a hit on an emissive triangle, seen from `from` (hit.p on the light).
  float triangle_pdf(const SurfaceHit& hit, glm::vec3 from) const;

  const Environment* environment() const { return env_; }
  std::size_t size() const { return entries_.size(); }

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
  std::vector<Entry> entries_;
  Distribution1D select_;
  float single_p_select_ = 0.0f;  ///< with one light: its selection probability
  int env_entry_ = -1;
  std::vector<int> first_light_;  ///< per instance: its first triangle entry, or -1
};

}  // namespace pbrkit
