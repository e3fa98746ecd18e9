#include "pbrkit/pt/lights.h"

#include <cmath>
#include <limits>

#include "pbrkit/core/color.h"
#include "pbrkit/core/math.h"
#include "pbrkit/pt/shading.h"

namespace pbrkit {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// KHR_lights_punctual's recommended range window: clamp(1 - (d / range)^4, 0, 1).
float range_window(const Light& l, float d) {
  if (!l.range || *l.range <= 0.0f) return 1.0f;
  const float x = d / *l.range;
  return saturate(1.0f - x * x * x * x);
}

// KHR_lights_punctual spot cone: smooth between the outer and inner cone (squared
// linear ramp, as in the Khronos sample viewer).
float spot_factor(const Light& l, glm::vec3 to_point) {
  const float cos_outer = std::cos(l.outer_cone_angle), cos_inner = std::cos(l.inner_cone_angle);
  const float cd = glm::dot(glm::normalize(l.direction), to_point);
  if (cd <= cos_outer) return 0.0f;
  if (cd >= cos_inner || cos_inner <= cos_outer) return 1.0f;
  const float t = (cd - cos_outer) / (cos_inner - cos_outer);
  return t * t;
}

}  // namespace

LightSet::LightSet(const Scene& scene, const SceneGeometry& geometry, const Environment* env)
    : scene_(scene), geometry_(geometry), env_(env) {
  // Power of each light (pbrt-v4 Light::Phi), used only to choose which light to sample.
  std::vector<float> power;
  const Bounds& b = geometry.bounds();
  const float radius = b.empty() ? 1.0f : std::max(0.5f * glm::length(b.extent()), 1e-3f);
  if (env) {
    env_sampler_ = std::make_unique<EnvironmentSampler>(*env);
    const float phi = 4.0f * kPi * kPi * radius * radius * env_sampler_->mean_luminance();
    if (phi > 0.0f) {
      env_entry_ = int(entries_.size());
      entries_.push_back({Kind::kEnvironment, 0});
      power.push_back(phi);
    }
  }
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const float I = l.intensity * luminance(l.color);
    if (!(I > 0.0f) || !std::isfinite(I)) continue;
    float phi = 0.0f;
    switch (l.type) {
      case Light::Type::kPoint:
        phi = 4.0f * kPi * I;
        break;
      case Light::Type::kSpot:
        phi = 2.0f * kPi * I *
              (1.0f - 0.5f * (std::cos(l.inner_cone_angle) + std::cos(l.outer_cone_angle)));
        break;
      case Light::Type::kDirectional:
        phi = kPi * radius * radius * I;
        break;
    }
    entries_.push_back({Kind::kPunctual, std::uint32_t(i)});
    power.push_back(phi);
  }
  // Emissive triangles, by power pi x area x luminance(emission factor); the emissive
  // texture's variation is not in the selection weights (it stays unbiased). Each instance
  // of an emissive mesh is its own light, its triangles' areas those of its world-space
  // copy (an affine map scales areas by a factor that depends on the triangle's
  // orientation under a non-uniform scale).
  const auto& meshes = geometry.meshes();
  first_light_.assign(meshes.size(), -1);
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    const WorldMesh& wm = meshes[g];
    if (!wm.emissive || !wm.visible) continue;
    const Material& m = *wm.material;
    const float le = luminance(m.emissive_factor * m.emissive_strength);
    first_light_[g] = int(entries_.size());
    const std::size_t n = wm.mesh->triangle_count();
    for (std::size_t t = 0; t < n; ++t) {
      const float area = geometry.triangle_area(std::uint32_t(g), std::uint32_t(t));
      entries_.push_back({Kind::kTriangle, std::uint32_t(g), std::uint32_t(t)});
      power.push_back(kPi * area * le * (m.double_sided ? 2.0f : 1.0f));
    }
  }
  if (!entries_.empty()) select_ = Distribution1D(std::move(power));
  // With a single light the choice is always it, with the probability the distribution
  // gives (computed once; a search per sample otherwise).
  if (entries_.size() == 1) select_.sample_discrete(0.5f, single_p_select_);
}

bool LightSet::sample(glm::vec3 p, float u_select, glm::vec2 u, LightSample& out) const {
  if (entries_.empty()) return false;
  float p_select = single_p_select_;
  const std::size_t i = entries_.size() == 1 ? 0 : select_.sample_discrete(u_select, p_select);
  if (!(p_select > 0.0f)) return false;
  const Entry& e = entries_[i];
  out = LightSample{};
  switch (e.kind) {
    case Kind::kEnvironment: {
      const EnvironmentSampler::Sample s = env_sampler_->sample(u);
      if (!(s.pdf > 0.0f)) return false;
      out.wi = s.direction;
      out.distance = kInfinity;
      out.Li = s.radiance;
      out.pdf = p_select * s.pdf;
      out.infinite = true;
      return true;
    }
    case Kind::kPunctual: {
      const Light& l = scene_.lights[e.index];
      const glm::vec3 I = l.color * l.intensity;
      out.delta = true;
      out.pdf = p_select;
      if (l.type == Light::Type::kDirectional) {
        out.wi = -glm::normalize(l.direction);
        out.distance = kInfinity;
        out.infinite = true;
        out.Li = I;  // illuminance in lux: E = I (n.l) at normal incidence
        return true;
      }
      const glm::vec3 to = l.position - p;
      const float d2 = glm::dot(to, to);
      if (!(d2 > 0.0f)) return false;
      out.distance = std::sqrt(d2);
      out.wi = to / out.distance;
      float f = range_window(l, out.distance) / d2;  // inverse square law
      if (l.type == Light::Type::kSpot) f *= spot_factor(l, -out.wi);
      out.Li = I * f;
      out.light_point = l.position;
      return f > 0.0f;
    }
    case Kind::kTriangle: {
      const WorldMesh& wm = geometry_.meshes()[e.index];
      // Uniform point on the triangle (pbrt-v3 SampleUniformTriangle): b0 = 1 - sqrt(u0).
      // Uniform in object space is uniform in world space: an affine map scales every
      // area of one triangle by the same factor.
      const float su = std::sqrt(u.x);
      const float b1 = u.y * su, b2 = 1.0f - su;
      const SurfaceHit hit = geometry_.resolve(e.index, e.prim, 0.0f, b1, b2);
      const glm::vec3 to = hit.p - p;
      const float d2 = glm::dot(to, to);
      if (!(d2 > 0.0f) || !(hit.area > 0.0f)) return false;
      out.distance = std::sqrt(d2);
      out.wi = to / out.distance;
      const float cos_l = -glm::dot(hit.ng, out.wi);
      if (!wm.material->double_sided && cos_l <= 0.0f) return false;  // emits from the front
      if (cos_l == 0.0f) return false;
      out.Li = material_emission(scene_, *wm.material, hit);
      // Area density 1/A converted to solid angle: d^2 / (|cos| A).
      out.pdf = p_select * d2 / (std::fabs(cos_l) * hit.area);
      out.light_point = hit.p;
      out.light_normal = cos_l > 0.0f ? hit.ng : -hit.ng;
      return true;
    }
  }
  return false;
}

float LightSet::environment_pdf(glm::vec3 d) const {
  if (env_entry_ < 0) return 0.0f;
  return select_.probability(std::size_t(env_entry_)) * env_sampler_->pdf(d);
}

float LightSet::triangle_pdf(const SurfaceHit& hit, glm::vec3 from) const {
  const int first = first_light_[hit.geom];
  if (first < 0) return 0.0f;
  const glm::vec3 to = hit.p - from;
  const float d2 = glm::dot(to, to);
  const float cos_l = std::fabs(glm::dot(hit.ng, to)) / std::sqrt(d2);
  if (!(cos_l > 0.0f) || !(hit.area > 0.0f)) return 0.0f;
  return select_.probability(std::size_t(first) + hit.prim) * d2 / (cos_l * hit.area);
}

}  // namespace pbrkit
