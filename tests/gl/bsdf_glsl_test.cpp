// The extensions' shader unit tests: the GLSL base layer with KHR_materials_ior, _specular,
// _anisotropy and _iridescence (brdf.glsl) against the C++ Brdf, and the layered material
// (bsdf.glsl: clearcoat over sheen over the base) against the C++ Bsdf, to 1e-4 relative
// as tests/gl/brdf_glsl_test.cpp does for the plain base layer.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "brdf_conditioning.h"
#include "gl/harness/bsdf_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/bsdf.h"

namespace pbrkit::gl {
namespace {

constexpr float kPiF = 3.14159265f;

glm::vec3 direction(float z, float phi) {
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A grid of base layers with the extensions over a grid of directions: strongly
// anisotropic (strength 1 at roughness 0.05: alpha_x / alpha_y = 400), grazing (n.v and
// n.l down to 0.03), along, across and between the anisotropy direction, ior 1 (no
// dielectric specular) to 3, specular colours above 1 (F0 clamped), iridescence.
std::vector<BrdfCase> extension_cases() {
  std::vector<BrdfCase> cases;
  const float zs[] = {0.03f, 0.2f, 0.6f, 1.0f};
  const float phis[] = {0.0f, 0.5f * kPiF, 0.25f * kPiF, 1.1f * kPiF};
  const float anisos[] = {0.0f, 0.5f, 0.9f, 1.0f};
  const float roughs[] = {0.05f, 0.3f, 0.8f};
  const float iors[] = {1.0f, 1.5f, 1.33f, 3.0f};
  int k = 0;
  for (float zo : zs)
    for (float zi : zs)
      for (float po : phis)
        for (float pi : phis)
          for (float a : anisos)
            for (float r : roughs) {
              BrdfCase c;
              c.wo = direction(zo, po);
              c.wi = direction(zi, pi + 0.3f);
              c.anisotropy = a;
              c.roughness = r;
              c.base_color = glm::vec3(0.9f, 0.5f, 0.2f);
              c.metallic = k % 3 == 0 ? 1.0f : k % 3 == 1 ? 0.0f : 0.4f;
              c.ior = iors[k % 4];
              c.specular = k % 5 == 0 ? 0.3f : 1.0f;
              c.specular_color = k % 7 == 0 ? glm::vec3(2.0f, 1.0f, 0.5f) : glm::vec3(1.0f);
              c.iridescence = k % 6 == 0 ? 0.7f : 0.0f;
              c.iridescence_thickness = 300.0f;
              cases.push_back(c);
              ++k;
            }
  return cases;
}

struct Comparison {
  double worst = 0.0;
  std::size_t index = 0;
};

// max |gpu - cpu| / (1e-4 max|cpu| + floor(i)) over the cases: 1e-9 absorbs values that
// are rounding noise around 0 in both; with compensation, brdf_glsl_test.cpp's
// conditioning bound (the propagated rounding of E near 1) is added, for the base scaled
// by layer weights <= 1.
template <class F, class Floor>
Comparison compare(const std::vector<glm::vec3>& gpu, std::size_t n, F cpu_of, Floor floor_of) {
  Comparison r;
  EXPECT_EQ(gpu.size(), n);
  for (std::size_t i = 0; i < n && i < gpu.size(); ++i) {
    const glm::vec3 cpu = cpu_of(i);
    EXPECT_TRUE(std::isfinite(gpu[i].r) && std::isfinite(gpu[i].g) && std::isfinite(gpu[i].b))
        << "case " << i;
    const double scale = std::max({std::abs(cpu.r), std::abs(cpu.g), std::abs(cpu.b)});
    double d = 0.0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(gpu[i][k]) - cpu[k]));
    const double ratio = d / (1e-4 * scale + floor_of(i));
    if (ratio > r.worst) r = {ratio, i};
  }
  return r;
}

TEST(BsdfGlsl, BaseLayerExtensionsMatchCpp) {
  testing::context();
  const std::vector<BrdfCase> cases = extension_cases();
  // Without compensation: no cancellation anywhere, so 1e-4 relative with a 1e-9 floor.
  const BrdfOptions options{BrdfModel::kReference, false};
  const std::vector<glm::vec3> gpu = eval_brdf_glsl(cases, options);
  const Comparison r = compare(
      gpu, cases.size(),
      [&](std::size_t i) { return Brdf(cases[i].layer(), options).eval(cases[i].wo, cases[i].wi); },
      [](std::size_t) { return 1e-9; });
  const BrdfCase& w = cases[r.index];
  EXPECT_LE(r.worst, 1.0) << "case " << r.index << ": anisotropy " << w.anisotropy << ", roughness "
                          << w.roughness << ", ior " << w.ior << ", wo.z " << w.wo.z << ", wi.z "
                          << w.wi.z;
  std::printf("%zu cases, largest difference %.3g of the allowed\n", cases.size(), r.worst);
  // The grid must exercise the extensions: strong anisotropy changes the value.
  BrdfCase iso = cases[1], aniso = cases[1];
  iso.anisotropy = 0.0f;
  aniso.anisotropy = 1.0f;
  const auto both = eval_brdf_glsl({iso, aniso}, options);
  EXPECT_GT(std::abs(both[0].r - both[1].r), 1e-3f * both[0].r);
}

TEST(BsdfGlsl, BaseLayerExtensionsWithCompensationMatchCpp) {
  testing::context();
  const std::vector<BrdfCase> cases = extension_cases();
  const BrdfOptions options{BrdfModel::kReference, true};
  const std::vector<glm::vec3> gpu = eval_brdf_glsl(cases, options);
  const Comparison r = compare(
      gpu, cases.size(),
      [&](std::size_t i) { return Brdf(cases[i].layer(), options).eval(cases[i].wo, cases[i].wi); },
      [&](std::size_t i) { return 1e-9 + testing::conditioning_bound(cases[i], options); });
  EXPECT_LE(r.worst, 1.0) << "case " << r.index;
  std::printf("%zu cases, largest difference %.3g of the allowed\n", cases.size(), r.worst);
}

std::vector<BsdfCase> layered_cases(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<BsdfCase> cases;
  for (int i = 0; i < count; ++i) {
    BsdfCase c;
    c.base.wo = direction(0.03f + 0.97f * u(rng), 2.0f * kPiF * u(rng));
    c.base.wi = direction(0.03f + 0.97f * u(rng), 2.0f * kPiF * u(rng));
    c.base.base_color = glm::vec3(u(rng), u(rng), u(rng));
    c.base.metallic = i % 3 == 0 ? 1.0f : i % 3 == 1 ? 0.0f : u(rng);
    c.base.roughness = 0.05f + 0.95f * u(rng);
    c.base.anisotropy = i % 4 == 0 ? u(rng) : 0.0f;
    c.base.ior = 1.2f + u(rng);
    // Every combination: coat only, sheen only, both.
    if (i % 3 != 1) {
      c.coat_weight = u(rng);
      c.coat_roughness = u(rng);
      // A tilted coat normal (a coat normal map) half the time.
      c.coat_normal = i % 2 ? glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, 1.0f))
                            : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    if (i % 3 != 0) {
      c.sheen_color = glm::vec3(u(rng), u(rng), u(rng));
      c.sheen_roughness = u(rng);
    }
    cases.push_back(c);
  }
  return cases;
}

void expect_layered_matches(const BrdfOptions& options, unsigned seed) {
  testing::context();
  const std::vector<BsdfCase> cases = layered_cases(seed, 3000);
  const std::vector<glm::vec3> gpu = eval_bsdf_glsl(cases, options);
  const Comparison r = compare(
      gpu, cases.size(),
      [&](std::size_t i) {
        return Bsdf(cases[i].params(), options).eval(cases[i].base.wo, cases[i].base.wi);
      },
      [&](std::size_t i) { return 1e-9 + testing::conditioning_bound(cases[i].base, options); });
  const BsdfCase& w = cases[r.index];
  EXPECT_LE(r.worst, 1.0) << "case " << r.index << ": coat " << w.coat_weight << " / "
                          << w.coat_roughness << ", sheen roughness " << w.sheen_roughness
                          << ", wo.z " << w.base.wo.z << ", wi.z " << w.base.wi.z;
  std::printf("%zu cases, largest difference %.3g of the allowed\n", cases.size(), r.worst);
}

TEST(BsdfGlsl, LayeredMatchesCpp) {
  expect_layered_matches({BrdfModel::kReference, false}, 11);
}
TEST(BsdfGlsl, LayeredWithCompensationMatchesCpp) {
  expect_layered_matches({BrdfModel::kReference, true}, 12);
}
TEST(BsdfGlsl, LayeredClassicMatchesCpp) {
  expect_layered_matches({BrdfModel::kClassic, false}, 13);
}

TEST(BsdfGlsl, LayersChangeTheResult) {
  // The harness must see the layers: a white coat over a black base reflects, a sheen
  // adds its colour.
  testing::context();
  BsdfCase plain;
  plain.base.base_color = glm::vec3(0.0f);
  plain.base.metallic = 0.0f;
  plain.base.ior = 1.0f;  // no dielectric specular: the base is black
  // wo = wi: h = wo, away from the normal, where the Charlie D is not 0.
  plain.base.wo = plain.base.wi = direction(0.3f, 0.0f);
  BsdfCase coated = plain, sheen = plain;
  coated.base.wi = direction(0.3f, kPiF);  // the mirror direction: the coat's peak
  coated.coat_weight = 1.0f;
  coated.coat_roughness = 0.3f;
  sheen.sheen_color = glm::vec3(1.0f, 0.0f, 0.0f);
  sheen.sheen_roughness = 0.5f;
  const auto f = eval_bsdf_glsl({plain, coated, sheen}, {BrdfModel::kReference, false});
  EXPECT_EQ(f[0], glm::vec3(0.0f));
  EXPECT_GT(f[1].g, 0.01f);
  EXPECT_GT(f[2].r, 0.01f);
  EXPECT_EQ(f[2].g, 0.0f);
}

}  // namespace
}  // namespace pbrkit::gl
