#include "pbrkit/pt/lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pbrkit/core/color.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/shading.h"
#include "pbrkit/util/error.h"

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

LightSamplerKind parse_light_sampler(std::string_view name) {
  if (name == "bvh") return LightSamplerKind::kBvh;
  if (name == "power") return LightSamplerKind::kPower;
  fail("unknown light sampler '{}' (expected 'bvh' or 'power')", name);
}

std::string_view light_sampler_name(LightSamplerKind kind) {
  return kind == LightSamplerKind::kPower ? "power" : "bvh";
}

LightSet::LightSet(const Scene& scene, const SceneGeometry& geometry, const Environment* env,
                   LightSamplerKind kind)
    : scene_(scene), geometry_(geometry), env_(env), kind_(kind) {
  // Power of each light (pbrt-v4 Light::Phi), used only to choose which light to sample;
  // for the BVH also where each light is and where it emits (LightBounds: zero power for
  // the lights without a position, which are not in the tree).
  std::vector<float> power;
  std::vector<LightBounds> bounds;
  const Bounds& b = geometry.bounds();
  const float radius = b.empty() ? 1.0f : std::max(0.5f * glm::length(b.extent()), 1e-3f);
  if (env) {
    env_sampler_ = std::make_unique<EnvironmentSampler>(*env);
    const float phi = 4.0f * kPi * kPi * radius * radius * env_sampler_->mean_luminance();
    if (phi > 0.0f) {
      env_entry_ = int(entries_.size());
      entries_.push_back({Kind::kEnvironment, 0});
      power.push_back(phi);
      bounds.emplace_back();
    }
  }
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const float I = l.intensity * luminance(l.color);
    if (!(I > 0.0f) || !std::isfinite(I)) continue;
    float phi = 0.0f;
    LightBounds lb;
    lb.lo = lb.hi = l.position;
    switch (l.type) {
      case Light::Type::kPoint:
        phi = 4.0f * kPi * I;
        lb.cos_theta_o = -1.0f;  // every direction
        break;
      case Light::Type::kSpot:
        phi = 2.0f * kPi * I *
              (1.0f - 0.5f * (std::cos(l.inner_cone_angle) + std::cos(l.outer_cone_angle)));
        // Light leaves within the outer cone around the spot axis, nowhere beyond it.
        lb.w = glm::normalize(l.direction);
        lb.cos_theta_o = std::cos(std::max(l.outer_cone_angle, l.inner_cone_angle));
        lb.cos_theta_e = 1.0f;
        break;
      case Light::Type::kDirectional:
        phi = kPi * radius * radius * I;
        break;
    }
    entries_.push_back({Kind::kPunctual, std::uint32_t(i)});
    power.push_back(phi);
    if (l.type != Light::Type::kDirectional) lb.phi = phi;
    bounds.push_back(lb);
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
      const float phi = kPi * area * le * (m.double_sided ? 2.0f : 1.0f);
      power.push_back(phi);
      if (kind == LightSamplerKind::kBvh) {
        // A triangle emits from its front (both sides when double-sided) into the
        // hemisphere around its geometric normal: theta_o = 0, theta_e = pi / 2.
        LightBounds lb;
        const auto corner = [&](float u, float v) {
          return geometry.resolve(std::uint32_t(g), std::uint32_t(t), 0.0f, u, v, kShutterCentre);
        };
        const SurfaceHit h0 = corner(0.0f, 0.0f);
        const glm::vec3 p1 = corner(1.0f, 0.0f).p, p2 = corner(0.0f, 1.0f).p;
        lb.lo = glm::min(h0.p, glm::min(p1, p2));
        lb.hi = glm::max(h0.p, glm::max(p1, p2));
        lb.w = h0.ng;
        lb.cos_theta_o = 1.0f;
        lb.cos_theta_e = 0.0f;
        lb.two_sided = m.double_sided;
        lb.phi = phi;
        bounds.push_back(lb);
      }
    }
  }
  // With at most one light there is no choice to make: the power sampler's code makes it,
  // so that both samplers give the same image.
  if (entries_.size() <= 1) kind_ = LightSamplerKind::kPower;
  if (kind_ == LightSamplerKind::kPower) {
    if (!entries_.empty()) select_ = Distribution1D(std::move(power));
    // With a single light the choice is always it, with the probability the distribution
    // gives (computed once; a search per sample otherwise).
    if (entries_.size() == 1) select_.sample_discrete(0.5f, single_p_select_);
    if (env_entry_ >= 0) env_probability_ = select_.probability(std::size_t(env_entry_));
    return;
  }
  // The infinite lights as one group, chosen by its share of the power (the probability
  // the power sampler gives it), then one of them by power.
  std::vector<float> infinite_power;
  double infinite_total = 0.0;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    const bool infinite =
        e.kind == Kind::kEnvironment ||
        (e.kind == Kind::kPunctual && scene.lights[e.index].type == Light::Type::kDirectional);
    if (!infinite) continue;
    infinite_entries_.push_back(std::uint32_t(i));
    infinite_power.push_back(power[i]);
    infinite_total += double(power[i]);
  }
  bvh_ = LightBvh(bounds);
  const double total = infinite_total + bvh_.total_power();
  if (!infinite_entries_.empty()) {
    infinite_select_ = Distribution1D(std::move(infinite_power));
    p_infinite_ = bvh_.empty() ? 1.0f : total > 0.0 ? float(infinite_total / total) : 0.0f;
  }
  if (env_entry_ >= 0) env_probability_ = p_infinite_ * infinite_select_.probability(0);
}

std::int64_t LightSet::select(glm::vec3 p, glm::vec3 n, float u_select, float& p_select) const {
  p_select = 0.0f;
  if (entries_.empty()) return -1;
  if (kind_ == LightSamplerKind::kPower) {
    p_select = single_p_select_;
    return entries_.size() == 1 ? 0 : std::int64_t(select_.sample_discrete(u_select, p_select));
  }
  return select_bvh(p, n, u_select, p_select);
}

std::int64_t LightSet::select_bvh(glm::vec3 p, glm::vec3 n, float u_select, float& p_select) const {
  if (u_select < p_infinite_) {
    const float u = std::min(u_select / p_infinite_, kOneMinusEpsilon);
    float unused = 0.0f;
    const std::size_t k = infinite_select_.sample_discrete(u, unused);
    // (The same expression as pmf() and environment_probability().)
    p_select = p_infinite_ * infinite_select_.probability(k);
    return infinite_entries_[k];
  }
  const float u = std::min((u_select - p_infinite_) / (1.0f - p_infinite_), kOneMinusEpsilon);
  float q = 0.0f;
  const std::int64_t i = bvh_.sample(p, n, u, q);
  if (i < 0) return -1;
  p_select = (1.0f - p_infinite_) * q;
  return i;
}

float LightSet::pmf(glm::vec3 p, glm::vec3 n, std::size_t light) const {
  if (light >= entries_.size()) return 0.0f;
  if (kind_ == LightSamplerKind::kPower)
    return entries_.size() == 1 ? single_p_select_ : select_.probability(light);
  for (std::size_t k = 0; k < infinite_entries_.size(); ++k)
    if (infinite_entries_[k] == light) return p_infinite_ * infinite_select_.probability(k);
  return (1.0f - p_infinite_) * bvh_.pmf(p, n, std::uint32_t(light));
}

bool LightSet::sample(glm::vec3 p, glm::vec3 n, float u_select, glm::vec2 u,
                      LightSample& out) const {
  if (entries_.empty()) return false;
  // (The power sampler's choice inline, as it was before the BVH existed: the integrator's
  // opaque path is sensitive to what gets inlined into it.)
  float p_select = single_p_select_;
  std::size_t i = 0;
  if (kind_ == LightSamplerKind::kPower) {
    i = entries_.size() == 1 ? 0 : select_.sample_discrete(u_select, p_select);
  } else {
    const std::int64_t k = select_bvh(p, n, u_select, p_select);
    if (k < 0) return false;
    i = std::size_t(k);
  }
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
      const SurfaceHit hit = geometry_.resolve(e.index, e.prim, 0.0f, b1, b2, kShutterCentre);
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
  return env_probability_ * env_sampler_->pdf(d);
}

float LightSet::triangle_pdf(const SurfaceHit& hit, glm::vec3 from, glm::vec3 from_n) const {
  const int first = first_light_[hit.geom];
  if (first < 0) return 0.0f;
  const glm::vec3 to = hit.p - from;
  const float d2 = glm::dot(to, to);
  const float cos_l = std::fabs(glm::dot(hit.ng, to)) / std::sqrt(d2);
  if (!(cos_l > 0.0f) || !(hit.area > 0.0f)) return 0.0f;
  const std::size_t light = std::size_t(first) + hit.prim;
  const float p_select = kind_ == LightSamplerKind::kPower
                             ? select_.probability(light)
                             : (1.0f - p_infinite_) * bvh_.pmf(from, from_n, std::uint32_t(light));
  return p_select * d2 / (cos_l * hit.area);
}

}  // namespace pbrkit
