// VertexBrdf (the path tracer's per-vertex evaluation of the model's BRDF) against core's
// Brdf: the same bits for eval, pdf and sample, for both geometry models, with and
// without multiple-scattering compensation, over random materials and directions
// (including directions below the horizon and out-of-range material inputs). If this
// fails after a change to core/brdf.cpp, mirror the change in pt/vertex_brdf.h.
#include <gtest/gtest.h>

#include <cstring>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/vertex_brdf.h"

namespace pbrkit::test {
namespace {

template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

TEST(VertexBrdf, BitIdenticalToBrdf) {
  Pcg32 rng(17);
  int valid_samples = 0;
  for (BrdfModel model : {BrdfModel::kReference, BrdfModel::kClassic})
    for (bool multiscatter : {false, true}) {
      BrdfOptions options;
      options.model = model;
      options.multiscatter = multiscatter;
      for (int m = 0; m < 300; ++m) {
        const glm::vec3 base(1.2f * rng.next_float() - 0.1f, rng.next_float(), rng.next_float());
        const float metallic = 1.2f * rng.next_float() - 0.1f;
        const float roughness = m % 10 == 0 ? 0.0f : m % 10 == 1 ? 1.0f : rng.next_float();
        const Brdf brdf(base, metallic, roughness, options);
        for (int o = 0; o < 20; ++o) {
          glm::vec3 wo = sample_uniform_sphere(rng.next_2d()).direction;
          if (o == 0) wo = glm::normalize(glm::vec3(1.0f, 0.0f, 1e-4f));  // grazing
          const VertexBrdf vertex(brdf, wo);
          for (int i = 0; i < 20; ++i) {
            const glm::vec3 wi = sample_uniform_sphere(rng.next_2d()).direction;
            float pdf = -1.0f;
            const glm::vec3 f = vertex.eval(wi, &pdf);
            ASSERT_TRUE(same_bits(f, brdf.eval(wo, wi))) << "eval, material " << m;
            ASSERT_TRUE(same_bits(pdf, brdf.pdf(wo, wi))) << "pdf, material " << m;
            ASSERT_TRUE(same_bits(vertex.eval(wi), f));
            const float u_lobe = rng.next_float();
            const glm::vec2 u = rng.next_2d();
            const BrdfSample a = vertex.sample(u_lobe, u), b = brdf.sample(wo, u_lobe, u);
            ASSERT_EQ(a.valid, b.valid);
            ASSERT_TRUE(same_bits(a.wi, b.wi));
            ASSERT_TRUE(same_bits(a.pdf, b.pdf));
            ASSERT_TRUE(same_bits(a.weight, b.weight)) << "sample, material " << m;
            valid_samples += a.valid;
          }
        }
      }
    }
  EXPECT_GT(valid_samples, 40000);  // most samples above the horizon are valid
}

}  // namespace
}  // namespace pbrkit::test
