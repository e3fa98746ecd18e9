// anisotropy_ibl.glsl evaluated on the GPU (llvmpipe in CI) against ibl/anisotropic_taps.h
// and ibl/anisotropic_albedo.h: the tap points exactly, each tap's direction, weight and
// lookup roughness to float rounding (1e-4), the albedo texture's lookup against the C++
// table's to the filter's precision, and the lobe radiance from a cube of six flat faces
// against the C++ taps' weighted mean of the colour of the face each tap's direction (in
// world space, after the environment's rotation) falls on, times the albedo.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gl/harness/anisotropy_eval.h"
#include "gl_test_context.h"
#include "pbrkit/ibl/anisotropic_albedo.h"
#include "pbrkit/ibl/anisotropic_taps.h"

namespace pbrkit::gl {
namespace {

// Views from normal incidence to grazing (n.v = 0.01) in every azimuth, lobes from
// isotropic to the most stretched (alpha 1 x 4e-4, anisotropy 1 at roughness 0.02) either
// way round, every tap, and random right-handed world frames.
std::vector<AnisotropyCase> tap_cases() {
  std::vector<AnisotropyCase> cases;
  std::mt19937 rng(26);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float cosines[] = {1.0f, 0.8f, 0.5f, 0.2f, 0.05f, 0.01f};
  const glm::vec2 alphas[] = {{0.09f, 0.09f}, {0.126f, 0.09f}, {0.5f, 0.09f}, {1.0f, 0.09f},
                              {1.0f, 4e-4f},  {0.09f, 1.0f},   {0.3f, 0.6f},  {1.0f, 1.0f}};
  for (float c : cosines)
    for (const glm::vec2& a : alphas)
      for (int tap = 0; tap < kAnisotropicTaps; ++tap) {
        AnisotropyCase t;
        const float phi = 6.2831853f * u(rng), s = std::sqrt(1.0f - c * c);
        t.wo = glm::vec3(s * std::cos(phi), s * std::sin(phi), c);
        t.tap = tap;
        t.alpha_x = a.x;
        t.alpha_y = a.y;
        const float z = 2.0f * u(rng) - 1.0f, psi = 6.2831853f * u(rng);
        const glm::vec3 n(std::sqrt(1.0f - z * z) * std::cos(psi),
                          std::sqrt(1.0f - z * z) * std::sin(psi), z);
        const glm::vec3 a0 = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 t0 = glm::normalize(glm::cross(a0, n));
        t.frame = glm::mat3(t0, glm::cross(n, t0), n);
        cases.push_back(t);
      }
  return cases;
}

TEST(AnisotropyGlsl, TapPointsAreTheCpps) {
  testing::context();
  std::vector<AnisotropyCase> cases(kAnisotropicTaps);
  for (int i = 0; i < kAnisotropicTaps; ++i) cases[std::size_t(i)].tap = i;
  const std::vector<glm::vec4> gpu = eval_anisotropy_glsl(cases, AnisotropyFunction::kTapPoint);
  for (int i = 0; i < kAnisotropicTaps; ++i) {
    const glm::vec2 want = anisotropic_tap_point(i);
    EXPECT_EQ(gpu[std::size_t(i)].x, want.x) << i;
    EXPECT_EQ(gpu[std::size_t(i)].y, want.y) << i;
    // On the disk, along the long axis, the set symmetric about the centre: a point
    // off the axis or a lopsided pair fails.
    EXPECT_LE(glm::length(want), 1.0f);
    EXPECT_EQ(want.y, 0.0f);
  }
  EXPECT_EQ(anisotropic_tap_point(0).x, 0.0f);
  EXPECT_EQ(anisotropic_tap_point(1).x, -anisotropic_tap_point(2).x);
  EXPECT_GT(anisotropic_tap_point(1).x, 0.0f);
}

TEST(AnisotropyGlsl, TapDirectionWeightAndRoughnessAreTheCpps) {
  testing::context();
  const std::vector<AnisotropyCase> cases = tap_cases();
  const std::vector<glm::vec4> wi = eval_anisotropy_glsl(cases, AnisotropyFunction::kTapWi);
  const std::vector<glm::vec4> wr = eval_anisotropy_glsl(cases, AnisotropyFunction::kTapWeight);
  int compared = 0, above = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const AnisotropyCase& c = cases[i];
    const AnisotropicTap want = anisotropic_tap(c.wo, c.alpha_x, c.alpha_y, c.tap);
    // Unit vectors: 1e-4 absolute is float rounding through the sampling's square roots.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(wi[i][k], want.wi[k], 1e-4f) << i << " axis " << k;
    EXPECT_NEAR(glm::length(want.wi), 1.0f, 1e-4f) << i;
    EXPECT_NEAR(wr[i].y, want.roughness, 1e-4f * want.roughness) << i;
    // A direction within rounding of the horizon may be kept on one side and dropped on
    // the other; elsewhere the weight G2 / G1 in [0, 1] agrees to 1e-4.
    if (std::abs(want.wi.z) < 1e-3f) continue;
    EXPECT_NEAR(wr[i].x, want.weight, 1e-4f) << i;
    EXPECT_GE(want.weight, 0.0f);
    EXPECT_LE(want.weight, 1.0f);
    above += want.weight > 0.0f;
    ++compared;
  }
  EXPECT_GT(compared, int(cases.size()) * 9 / 10);
  EXPECT_GT(above, compared / 2);
}

// The GL cube face a direction reads (+X, -X, +Y, -Y, +Z, -Z: the major axis), or -1 within
// 1e-3 of an edge, where rounding may pick either face.
int cube_face(glm::vec3 d) {
  const glm::vec3 a = glm::abs(d);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  const float major = a[axis];
  for (int k = 0; k < 3; ++k)
    if (k != axis && major - a[k] < 1e-3f) return -1;
  return 2 * axis + (d[axis] < 0.0f ? 1 : 0);
}

TEST(AnisotropyGlsl, RadianceIsTheWeightedSumOfTheTapsLookups) {
  testing::context();
  const std::array<glm::vec3, 6> colors = {
      glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f),
      glm::vec3(2.0f, 2.0f, 0.0f), glm::vec3(0.0f, 3.0f, 3.0f), glm::vec3(4.0f, 0.0f, 4.0f)};
  const float angle = 0.7f;  // world_to_env's (cos, sin) of a rotated map
  const glm::vec2 rotation(std::cos(angle), std::sin(angle));
  std::vector<AnisotropyCase> cases;
  for (AnisotropyCase c : tap_cases())
    if (c.tap == 0 && c.wo.z >= 1e-2f) cases.push_back(c);
  const std::vector<glm::vec4> gpu =
      eval_anisotropy_glsl(cases, AnisotropyFunction::kRadiance, colors, rotation);
  int compared = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const AnisotropyCase& c = cases[i];
    glm::vec3 want(0.0f);
    float weights = 0.0f;
    bool ambiguous = false;
    for (const AnisotropicTap& tap : anisotropic_taps(c.wo, c.alpha_x, c.alpha_y)) {
      if (std::abs(tap.wi.z) < 1e-3f) ambiguous = true;
      if (tap.weight <= 0.0f) continue;
      const glm::vec3 d = c.frame * tap.wi;
      const glm::vec3 e(rotation.x * d.x + rotation.y * d.z, d.y,
                        -rotation.y * d.x + rotation.x * d.z);
      const int face = cube_face(e);
      if (face < 0)
        ambiguous = true;
      else
        want += tap.weight * colors[std::size_t(face)];
      weights += tap.weight;
    }
    if (ambiguous) continue;
    want *= weights > 0.0f
                ? AnisotropicAlbedoTable::get().lookup(c.wo, c.alpha_x, c.alpha_y) / weights
                : 0.0f;
    // 1e-4 for the taps' rounding, 2e-3 for the albedo texture's filter weights (below).
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(gpu[i][k], want[k], 1e-4f + 2e-3f * want[k]) << i << " channel " << k;
    ++compared;
  }
  EXPECT_GT(compared, int(cases.size()) / 2);
}

// The albedo texture read with the renderer's filtering equals the C++ table's interpolation
// within 2e-3 relative (the hardware's filter weights are coarser than float: llvmpipe
// rounds them to 8 bits, half a 1/256 step of a node difference), over views, azimuths
// and lobes either way round. A texture coordinate off by half a texel, or the s blocks
// mixed up, misses by the nodes' differences (several percent).
TEST(AnisotropyGlsl, AlbedoIsTheTables) {
  testing::context();
  std::vector<AnisotropyCase> cases;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int n = 0; n < 512; ++n) {
    AnisotropyCase c;
    const float mu = 0.02f + 0.98f * u(rng), phi = 6.2831853f * u(rng);
    const float s = std::sqrt(1.0f - mu * mu);
    c.wo = glm::vec3(s * std::cos(phi), s * std::sin(phi), mu);
    const float roughness = 0.02f + 0.98f * u(rng), strength = u(rng);
    const float ab = roughness * roughness, at = ab + (1.0f - ab) * strength * strength;
    c.alpha_x = n % 2 ? at : ab;
    c.alpha_y = n % 2 ? ab : at;
    cases.push_back(c);
  }
  const std::vector<glm::vec4> gpu = eval_anisotropy_glsl(cases, AnisotropyFunction::kAlbedo);
  const AnisotropicAlbedoTable& table = AnisotropicAlbedoTable::get();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const AnisotropyCase& c = cases[i];
    const float want = table.lookup(c.wo, c.alpha_x, c.alpha_y);
    EXPECT_NEAR(gpu[i].x, want, 2e-3f * want) << i;
  }
}

}  // namespace
}  // namespace pbrkit::gl
