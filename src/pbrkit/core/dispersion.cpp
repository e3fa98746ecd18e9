#include "pbrkit/core/dispersion.h"

#include <algorithm>

namespace pbrkit {

float dispersion_ior(float ior, float dispersion, float lambda_nm) {
  if (!(dispersion > 0.0f) || !(ior > 1.0f) || !(lambda_nm > 0.0f)) return ior;
  // KHR_materials_dispersion README: V_d = 20 / dispersion and
  // n(lambda) = max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1).
  const float inv_abbe = dispersion / 20.0f;
  const float n = ior + (ior - 1.0f) * inv_abbe * (523655.0f / (lambda_nm * lambda_nm) - 1.5168f);
  return std::max(n, 1.0f);
}

glm::vec3 dispersion_iors(float ior, float dispersion) {
  return {dispersion_ior(ior, dispersion, kChannelWavelengthR), ior,
          dispersion_ior(ior, dispersion, kChannelWavelengthB)};
}

ChannelSample sample_channel(float u) {
  ChannelSample s;
  s.channel = std::clamp(int(u * 3.0f), 0, 2);
  s.lambda_nm = s.channel == 0   ? kChannelWavelengthR
                : s.channel == 1 ? kChannelWavelengthG
                                 : kChannelWavelengthB;
  s.weight = glm::vec3(0.0f);
  s.weight[s.channel] = 3.0f;
  return s;
}

}  // namespace pbrkit
