// Irradiance SH9 (Ramamoorthi & Hanrahan 2001) and the irradiance cube against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/equirect.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/ibl/environment_cube.h"
#include "pbrkit/ibl/irradiance_cube.h"
#include "pbrkit/ibl/spherical_harmonics.h"

namespace pbrkit {
namespace {

// An environment whose radiance is a pure l <= 2 SH function, positive everywhere:
// L(w) = 1 + 0.5 x + 0.25 (3 y^2 - 1) + 0.2 x z (RGB scaled differently).
glm::vec3 band_limited_L(glm::vec3 w) {
  const float f = 1.0f + 0.5f * w.x + 0.25f * (3.0f * w.y * w.y - 1.0f) + 0.2f * w.x * w.z;
  return glm::vec3(f, 2.0f * f, 0.5f * f);
}
// Its irradiance E(n) = int L max(0, n.w) dw: the cosine convolution scales band l by
// A_l = pi, 2 pi / 3, pi / 4 (Funk-Hecke; R&H 2001 eq. 8).
glm::vec3 band_limited_E(glm::vec3 n) {
  const float f = kPi * 1.0f + (2.0f * kPi / 3.0f) * 0.5f * n.x +
                  (kPi / 4.0f) * (0.25f * (3.0f * n.y * n.y - 1.0f) + 0.2f * n.x * n.z);
  return glm::vec3(f, 2.0f * f, 0.5f * f);
}

Environment function_environment(glm::vec3 (*L)(glm::vec3), int width) {
  Environment env;
  env.map = Image(width, width / 2, 3);
  for (int y = 0; y < env.map.height; ++y)
    for (int x = 0; x < env.map.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / env.map.width, (y + 0.5f) / env.map.height);
      env.map.set_rgb(x, y, L(equirect_direction(uv)));
    }
  env.source = "test";
  return env;
}

Cubemap cube_of(const Environment& env, int size) {
  Cubemap cube = resample_to_cube(env, size);
  build_mip_chain(cube, 1);
  return cube;
}

TEST(SphericalHarmonics, ConstantEnvironmentGivesPiL) {
  const glm::vec3 L(0.3f, 1.0f, 2.5f);
  const Cubemap cube = cube_of(Environment::constant(L), 32);
  const SH9 sh = project_sh_irradiance(cube);
  Pcg32 rng(1);
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 n = sample_uniform_sphere(rng.next_2d()).direction;
    const glm::vec3 E = eval_sh_irradiance(sh, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(E[c] / (kPi * L[c]), 1.0f, 1e-4f);
  }
  for (int i = 1; i < 9; ++i) EXPECT_NEAR(glm::length(sh[i]), 0.0f, 1e-4f) << i;
}

TEST(SphericalHarmonics, BandLimitedEnvironmentMatchesClosedForm) {
  const Cubemap cube = cube_of(function_environment(band_limited_L, 512), 64);
  const SH9 sh = project_sh_irradiance(cube);
  Pcg32 rng(2);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 n = sample_uniform_sphere(rng.next_2d()).direction;
    const glm::vec3 E = eval_sh_irradiance(sh, n), ref = band_limited_E(n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(E[c] / ref[c], 1.0f, 1e-3f) << n.x << n.y << n.z;
  }
}

TEST(SphericalHarmonics, HalfSkyIrradianceAtTheZenith) {
  // L = max(0, w.y) is not band-limited, but its irradiance at n = +Y is
  // int_{upper} y^2 dw = 2 pi / 3 exactly, and R&H's 9 terms reproduce irradiance to a few
  // percent (their section 3); the l = 4 term of the cosine lobe is -pi/24 * ... small.
  const Cubemap cube = cube_of(
      function_environment([](glm::vec3 w) { return glm::vec3(std::max(0.0f, w.y)); }, 512), 64);
  const SH9 sh = project_sh_irradiance(cube);
  EXPECT_NEAR(eval_sh_irradiance(sh, {0, 1, 0}).x / (2.0f * kPi / 3.0f), 1.0f, 0.03f);
  // The irradiance cube is a direct quadrature: accurate to much better.
  // (9 px faces: the face centre is a texel centre, so no interpolation is involved.)
  const Cubemap irr = irradiance_cube(cube, 9);
  EXPECT_NEAR(irr.mips[0][2].rgb(4, 4).x, 2.0f * kPi / 3.0f, 2e-3f);
  // At n = -Y nothing is visible but the resampling blur of the horizon (L ~ texel size).
  EXPECT_NEAR(irr.mips[0][3].rgb(4, 4).x, 0.0f, 2e-3f);
}

TEST(IrradianceCube, MatchesClosedFormsAtTexelCentres) {
  const glm::vec3 L(0.5f, 1.0f, 2.0f);
  const Cubemap flat = irradiance_cube(cube_of(Environment::constant(L), 32), 8);
  const Cubemap band = irradiance_cube(cube_of(function_environment(band_limited_L, 512), 64), 8);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const glm::vec3 n = cube_direction(f, {(x + 0.5f) / 8, (y + 0.5f) / 8});
        const glm::vec3 E0 = flat.mips[0][f].rgb(x, y);
        const glm::vec3 E1 = band.mips[0][f].rgb(x, y), ref = band_limited_E(n);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(E0[c] / (kPi * L[c]), 1.0f, 1e-4f);
          EXPECT_NEAR(E1[c] / ref[c], 1.0f, 2e-3f);
        }
      }
}

}  // namespace
}  // namespace pbrkit
