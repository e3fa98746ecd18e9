// The sheen's SH radiance (see sheen_sh.h).
#include "pbrkit/ibl/sheen_sh.h"

#include <cmath>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sheen.h"

namespace pbrkit {

glm::vec3 sheen_tangent(glm::vec3 n, glm::vec3 v) {
  const glm::vec3 t = v - n * glm::dot(n, v);
  const float tl = glm::length(t);
  if (tl > 1e-6f) return t / tl;
  return glm::normalize(glm::cross(
      n, std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f)));
}

glm::vec3 sheen_sh_radiance(const SH9& sh, glm::vec3 n, glm::vec3 v, float roughness) {
  const SheenTable& table = SheenTable::get();
  const float mu = glm::dot(n, v);
  const glm::vec3 t = sheen_tangent(n, v);
  const glm::vec3 b = glm::cross(n, t);
  const glm::vec2 m = table.lobe_mean(mu, roughness);
  const glm::vec3 q = table.lobe_second_moments(mu, roughness);  // (tt, nn, tn)
  const glm::vec3 mean = m.x * t + m.y * n;
  // <l_i l_j> in the world frame: the tabulated moments in (t, n, b); bb = 1 - tt - nn
  // (|l| = 1), tb = nb = 0 (the lobe is symmetric across the plane of n and v).
  const glm::mat3 M = q.x * glm::outerProduct(t, t) + q.y * glm::outerProduct(n, n) +
                      (1.0f - q.x - q.y) * glm::outerProduct(b, b) +
                      q.z * (glm::outerProduct(t, n) + glm::outerProduct(n, t));
  // Radiance coefficients L_lm = sh_lm / A_l (A_l = pi, 2 pi / 3, pi / 4: R&H 2001 eq. 8),
  // times <Y_lm> in SH9's basis (Y_1-1 ~ y, Y_10 ~ z, Y_11 ~ x).
  const glm::vec3 band0 = sh[0] * (0.282095f / kPi);
  const glm::vec3 band1 =
      (sh[1] * mean.y + sh[2] * mean.z + sh[3] * mean.x) * (0.488603f * 3.0f / (2.0f * kPi));
  const glm::vec3 band2 =
      (sh[4] * (1.092548f * M[0][1]) + sh[5] * (1.092548f * M[1][2]) +
       sh[6] * (0.315392f * (3.0f * M[2][2] - 1.0f)) + sh[7] * (1.092548f * M[0][2]) +
       sh[8] * (0.546274f * (M[0][0] - M[1][1]))) *
      (4.0f / kPi);
  return band0 + band1 + band2;
}

}  // namespace pbrkit
