#include "pbrkit/ibl/anisotropic_albedo.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "pbrkit/core/anisotropic_energy.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/ibl/anisotropic_taps.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

float anisotropic_albedo(glm::vec3 wo, float alpha_x, float alpha_y, int radii, int angles) {
  // The disk's area split into `radii` rings of equal area (r = sqrt of a stratum's
  // midpoint) and `angles` sectors: every point carries the same share of the visible
  // normals. The integrand G2 / G1(wo) is smooth but for the horizon's cut (0 below it).
  const float lambda_o = SmithLambdaGGXAniso(wo, alpha_x, alpha_y);
  double sum = 0.0;
  for (int a = 0; a < radii; ++a) {
    const float r = std::sqrt((float(a) + 0.5f) / float(radii));
    for (int b = 0; b < angles; ++b) {
      const float phi = 2.0f * kPi * (float(b) + 0.5f) / float(angles);
      const glm::vec3 h = anisotropic_visible_normal(
          wo, r * glm::vec2(std::cos(phi), std::sin(phi)), alpha_x, alpha_y);
      const glm::vec3 wi = 2.0f * glm::dot(wo, h) * h - wo;
      if (wi.z > 0.0f)
        sum += (1.0f + lambda_o) / (1.0f + lambda_o + SmithLambdaGGXAniso(wi, alpha_x, alpha_y));
    }
  }
  return float(sum / (double(radii) * double(angles)));
}

namespace {

// The nodes and weight of coordinate c in [0, 1] over n nodes.
void bracket(float c, int n, int& i0, int& i1, float& f) {
  const float x = std::clamp(c * float(n - 1), 0.0f, float(n - 1));
  i0 = std::min(int(x), n - 2);
  i1 = i0 + 1;
  f = x - float(i0);
}

}  // namespace

void AnisotropicAlbedoTable::node_lobe(int i, int j, int k, int l, glm::vec3& wo, float& alpha_x,
                                       float& alpha_y) {
  // One grid for both tables: the multiple-scattering table the path tracer reads
  // (core/anisotropic_energy.h) says where the nodes are (mu = c^2, dense towards grazing;
  // p = y / (x + y) on the unit circle's first quadrant; r from kMinRoughness).
  static_assert(kMu == AnisotropicEnergyTable::kMu && kPhi == AnisotropicEnergyTable::kPhi &&
                kR == AnisotropicEnergyTable::kR && kS == AnisotropicEnergyTable::kS);
  AnisotropicEnergyTable::node_lobe(i, j, k, l, wo, alpha_x, alpha_y);
}

std::vector<float> AnisotropicAlbedoTable::compute() {
  std::vector<float> values(std::size_t(kMu) * kPhi * kR * kS);
  pbrkit::parallel_for(0, kR * kS, [&](int kl) {
    const int k = kl % kR, l = kl / kR;
    for (int j = 0; j < kPhi; ++j)
      for (int i = 0; i < kMu; ++i) {
        glm::vec3 wo;
        float ax = 0.0f, ay = 0.0f;
        node_lobe(i, j, k, l, wo, ax, ay);
        values[index(i, j, k, l)] = anisotropic_albedo(wo, ax, ay);
      }
  });
  return values;
}

namespace {
#include "anisotropic_albedo_data.inc"  // kBakedAlbedo: compute()
}  // namespace

AnisotropicAlbedoTable::AnisotropicAlbedoTable()
    : values_(std::begin(kBakedAlbedo), std::end(kBakedAlbedo)) {
  static_assert(std::size(kBakedAlbedo) == std::size_t(kMu) * kPhi * kR * kS);
}

const AnisotropicAlbedoTable& AnisotropicAlbedoTable::get() {
  static const AnisotropicAlbedoTable table;
  return table;
}

glm::vec4 AnisotropicAlbedoTable::coordinates(glm::vec3 wo, float alpha_x, float alpha_y) {
  // The lobe is symmetric under x -> -x and y -> -y (D and Smith's Lambda are even in
  // both), so the azimuth folds into [0, pi/2]; swapping the axes swaps the alphas.
  float ax = alpha_x, ay = alpha_y;
  glm::vec2 xy = glm::abs(glm::vec2(wo.x, wo.y));
  if (ay > ax) {
    std::swap(ax, ay);
    std::swap(xy.x, xy.y);
  }
  const float p = xy.x + xy.y > 0.0f ? xy.y / (xy.x + xy.y) : 0.0f;
  const float s = ay < 1.0f ? std::clamp((ax - ay) / (1.0f - ay), 0.0f, 1.0f) : 0.0f;
  return {std::sqrt(std::clamp(wo.z, 0.0f, 1.0f)), p, std::sqrt(ay), std::sqrt(s)};
}

float AnisotropicAlbedoTable::lookup(glm::vec3 wo, float alpha_x, float alpha_y) const {
  const glm::vec4 c = coordinates(wo, alpha_x, alpha_y);
  int i[2], j[2], k[2], l[2];
  float fi, fj, fk, fl;
  bracket(c.x, kMu, i[0], i[1], fi);
  bracket(c.y, kPhi, j[0], j[1], fj);
  bracket(c.z, kR, k[0], k[1], fk);
  bracket(c.w, kS, l[0], l[1], fl);
  float result = 0.0f;
  for (int d = 0; d < 16; ++d) {
    const int a = d & 1, b = (d >> 1) & 1, e = (d >> 2) & 1, g = (d >> 3) & 1;
    const float w =
        (a ? fi : 1.0f - fi) * (b ? fj : 1.0f - fj) * (e ? fk : 1.0f - fk) * (g ? fl : 1.0f - fl);
    result += w * node(i[a], j[b], k[e], l[g]);
  }
  return result;
}

}  // namespace pbrkit
