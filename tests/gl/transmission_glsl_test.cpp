// transmission.glsl evaluated on the GPU (llvmpipe in CI) against the path tracer's C++
// (core/transmission.h's refract and volume_transmittance, core/dispersion.h's
// dispersion_iors, core/microfacet.h's D and G) and against references written here in
// double from other forms of the same definitions: the refracted ray from Snell's law in
// pbrt's form (and Snell's invariant itself), Beer-Lambert as exp(-sigma d), the Sample
// Viewer's ior -/+ halfSpread and applyIorToRoughness, the projection in double. 1e-4
// relative, with absolute floors where a value crosses 0 (each says why).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/harness/transmission_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/dispersion.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/transmission.h"

namespace pbrkit::gl {
namespace {

glm::dvec3 d3(glm::vec3 v) {
  return glm::dvec3(v);
}

// Random unit normals and view directions on the normal's side, with every limit: normal
// incidence, grazing (n.v = 1e-3), ior 1 (no bending), ior < 1 (total internal
// reflection past the critical angle), thickness 0 (thin walled), non-uniform scale.
std::vector<TransmissionCase> ray_cases() {
  std::vector<TransmissionCase> cases;
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float iors[] = {1.0f, 1.01f, 1.33f, 1.5f, 1.8f, 2.4f, 0.75f};
  const float cosines[] = {1.0f, 0.9f, 0.5f, 0.2f, 0.05f, 1e-3f};
  for (float ior : iors)
    for (float c : cosines)
      for (int k = 0; k < 8; ++k) {
        TransmissionCase t;
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        t.n = glm::vec3(std::sqrt(1.0f - z * z) * std::cos(phi),
                        std::sqrt(1.0f - z * z) * std::sin(phi), z);
        // v at angle acos(c) from n, in a random azimuth.
        glm::vec3 a = std::abs(t.n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 b1 = glm::normalize(glm::cross(t.n, a)), b2 = glm::cross(t.n, b1);
        const float psi = 6.2831853f * u(rng), s = std::sqrt(1.0f - c * c);
        t.v = glm::normalize(c * t.n + s * (std::cos(psi) * b1 + std::sin(psi) * b2));
        t.ior = ior;
        t.thickness = k == 0 ? 0.0f : 0.01f + 3.0f * u(rng);
        t.model_scale =
            k < 4 ? glm::vec3(1.0f) : glm::vec3(0.5f + u(rng), 0.5f + u(rng), 2.0f * u(rng));
        cases.push_back(t);
      }
  return cases;
}

TEST(TransmissionGlsl, VolumeRayIsSnellsRefractionThroughTheThickness) {
  testing::context();
  const std::vector<TransmissionCase> cases = ray_cases();
  const std::vector<glm::vec4> gpu =
      eval_transmission_glsl(cases, TransmissionFunction::kVolumeRay);
  double worst = 0.0, worst_snell = 0.0, worst_core = 0.0;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TransmissionCase& c = cases[i];
    const glm::dvec3 n = d3(c.n), v = glm::normalize(d3(c.v));
    // pbrt-v4's Refract (eq. 9.4 form): wt = -wi/eta + (cos_i/eta - cos_t) n, eta = ior.
    const double cos_i = glm::dot(n, v);
    const double sin2_t = (1.0 - cos_i * cos_i) / (double(c.ior) * c.ior);
    glm::dvec3 expected(0.0);
    double cos_t = 1.0;
    if (c.thickness > 0.0f && sin2_t < 1.0) {
      cos_t = std::sqrt(1.0 - sin2_t);
      const glm::dvec3 wt = -v / double(c.ior) + (cos_i / double(c.ior) - cos_t) * n;
      expected = glm::normalize(wt) * double(c.thickness) * d3(c.model_scale);
      // The path tracer's refract (core/transmission.h), the same direction in float.
      glm::vec3 wt_core(0.0f);
      EXPECT_TRUE(refract(c.v, c.n, c.ior, wt_core)) << "case " << i;
      const glm::dvec3 g = glm::normalize(d3(glm::vec3(gpu[i])) / d3(c.model_scale));
      worst_core = std::max(
          worst_core, glm::length(g - d3(wt_core)) / (1e-4 + 6e-8 / (2.0 * std::max(cos_t, 1e-6))));
      // Snell's law on the GPU's direction (before the scale): ior sin_t = sin_i.
      if (c.model_scale == glm::vec3(1.0f)) {
        const glm::dvec3 g = glm::normalize(d3(glm::vec3(gpu[i])));
        const double sin_t = glm::length(glm::cross(n, g)), sin_i = glm::length(glm::cross(n, v));
        worst_snell = std::max(worst_snell, std::abs(c.ior * sin_t - sin_i) / 1e-4);
        EXPECT_LT(glm::dot(g, n), 0.0) << "case " << i << ": the ray must go into the medium";
      }
    }
    // Floor: the ray's components cross 0 while its length is thickness x scale; float
    // rounding of a unit vector's components is ~1e-7 of that length, so 1e-6 of it. Near
    // grazing, refract's cos_t = sqrt(1 - eta^2 (1 - cos_i^2)) cancels: float's rounding of
    // the argument near 1 (6e-8) moves cos_t by 6e-8 / (2 cos_t), of the length too
    // (measured: 2e-6 of the length at ior 1, n.v = 1e-3, where cos_t = 1e-3 allows 3e-5).
    const double floor =
        (1e-6 + 6e-8 / (2.0 * std::max(cos_t, 1e-6))) * std::max(glm::length(expected), 1e-9);
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(gpu[i][k])) << "case " << i;
      const double d = std::abs(double(gpu[i][k]) - expected[k]);
      const double ratio = d / (1e-4 * std::abs(expected[k]) + floor);
      if (ratio > worst) {
        worst = ratio;
        worst_index = i;
      }
    }
  }
  const TransmissionCase& w = cases[worst_index];
  std::printf("worst case %zu: ior %g, n.v %g, thickness %g\n", worst_index, double(w.ior),
              double(glm::dot(w.n, w.v)), double(w.thickness));
  std::printf("%zu cases; worst %.3g of the allowed error; Snell %.3g of 1e-4; core refract %.3g\n",
              cases.size(), worst, worst_snell, worst_core);
  EXPECT_LE(worst, 1.0);
  EXPECT_LE(worst_core, 1.0);
  EXPECT_LE(worst_snell, 1.0);
}

TEST(TransmissionGlsl, DispersionIorsAreThePathTracersAndTheSampleViewers) {
  testing::context();
  std::vector<TransmissionCase> cases;
  for (float ior : {1.0f, 1.1f, 1.33f, 1.5f, 1.7f, 2.0f, 2.42f})
    for (float dispersion : {0.0f, 0.01f, 0.1f, 0.33f, 0.5f, 1.0f, 3.0f, 20.0f}) {
      TransmissionCase c;
      c.ior = ior;
      c.dispersion = dispersion;
      cases.push_back(c);
    }
  const std::vector<glm::vec4> gpu =
      eval_transmission_glsl(cases, TransmissionFunction::kDispersion);
  // float rounding of n_d + (n_d - 1)/V (523655 / lambda^2 - 1.5168) near 1.5..2.4 is a few
  // ulps (2.4e-7 each; measured below 3e-7): 1e-6 absolute on each ior.
  constexpr double kIorTol = 1e-6;
  double worst = 0.0, worst_viewer = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TransmissionCase& c = cases[i];
    // The path tracer's (core/dispersion.h).
    const glm::vec3 cpu = dispersion_iors(c.ior, c.dispersion);
    // The Sample Viewer's ior -/+ halfSpread, halfSpread = (ior - 1) 0.025 dispersion, at
    // least 1. The channel wavelengths are rounded to 0.01 nm, which moves the README's
    // bracket 523655 / lambda^2 - 1.5168 off -/+1/2 by 8.3e-6 (R) and 3.8e-5 (B): 4e-5 of
    // (ior - 1) / V on top of the float tolerance.
    const double half = c.ior > 1.0f ? (c.ior - 1.0) * 0.025 * c.dispersion : 0.0;
    const glm::dvec3 viewer(std::max(c.ior - half, 1.0), c.ior, c.ior + half);
    const double viewer_tol = kIorTol + 4e-5 * 2.0 * half;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isfinite(gpu[i][k])) << "case " << i;
      worst = std::max(worst, std::abs(double(gpu[i][k]) - cpu[k]) / kIorTol);
      worst_viewer = std::max(worst_viewer, std::abs(double(gpu[i][k]) - viewer[k]) / viewer_tol);
    }
    if (c.dispersion > 0.0f && c.ior > 1.0f) {
      EXPECT_LT(gpu[i].x, gpu[i].y) << "normal dispersion: red bends least";
      EXPECT_GT(gpu[i].z, gpu[i].y);
    }
  }
  std::printf(
      "%zu cases; worst %.3g of the allowed error against core/dispersion.h, %.3g "
      "against the Sample Viewer's\n",
      cases.size(), worst, worst_viewer);
  EXPECT_LE(worst, 1.0);
  EXPECT_LE(worst_viewer, 1.0);
}

TEST(TransmissionGlsl, AttenuationIsBeerLambert) {
  testing::context();
  std::vector<TransmissionCase> cases;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    TransmissionCase c;
    c.attenuation_color = glm::vec3(u(rng), u(rng), i % 7 == 0 ? 0.0f : u(rng));
    c.attenuation_distance = i % 11 == 0 ? 0.0f : 0.01f + 4.0f * u(rng);
    c.distance = i % 13 == 0 ? 0.0f : 5.0f * u(rng);
    cases.push_back(c);
  }
  const std::vector<glm::vec4> gpu =
      eval_transmission_glsl(cases, TransmissionFunction::kAttenuation);
  double worst = 0.0, worst_core = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TransmissionCase& c = cases[i];
    for (int k = 0; k < 3; ++k) {
      // T = exp(-sigma d), sigma = -ln(c) / attenuation distance (KHR_materials_volume).
      double expected = 1.0;
      if (c.attenuation_distance > 0.0f && c.distance > 0.0f) {
        const double col = c.attenuation_color[k];
        expected = col <= 0.0 ? 0.0 : std::exp(std::log(col) / c.attenuation_distance * c.distance);
      }
      // The path tracer's (core/transmission.h; its "none" is an infinite distance).
      const float core_distance = c.attenuation_distance > 0.0f
                                      ? c.attenuation_distance
                                      : std::numeric_limits<float>::infinity();
      const float core = volume_transmittance(c.attenuation_color, core_distance, c.distance)[k];
      worst_core = std::max(worst_core, std::abs(double(gpu[i][k]) - core) / (1e-4 * core + 1e-6));
      ASSERT_TRUE(std::isfinite(gpu[i][k])) << "case " << i;
      // Floor: pow's exp2(y log2 x) carries ~1e-7 relative error in its exponent times
      // |y log2 x| (up to ~500 here): 1e-6 absolute at the smallest transmittances, 1/300 of
      // an 8-bit sRGB step at black.
      const double d = std::abs(double(gpu[i][k]) - expected);
      worst = std::max(worst, d / (1e-4 * expected + 1e-6));
    }
  }
  std::printf("%zu cases; worst %.3g of the allowed error; against core %.3g\n", cases.size(),
              worst, worst_core);
  EXPECT_LE(worst, 1.0);
  EXPECT_LE(worst_core, 1.0);
}

TEST(TransmissionGlsl, RoughnessAndLodFollowTheSampleViewer) {
  testing::context();
  std::vector<TransmissionCase> cases;
  for (float ior : {0.8f, 1.0f, 1.1f, 1.25f, 1.4f, 1.5f, 1.6f, 2.5f})
    for (float r : {0.0f, 0.02f, 0.3f, 0.7f, 1.0f})
      for (float w : {1.0f, 96.0f, 1920.0f}) {
        TransmissionCase c;
        c.ior = ior;
        c.roughness = r;
        c.width = w;
        cases.push_back(c);
      }
  const std::vector<glm::vec4> gpu =
      eval_transmission_glsl(cases, TransmissionFunction::kRoughness);
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TransmissionCase& c = cases[i];
    // applyIorToRoughness: none at ior <= 1, all of it from ior 1.5, linear in between.
    const double scale = c.ior <= 1.0f ? 0.0 : c.ior >= 1.5f ? 1.0 : (c.ior - 1.0) / 0.5;
    const double rough = c.roughness * scale;
    const double lod = std::log2(double(c.width)) * rough;  // 1x1 level at roughness 1
    worst = std::max({worst, std::abs(gpu[i].x - rough) / (1e-4 * rough + 1e-7),
                      std::abs(gpu[i].y - lod) / (1e-4 * lod + 1e-6)});
  }
  std::printf("%zu cases; worst %.3g of the allowed error\n", cases.size(), worst);
  EXPECT_LE(worst, 1.0);
}

// The Sample Viewer's punctual transmission lobe, against the C++ GGX D and
// height-correlated Smith G of core/microfacet.h (the path tracer's), with the dielectric
// Schlick Fresnel and KHR_materials_ior's F0 = ((ior - 1) / (ior + 1))^2 written here.
TEST(TransmissionGlsl, PunctualTransmissionIsTheMirroredGgxLobe) {
  testing::context();
  std::vector<TransmissionCase> cases;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto hemisphere = [&] {
    const float z = 0.02f + 0.98f * u(rng), phi = 6.2831853f * u(rng);
    const float s = std::sqrt(1.0f - z * z);
    return glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  for (float ior : {1.0f, 1.2f, 1.33f, 1.5f, 2.0f})
    for (float roughness : {0.0f, 0.1f, 0.4f, 1.0f})
      for (int k = 0; k < 40; ++k) {
        TransmissionCase c;
        c.ior = ior;
        c.roughness = roughness;
        c.n = hemisphere();
        // Half the cases near the straight-through direction, where the lobe peaks.
        c.v = k % 2 == 0 ? glm::normalize(c.n + 0.05f * hemisphere()) : hemisphere();
        c.base_color = glm::vec3(u(rng), u(rng), u(rng));
        c.metallic = k % 5 == 0 ? u(rng) : 0.0f;
        cases.push_back(c);
      }
  const std::vector<glm::vec4> gpu = eval_transmission_glsl(cases, TransmissionFunction::kPunctual);
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TransmissionCase& c = cases[i];
    const double scale = c.ior <= 1.0f ? 0.0 : c.ior >= 1.5f ? 1.0 : (c.ior - 1.0) / 0.5;
    const float r = std::max(float(std::max(c.roughness, kMinRoughness) * scale), kMinRoughness);
    const float alpha = r * r;
    const glm::vec3 h = glm::normalize(c.n + c.v);
    const double D = DistributionGGX(h, alpha), G = SmithG2HeightCorrelated(c.n, c.v, alpha);
    const double f0 = c.ior == 1.5f ? 0.04 : std::pow((c.ior - 1.0) / (c.ior + 1.0), 2.0);
    const double f90 = c.ior > 1.0f ? 1.0 : 0.0;
    const double F = f0 + (f90 - f0) * std::pow(1.0 - glm::dot(c.n, h), 5.0);
    for (int k = 0; k < 3; ++k) {
      const double expected =
          (1.0 - F) * (1.0 - c.metallic) * c.base_color[k] * D * G / (4.0 * c.n.z * c.v.z);
      ASSERT_TRUE(std::isfinite(gpu[i][k])) << "case " << i;
      // Floor: 1e-6 of the lobe's peak-free scale 1 / (4 pi): where the lobe falls to 0
      // only absolute float rounding of the terms remains.
      worst = std::max(worst, std::abs(gpu[i][k] - expected) / (1e-4 * expected + 1e-6 / 12.566));
    }
  }
  std::printf("%zu cases; worst %.3g of the allowed error\n", cases.size(), worst);
  EXPECT_LE(worst, 1.0);
}

TEST(TransmissionGlsl, ProjectionToTheScreen) {
  testing::context();
  const glm::mat4 projection = glm::perspective(0.8f, 1.5f, 0.05f, 100.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(1, 2, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::mat4 vp = projection * view;
  std::vector<TransmissionCase> cases;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  for (int i = 0; i < 1000; ++i) {
    TransmissionCase c;
    c.n = glm::vec3(u(rng), u(rng), u(rng));
    cases.push_back(c);
  }
  const std::vector<glm::vec4> gpu =
      eval_transmission_glsl(cases, TransmissionFunction::kProject, vp);
  int on = 0, off = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::dvec4 clip = glm::dmat4(vp) * glm::dvec4(d3(cases[i].n), 1.0);
    const glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
    const bool visible = clip.w > 0.0 && uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
    // Points within 1e-5 of the screen's edge may fall either side in float.
    const double edge =
        std::min({std::abs(uv.x), std::abs(uv.x - 1.0), std::abs(uv.y), std::abs(uv.y - 1.0)});
    if (edge > 1e-5) {
      EXPECT_EQ(gpu[i].z > 0.5f, visible) << "case " << i;
    }
    if (!visible) {
      ++off;
      continue;
    }
    ++on;
    EXPECT_NEAR(gpu[i].x, uv.x, 1e-5) << "case " << i;
    EXPECT_NEAR(gpu[i].y, uv.y, 1e-5) << "case " << i;
  }
  EXPECT_GT(on, 50);
  EXPECT_GT(off, 50);
}

}  // namespace
}  // namespace pbrkit::gl
