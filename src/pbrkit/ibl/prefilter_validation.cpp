// Brute-force prefilter references (see prefilter_validation.h).
#include "pbrkit/ibl/prefilter_validation.h"

#include <cmath>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/equirect.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

PrefilterReference::PrefilterReference(const Environment& env) {
  const Image& map = env.map;
  const double dphi = 2.0 * kPi / map.width;
  for (int y = 0; y < map.height; ++y) {
    // Exact solid angle of a lat-long texel: dphi (cos theta0 - cos theta1).
    const double theta0 = kPi * y / map.height, theta1 = kPi * (y + 1) / map.height;
    const float dw = float(dphi * (std::cos(theta0) - std::cos(theta1)));
    for (int x = 0; x < map.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / map.width, (y + 0.5f) / map.height);
      directions_.push_back(env_to_world(equirect_direction(uv), env.rotation_deg));
      radiance_.push_back(map.rgb(x, y) * env.intensity * dw);
      solid_angle_.push_back(dw);
    }
  }
}

glm::vec3 PrefilterReference::eval(glm::vec3 R, float roughness) const {
  const float alpha = sqr(std::max(roughness, kMinRoughness));
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (std::size_t i = 0; i < directions_.size(); ++i) {
    const glm::vec3& l = directions_[i];
    const float RdotL = glm::dot(R, l);
    if (RdotL <= 0.0f) continue;
    const float NdotH = glm::dot(R, glm::normalize(R + l));
    const double w = double(DistributionGGX(NdotH, alpha)) * RdotL;
    sum += glm::dvec3(radiance_[i]) * w;
    weight += w * solid_angle_[i];
  }
  return weight > 0.0 ? glm::vec3(sum / weight) : glm::vec3(0.0f);
}

std::vector<PrefilterError> validate_prefilter(const Environment& env, const Cubemap& specular,
                                               RoughnessMapping mapping, int per_face) {
  const PrefilterReference reference(env);
  std::vector<PrefilterError> out;
  for (int level = 1; level < specular.levels(); ++level) {
    const int size = specular.size(level);
    // Texel centres spread over each face (deterministic, away from the exact centre).
    struct Probe {
      int face, x, y;
    };
    std::vector<Probe> probes;
    for (int face = 0; face < 6; ++face)
      for (int k = 0; k < per_face; ++k) {
        const int x = (size * (2 * k + 1)) / (2 * per_face);
        const int y = (size * (k * 7 % per_face * 2 + 1)) / (2 * per_face);
        probes.push_back({face, std::min(x, size - 1), std::min(y, size - 1)});
      }
    const float roughness = mip_roughness(level, specular.levels(), mapping);
    std::vector<double> errors(probes.size());
    pbrkit::parallel_for(std::size_t(0), probes.size(), [&](std::size_t i) {
      const Probe& p = probes[i];
      const glm::vec3 R =
          cube_direction(p.face, {(p.x + 0.5f) / float(size), (p.y + 0.5f) / float(size)});
      const glm::vec3 ref = reference.eval(R, roughness);
      const glm::vec3 got = specular.mips[level][p.face].rgb(p.x, p.y);
      const glm::vec3 d = glm::abs(got - ref);
      errors[i] = double(d.x + d.y + d.z) / std::max(double(ref.x + ref.y + ref.z), 1e-12);
    });
    PrefilterError e;
    e.level = level;
    e.roughness = roughness;
    e.directions = int(probes.size());
    for (double err : errors) {
      e.mean_relative += err / double(errors.size());
      e.max_relative = std::max(e.max_relative, err);
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace pbrkit
