#include "pbrkit/core/anisotropic_energy.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {

float node_at(int i, int n) {
  return float(i) / float(n - 1);
}

// The nodes and weight of coordinate c in [0, 1] over n nodes.
void bracket(float c, int n, int& i0, float& f) {
  const float x = std::clamp(c * float(n - 1), 0.0f, float(n - 1));
  i0 = std::min(int(x), n - 2);
  f = x - float(i0);
}

// One (r, s) slice of the table: (mu, p) nodes, bilinear in between.
struct Slice {
  float ax, ay, bx, by;
  std::vector<float> v =
      std::vector<float>(std::size_t(AnisotropicEnergyTable::kMu) * AnisotropicEnergyTable::kPhi);
  float at(glm::vec3 w) const {
    using T = AnisotropicEnergyTable;
    const glm::vec4 c = T::coordinates(w, ax, ay);
    int i, j;
    float fi, fj;
    bracket(c.x, T::kMu, i, fi);
    bracket(c.y, T::kPhi, j, fj);
    auto n = [&](int a, int b) { return v[std::size_t(b) * T::kMu + std::size_t(a)]; };
    return (1.0f - fj) * ((1.0f - fi) * n(i, j) + fi * n(i + 1, j)) +
           fj * ((1.0f - fi) * n(i, j + 1) + fi * n(i + 1, j + 1));
  }
  // The hemispherical average 1 / pi int E cos dw of the interpolant: with u = mu^2,
  // 2 / pi int_0^(pi/2) int_0^1 E du dphi (midpoints; the lobe is even in x and y).
  double average() const {
    constexpr int nu = 128, nphi = 64;
    double sum = 0.0;
    for (int a = 0; a < nu; ++a) {
      const float mu = std::sqrt((float(a) + 0.5f) / float(nu)), s = std::sqrt(1.0f - mu * mu);
      for (int b = 0; b < nphi; ++b) {
        const float phi = 0.5f * kPi * (float(b) + 0.5f) / float(nphi);
        sum += at(glm::vec3(s * std::cos(phi), s * std::sin(phi), mu));
      }
    }
    return sum / (double(nu) * nphi);
  }
};

// int f(wo, wi) w(wi) cos dwi for the GGX lobe (ax, ay) with height-correlated Smith: the mean
// of G2 / G1(wo) w(wi) over its visible normals (Heitz 2018), on a lattice of midpoints.
template <class Weight>
double lobe_integral(glm::vec3 wo, float ax, float ay, Weight weight) {
  constexpr int n = AnisotropicEnergyTable::kLattice;
  const float lambda_o = SmithLambdaGGXAniso(wo, ax, ay);
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const glm::vec2 u((float(a) + 0.5f) / n, (float(b) + 0.5f) / n);
      const glm::vec3 wi = reflect_about(wo, sample_ggx_visible_normal(wo, u, ax, ay));
      if (!(wi.z > 0.0f)) continue;
      sum += (1.0f + lambda_o) / (1.0f + lambda_o + SmithLambdaGGXAniso(wi, ax, ay)) * weight(wi);
    }
  return sum / (double(n) * n);
}

}  // namespace

float AnisotropicEnergyTable::broadening(float alpha_x, float alpha_y) {
  const float rho = std::max(alpha_x, alpha_y) / std::max(std::min(alpha_x, alpha_y), 1e-6f);
  return std::max(1.5f - 0.87f * std::log(std::max(rho / 4.4f, 1.0f)), 0.5f);
}

glm::vec2 AnisotropicEnergyTable::broadened_alphas(float alpha_x, float alpha_y) {
  const float beta = broadening(alpha_x, alpha_y);
  return glm::min(beta * glm::vec2(alpha_x, alpha_y), glm::vec2(1.0f));
}

void AnisotropicEnergyTable::node_lobe(int i, int j, int k, int l, glm::vec3& wo, float& alpha_x,
                                       float& alpha_y) {
  const float c = node_at(i, kMu);
  const float mu = std::max(c * c, 1e-4f), p = node_at(j, kPhi);
  const float s = std::sqrt(std::max(1.0f - mu * mu, 0.0f));
  const glm::vec2 xy = s * glm::normalize(glm::vec2(1.0f - p, p));
  wo = glm::vec3(xy, mu);
  const float r = std::max(node_at(k, kR), kMinRoughness);
  alpha_y = r * r;
  const float strength = node_at(l, kS);
  alpha_x = alpha_y + (1.0f - alpha_y) * strength * strength;
}

glm::vec4 AnisotropicEnergyTable::coordinates(glm::vec3 wo, float alpha_x, float alpha_y) {
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

std::vector<float> AnisotropicEnergyTable::compute() {
  std::vector<float> out(3 * kNodes + 2 * std::size_t(kR) * kS);
  pbrkit::parallel_for(0, kR * kS, [&](int kl) {
    const int k = kl % kR, l = kl / kR;
    Slice E_ss, h, E_tot;
    glm::vec3 wo[kMu * kPhi];
    for (int j = 0; j < kPhi; ++j)
      for (int i = 0; i < kMu; ++i) node_lobe(i, j, k, l, wo[j * kMu + i], E_ss.ax, E_ss.ay);
    const glm::vec2 b = broadened_alphas(E_ss.ax, E_ss.ay);
    for (Slice* s : {&E_ss, &h, &E_tot}) *s = Slice{E_ss.ax, E_ss.ay, b.x, b.y};
    auto one = [](glm::vec3) { return 1.0f; };
    std::vector<float> target(std::size_t(kMu) * kPhi);
    for (int n = 0; n < kMu * kPhi; ++n) {
      E_ss.v[n] = float(lobe_integral(wo[n], h.ax, h.ay, one));
      target[n] = kShare * std::max(1.0f - E_ss.v[n], 0.0f);
      const float E_b = float(lobe_integral(wo[n], b.x, b.y, one));
      h.v[n] = std::sqrt(target[n] / std::max(E_b, 1e-6f));
    }
    // Symmetric matrix scaling (Sinkhorn-Knopp, damped by the geometric mean so that it
    // converges for a symmetric kernel): h(wo) H(wo) -> target(wo), H = int f_b h cos.
    std::vector<float> H(target.size());
    for (int it = 0; it <= kIterations; ++it) {
      for (int n = 0; n < kMu * kPhi; ++n)
        H[n] = float(lobe_integral(wo[n], b.x, b.y, [&](glm::vec3 w) { return h.at(w); }));
      if (it == kIterations) break;
      Slice next = h;
      for (int n = 0; n < kMu * kPhi; ++n)
        next.v[n] = H[n] > 0.0f ? std::sqrt(h.v[n] * target[n] / H[n]) : 0.0f;
      h = next;
    }
    for (int n = 0; n < kMu * kPhi; ++n) E_tot.v[n] = std::min(E_ss.v[n] + h.v[n] * H[n], 1.0f);
    for (int j = 0; j < kPhi; ++j)
      for (int i = 0; i < kMu; ++i) {
        const std::size_t node = index(i, j, k, l), n = std::size_t(j) * kMu + i;
        out[3 * node + 0] = E_ss.v[n];
        out[3 * node + 1] = h.v[n];
        out[3 * node + 2] = E_tot.v[n];
      }
    out[3 * kNodes + 2 * std::size_t(kl) + 0] = float(E_ss.average());
    out[3 * kNodes + 2 * std::size_t(kl) + 1] = float(E_tot.average());
  });
  return out;
}

namespace {
#include "anisotropic_energy_data.inc"  // kBakedAnisotropicEnergy: compute()
}  // namespace

AnisotropicEnergyTable::AnisotropicEnergyTable()
    : values_(std::begin(kBakedAnisotropicEnergy), std::end(kBakedAnisotropicEnergy)) {
  static_assert(std::size(kBakedAnisotropicEnergy) == 3 * kNodes + 2 * std::size_t(kR) * kS);
}

const AnisotropicEnergyTable& AnisotropicEnergyTable::get() {
  static const AnisotropicEnergyTable table;
  return table;
}

AnisotropicEnergyTable::Entry AnisotropicEnergyTable::lookup(glm::vec3 wo, float alpha_x,
                                                             float alpha_y) const {
  const glm::vec4 c = coordinates(wo, alpha_x, alpha_y);
  int i, j, k, l;
  float fi, fj, fk, fl;
  bracket(c.x, kMu, i, fi);
  bracket(c.y, kPhi, j, fj);
  bracket(c.z, kR, k, fk);
  bracket(c.w, kS, l, fl);
  glm::vec3 sum(0.0f);
  for (int d = 0; d < 16; ++d) {
    const int a = d & 1, b = (d >> 1) & 1, e = (d >> 2) & 1, g = (d >> 3) & 1;
    const float w =
        (a ? fi : 1.0f - fi) * (b ? fj : 1.0f - fj) * (e ? fk : 1.0f - fk) * (g ? fl : 1.0f - fl);
    const float* v = &values_[3 * index(i + a, j + b, k + e, l + g)];
    sum += w * glm::vec3(v[0], v[1], v[2]);
  }
  return {sum.x, sum.y, sum.z};
}

glm::vec2 AnisotropicEnergyTable::averages(float alpha_x, float alpha_y) const {
  const glm::vec4 c = coordinates(glm::vec3(0.0f, 0.0f, 1.0f), alpha_x, alpha_y);
  int k, l;
  float fk, fl;
  bracket(c.z, kR, k, fk);
  bracket(c.w, kS, l, fl);
  auto at = [&](int a, int b) {
    const float* v = &values_[3 * kNodes + 2 * (std::size_t(b) * kR + std::size_t(a))];
    return glm::vec2(v[0], v[1]);
  };
  return (1.0f - fl) * ((1.0f - fk) * at(k, l) + fk * at(k + 1, l)) +
         fl * ((1.0f - fk) * at(k, l + 1) + fk * at(k + 1, l + 1));
}

}  // namespace pbrkit
