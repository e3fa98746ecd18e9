// The vectorised prefilter loops (prefilter_kernels.h) against plain scalar sums: the
// culling of texels behind R must drop nothing, and the SIMD face selection and fetches
// must read what sample_cubemap reads.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pbrkit/core/math.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/ibl/environment_cube.h"
#include "pbrkit/ibl/prefilter.h"
#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/ibl/simd.h"

namespace pbrkit {
namespace {

// A cube whose texels all differ (so a wrong texel or face shows), with its full chain.
Cubemap varied_cube(int size) {
  Cubemap cube;
  cube.mips.emplace_back();
  for (int f = 0; f < 6; ++f) {
    cube.mips[0][f] = Image(size, size, 4, 1.0f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        cube.mips[0][f].set_rgb(x, y, {1.0f + f + 0.37f * x, 2.0f + 0.11f * y * x, 0.5f + f * y});
  }
  build_mip_chain(cube, 1);
  return cube;
}

// Directions through face centres, edges, corners and in between, and off-axis ones.
std::vector<glm::vec3> probe_directions() {
  std::vector<glm::vec3> out;
  for (int f = 0; f < 6; ++f)
    for (float s : {0.0f, 0.03f, 0.5f, 0.77f, 1.0f})
      for (float t : {0.0f, 0.41f, 0.5f, 1.0f}) out.push_back(cube_direction(f, {s, t}));
  for (int i = 0; i < 64; ++i) {
    const float z = 1.0f - 2.0f * (i + 0.5f) / 64.0f, phi = 2.39996f * float(i);
    const float r = std::sqrt(1.0f - z * z);
    out.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return out;
}

TEST(PrefilterKernels, CubeFacePointIsAffineAndNormalisesToTheDirection) {
  for (int f = 0; f < 6; ++f)
    for (float t : {0.1f, 0.6f}) {
      const glm::vec3 p0 = cube_face_point(f, {0.0f, t}), p1 = cube_face_point(f, {1.0f, t});
      for (float s : {0.0f, 0.25f, 0.9f}) {
        const glm::vec3 p = cube_face_point(f, {s, t});
        EXPECT_LT(glm::length(p - (p0 + s * (p1 - p0))), 1e-6f);
        EXPECT_LT(glm::length(glm::normalize(p) - cube_direction(f, {s, t})), 1e-6f);
      }
    }
}

TEST(PrefilterKernels, QuadratureSumsSkipOnlyTexelsBehind) {
  for (int size : {1, 2, 4, 8, 16, 64}) {
    const Cubemap cube = varied_cube(size);
    const detail::QuadratureSource q = detail::flatten_level(cube, 0);
    ASSERT_EQ(q.x.size(), std::size_t(6) * size * size);
    for (const glm::vec3 R : probe_directions())
      for (float alpha : {0.04f, 0.36f, 1.0f})
        for (float cos_max : {2.0f, 0.9f}) {
          // Every texel's term as the kernel computes it (float), summed in double.
          glm::dvec4 ref(0.0);
          glm::dvec3 cosine(0.0);
          for (std::size_t i = 0; i < q.x.size(); ++i) {
            const float c = R.x * q.x[i] + R.y * q.y[i] + R.z * q.z[i];
            if (c <= 0.0f) continue;
            cosine += double(c) * glm::dvec3(q.r[i], q.g[i], q.b[i]);
            if (c >= cos_max) continue;
            const float d = (0.5f + 0.5f * c) * (alpha * alpha - 1.0f) + 1.0f;
            ref += double(c / (d * d)) * glm::dvec4(q.r[i], q.g[i], q.b[i], q.omega[i]);
          }
          const glm::vec4 got = detail::quadrature_sums(q, alpha, R, cos_max);
          for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(got[k], ref[k], 1e-5 * std::abs(ref[k]) + 1e-9)
                << "size " << size << " alpha " << alpha << " k " << k;
          const glm::vec3 E = detail::cosine_sum(q, R);
          for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(E[k], cosine[k], 1e-5 * std::abs(cosine[k]) + 1e-9) << "size " << size;
        }
  }
}

TEST(PrefilterKernels, SampleSumMatchesScalarLookups) {
  const Cubemap cube = varied_cube(128);  // FIS reads levels 0 to 3 (down to 16 px)
  for (float roughness : {0.1f, 0.4f, 1.0f}) {
    // Odd counts exercise the padding; the cone restriction gives lods of all sizes.
    for (int n : {61, 256}) {
      const auto samples =
          prefilter_samples(roughness, n, cube.size(0), cube.levels(), true, 0.0f, 0.9f);
      const detail::SampleSet set = detail::make_sample_set(samples, cube);
      EXPECT_EQ(set.x.size() % simd::kLanes, 0u);
      for (const glm::vec3 R : probe_directions()) {
        const Frame frame(R);
        glm::dvec3 ref(0.0);
        for (const PrefilterSample& s : samples)
          ref += glm::dvec3(sample_cubemap(cube, frame.to_world(s.l), s.lod)) * double(s.weight);
        const glm::vec3 got = detail::sample_sum(cube, set, R);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(got[k], ref[k], 1e-5 * std::abs(ref[k])) << roughness << " " << n;
      }
    }
  }
}

}  // namespace
}  // namespace pbrkit
