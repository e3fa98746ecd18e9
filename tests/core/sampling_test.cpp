// Random numbers, low-discrepancy points and hemisphere/sphere warps (core/sampling.h):
// known values, net (stratification) properties and chi-square fits of every warp against
// its pdf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "pbrkit/core/sampling.h"
#include "pbrkit/core/sobol.h"
#include "support/chi2.h"

namespace pbrkit {
namespace {

constexpr double kPiD = std::numbers::pi;

TEST(Pcg32, MatchesReferenceImplementation) {
  // pcg32-demo of the reference C implementation (O'Neill), seeded with initstate 42 and
  // initseq 54: the first six outputs.
  Pcg32 rng(42u, 54u);
  const std::uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                    0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  for (std::uint32_t e : expected) EXPECT_EQ(rng.next_u32(), e);
}

TEST(Pcg32, ReproducibleAndInUnitInterval) {
  Pcg32 a(7, 3), b(7, 3), c(8, 3), d(7, 4);
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 10000; ++i) {
    const float x = a.next_float();
    EXPECT_EQ(x, b.next_float());
    same_c += x == c.next_float();
    same_d += x == d.next_float();
    EXPECT_GE(x, 0.0f);
    EXPECT_LT(x, 1.0f);
    const double y = a.next_double();
    EXPECT_EQ(y, b.next_double());
    c.next_double();
    d.next_double();
    EXPECT_GE(y, 0.0);
    EXPECT_LT(y, 1.0);
  }
  // Different seeds or streams give different sequences (a coincidence has p ~ 2^-24).
  EXPECT_LT(same_c, 5);
  EXPECT_LT(same_d, 5);
}

TEST(Pcg32, MeanAndVarianceOfUniforms) {
  Pcg32 rng(1234);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.next_float();
    sum += x;
    sum2 += x * x;
  }
  // Mean 1/2 (sd 0.29/sqrt(n) = 6.5e-4) and variance 1/12.
  EXPECT_NEAR(sum / n, 0.5, 4 * 6.5e-4);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 2e-3);
}

TEST(RadicalInverse, KnownValues) {
  EXPECT_EQ(radical_inverse_base2(0), 0.0f);
  EXPECT_EQ(radical_inverse_base2(1), 0.5f);
  EXPECT_EQ(radical_inverse_base2(2), 0.25f);
  EXPECT_EQ(radical_inverse_base2(3), 0.75f);
  EXPECT_EQ(radical_inverse_base2(4), 0.125f);
  EXPECT_EQ(radical_inverse_base2(5), 0.625f);
  EXPECT_EQ(radical_inverse_base2(6), 0.375f);
  EXPECT_EQ(radical_inverse_base2(7), 0.875f);
  EXPECT_EQ(radical_inverse_base2(11), 0.8125f);  // 1011b -> 0.1101b
  EXPECT_LT(radical_inverse_base2(0xffffffffu), 1.0f);
}

TEST(Hammersley, PointsAreAZeroTwoNet) {
  // n = 2^m Hammersley points in base 2 form a (0, m, 2)-net: every elementary interval
  // [a 2^-k, (a+1) 2^-k) x [b 2^-(m-k), (b+1) 2^-(m-k)) holds exactly one point.
  const int m = 10, n = 1 << m;
  for (int k = 0; k <= m; ++k) {
    std::vector<int> count(std::size_t(n), 0);
    for (int i = 0; i < n; ++i) {
      const glm::vec2 p = hammersley(std::uint32_t(i), std::uint32_t(n));
      EXPECT_EQ(p.x, float(i) / float(n));
      const int a = int(p.x * float(1 << k)), b = int(p.y * float(1 << (m - k)));
      ++count[std::size_t(a * (1 << (m - k)) + b)];
    }
    for (int c : count) ASSERT_EQ(c, 1) << "k = " << k;
  }
}

TEST(Sobol, FirstDimensionsKnownValues) {
  // Dimension 0 is the van der Corput sequence; dimension 1 starts 0, 1/2, 3/4, 1/4.
  for (std::uint32_t i = 0; i < 4096; ++i)
    EXPECT_EQ(double(sobol_u32(i, 0)) * 0x1p-32, double(radical_inverse_base2(i)));
  const double dim1[] = {0.0, 0.5, 0.75, 0.25};
  for (std::uint32_t i = 0; i < 4; ++i) EXPECT_EQ(double(sobol_u32(i, 1)) * 0x1p-32, dim1[i]);
}

// Counts of points per elementary interval of shape 2^-k x 2^-(m-k), m = log2(points).
bool is_zero_m_2_net(const std::vector<glm::dvec2>& points) {
  const int n = int(points.size());
  int m = 0;
  while ((1 << m) < n) ++m;
  for (int k = 0; k <= m; ++k) {
    std::vector<int> count(std::size_t(n), 0);
    for (const glm::dvec2& p : points) {
      const int a = int(p.x * (1 << k)), b = int(p.y * (1 << (m - k)));
      if (++count[std::size_t(a * (1 << (m - k)) + b)] > 1) return false;
    }
  }
  return true;
}

bool is_stratified_1d(const std::vector<double>& xs) {
  std::set<int> strata;
  for (double x : xs) strata.insert(int(x * double(xs.size())));
  return strata.size() == xs.size();
}

TEST(Sobol, DimensionsZeroAndOneAreAZeroTwoSequence) {
  // Every aligned block of 2^m points of Sobol dimensions (0, 1) is a (0, m, 2)-net, and
  // each of the four dimensions alone is a (0, 1)-sequence.
  for (int m = 0; m <= 8; ++m)
    for (std::uint32_t block = 0; block < 4; ++block) {
      std::vector<glm::dvec2> pts;
      std::vector<std::vector<double>> dims(4);
      for (std::uint32_t i = 0; i < (1u << m); ++i) {
        const std::uint32_t index = (block << m) + i;
        pts.emplace_back(sobol_u32(index, 0) * 0x1p-32, sobol_u32(index, 1) * 0x1p-32);
        for (std::uint32_t d = 0; d < 4; ++d) dims[d].push_back(sobol_u32(index, d) * 0x1p-32);
      }
      EXPECT_TRUE(is_zero_m_2_net(pts)) << "m = " << m << ", block " << block;
      for (int d = 0; d < 4; ++d)
        EXPECT_TRUE(is_stratified_1d(dims[std::size_t(d)])) << "dim " << d << ", m = " << m;
    }
}

TEST(Sobol, TablesEqualTheGeneratorMatrixProduct) {
  // sobol_u32 comes from byte tables built at compile time; check it against the plain
  // product of the generator matrices (Joe & Kuo's direction numbers for the first four
  // dimensions, built here independently) over all index bits.
  std::uint32_t v[4][32];
  for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
  const int degree[3] = {1, 2, 3};
  const std::uint32_t coeffs[3] = {0, 1, 1};
  const std::uint32_t m_init[3][3] = {{1, 0, 0}, {1, 3, 0}, {1, 3, 1}};
  for (int d = 1; d < 4; ++d) {
    const int s = degree[d - 1];
    for (int k = 0; k < s; ++k) v[d][k] = m_init[d - 1][k] << (31 - k);
    for (int k = s; k < 32; ++k) {
      std::uint32_t x = v[d][k - s] ^ (v[d][k - s] >> s);
      for (int j = 1; j < s; ++j)
        if ((coeffs[d - 1] >> (s - 1 - j)) & 1u) x ^= v[d][k - j];
      v[d][k] = x;
    }
  }
  Pcg32 rng(8);
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t index = i < 4096 ? std::uint32_t(i) : rng.next_u32();
    for (std::uint32_t d = 0; d < 4; ++d) {
      std::uint32_t x = 0;
      for (int k = 0; k < 32; ++k)
        if ((index >> k) & 1u) x ^= v[d][k];
      ASSERT_EQ(sobol_u32(index, d), x) << "index " << index << ", dim " << d;
    }
  }
}

TEST(NestedUniformScramble, IsAPermutationPreservingStrata) {
  // An Owen scramble maps each dyadic interval onto a dyadic interval of the same size:
  // the images of the 2^k strata are again the 2^k strata (a bijection of them).
  for (std::uint32_t seed : {1u, 77u, 0xdeadbeefu}) {
    for (int k = 1; k <= 12; ++k) {
      std::set<std::uint32_t> image;
      for (std::uint32_t s = 0; s < (1u << k); ++s) {
        const std::uint32_t x = s << (32 - k);
        const std::uint32_t y = nested_uniform_scramble(x, seed) >> (32 - k);
        // Every point in stratum s maps to the same stratum.
        EXPECT_EQ(nested_uniform_scramble(x | ((1u << (32 - k)) - 1u), seed) >> (32 - k), y);
        image.insert(y);
      }
      EXPECT_EQ(image.size(), std::size_t(1) << k);
    }
  }
}

TEST(OwenSobolSampler, InUnitIntervalAndDeterministic) {
  const OwenSobolSampler a(5), b(5), c(6);
  int differ_seed = 0;
  for (std::uint32_t pixel = 0; pixel < 16; ++pixel)
    for (std::uint32_t i = 0; i < 64; ++i)
      for (std::uint32_t d = 0; d < 10; ++d) {
        const float x = a.sample(pixel, i, d);
        EXPECT_GE(x, 0.0f);
        EXPECT_LT(x, 1.0f);
        EXPECT_EQ(x, a.sample(pixel, i, d));
        EXPECT_EQ(x, b.sample(pixel, i, d));
        differ_seed += x != c.sample(pixel, i, d);
      }
  EXPECT_GT(differ_seed, 16 * 64 * 10 * 99 / 100);
}

TEST(OwenSobolSampler, BlocksAndPixelSequencesEqualSample) {
  // sample_block (a 4D block at once) and OwenSobolPixel (seeds cached per pixel, for the
  // first blocks; hashed per call beyond) return exactly sample()'s values, and
  // sample() is Burley's construction written out.
  const OwenSobolSampler s(3);
  Pcg32 rng(4);
  for (std::uint32_t pixel : {0u, 1u, 777u, 65535u}) {
    OwenSobolPixel seq(s, pixel);
    for (int n = 0; n < 400; ++n) {
      const std::uint32_t index = n < 64 ? std::uint32_t(n) : rng.next_u32() >> (n % 20);
      const std::uint32_t block = std::uint32_t(n % 31);  // past the 24 cached blocks too
      const glm::vec4 a = s.sample_block(s.pixel_seed(pixel), index, block);
      const glm::vec4 b = seq.sample_block(index, block);
      for (int d = 0; d < 4; ++d) {
        const float x = s.sample(pixel, index, 4 * block + std::uint32_t(d));
        EXPECT_EQ(a[d], x);
        EXPECT_EQ(b[d], x);
      }
    }
  }
}

TEST(OwenSobolSampler, EqualsThePlainConstruction) {
  // The sampler written plainly (Burley 2020, with this project's seed hashing: lowbias32
  // and a boost-style combine): dimension d of sample i in block b of a pixel is
  //   nested_uniform_scramble(sobol(nested_uniform_scramble(i, seed_b), d), seed_bd),
  //   seed_b = combine(combine(seed, pixel), b),  seed_bd = combine(seed_b, d + 1).
  // The table-driven, block-at-a-time implementation must give exactly these values.
  auto hash32 = [](std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
  };
  auto combine = [&](std::uint32_t seed, std::uint32_t v) {
    return hash32(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
  };
  const std::uint32_t seed = 21;
  const OwenSobolSampler s(seed);
  Pcg32 rng(6);
  for (int n = 0; n < 3000; ++n) {
    const std::uint32_t pixel = rng.next_u32() % 100000u;
    const std::uint32_t index = n % 2 ? rng.next_u32() % 4096u : rng.next_u32();
    const std::uint32_t dim = rng.next_u32() % 80u;
    const std::uint32_t block_seed = combine(combine(seed, pixel), dim / 4);
    const std::uint32_t shuffled = nested_uniform_scramble(index, block_seed);
    const std::uint32_t x =
        nested_uniform_scramble(sobol_u32(shuffled, dim % 4), combine(block_seed, dim % 4 + 1));
    const float expected = std::min(float(x >> 8) * 0x1p-24f, kOneMinusEpsilon);
    ASSERT_EQ(s.sample(pixel, index, dim), expected) << pixel << " " << index << " " << dim;
  }
}

TEST(OwenSobolSampler, DecorrelatedBetweenPixels) {
  const OwenSobolSampler s(0);
  // Same (index, dim), neighbouring pixels: values differ and are uniformly spread.
  int equal = 0;
  double sum = 0.0;
  const int pixels = 4096;
  for (int p = 0; p < pixels; ++p) {
    const float x = s.sample(std::uint32_t(p), 0, 0);
    equal += x == s.sample(std::uint32_t(p + 1), 0, 0);
    sum += x;
  }
  EXPECT_LT(equal, 3);
  // Mean of U(0,1) over 4096 pixels: sd = sqrt(1/12/4096) = 0.0045.
  EXPECT_NEAR(sum / pixels, 0.5, 4 * 0.0045);
  // Whole sequences of different pixels differ.
  int same_sequence = 0;
  for (std::uint32_t i = 0; i < 32; ++i) same_sequence += s.sample(3, i, 1) == s.sample(4, i, 1);
  EXPECT_LT(same_sequence, 2);
}

TEST(OwenSobolSampler, PrefixesAreStratified) {
  // Each power-of-two prefix of 2^k samples: dims (0, 1) and (4, 5) (two padded 4D blocks)
  // form (0, k, 2)-nets, and every dimension has one point per 1/2^k strip.
  const OwenSobolSampler s(11);
  for (std::uint32_t pixel : {0u, 1u, 12345u})
    for (int k = 0; k <= 10; ++k) {
      const std::uint32_t n = 1u << k;
      for (std::uint32_t dim : {0u, 4u}) {
        std::vector<glm::dvec2> pts;
        for (std::uint32_t i = 0; i < n; ++i) pts.emplace_back(s.sample_2d(pixel, i, dim));
        EXPECT_TRUE(is_zero_m_2_net(pts)) << "pixel " << pixel << ", k " << k << ", dim " << dim;
      }
      for (std::uint32_t dim = 0; dim < 8; ++dim) {
        std::vector<double> xs;
        for (std::uint32_t i = 0; i < n; ++i) xs.push_back(s.sample(pixel, i, dim));
        EXPECT_TRUE(is_stratified_1d(xs)) << "pixel " << pixel << ", k " << k << ", dim " << dim;
      }
    }
}

TEST(ConcentricDisk, MapsSquareRingsToCirclesPreservingArea) {
  // Shirley & Chiu 1997: the square ring max(|x|, |y|) = s (o = 2u - 1) maps onto the
  // circle of radius s, and the angle is linear along each edge: for x > |y| it is
  // (pi / 4) y / x. Radius and angle together make the map area preserving.
  EXPECT_EQ(sample_concentric_disk({0.5f, 0.5f}), glm::vec2(0.0f));
  Pcg32 rng(3);
  std::vector<int> ring(8, 0);
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 u = rng.next_2d();
    const glm::vec2 o = 2.0f * u - 1.0f;
    const glm::vec2 d = sample_concentric_disk(u);
    const float r = glm::length(d);
    ASSERT_NEAR(r, std::max(std::abs(o.x), std::abs(o.y)), 1e-5f);
    if (o.x > std::abs(o.y)) {
      ASSERT_NEAR(std::atan2(d.y, d.x), kPiD / 4 * o.y / o.x, 1e-5);
    }
    ++ring[std::size_t(std::min(7, int(r * r * 8)))];
  }
  // Uniform on the disk: P(r^2 in [k/8, (k+1)/8)) = 1/8; binomial sd 3.3e-4.
  for (int c : ring) EXPECT_NEAR(double(c) / n, 1.0 / 8.0, 5 * 3.3e-4);
  EXPECT_FLOAT_EQ(concentric_disk_pdf(), float(1.0 / kPiD));
}

// The family of warp chi-square tests shares one Sidak correction.
constexpr int kWarpRuns = 3;

test::Chi2Options warp_options() {
  test::Chi2Options o;
  o.runs = kWarpRuns;
  return o;
}

// `pdf` is the warp's density written out in the test (not the library's *_pdf function):
// the returned pdf must equal it at every sample, and the histogram must follow it.
template <typename Sampler, typename Pdf>
void expect_warp_matches_pdf(Sampler sampler, Pdf pdf, double mass = 1.0) {
  Pcg32 rng(99);
  for (int i = 0; i < 1000; ++i) {
    const DirectionSample s = sampler(rng.next_2d());
    EXPECT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
    EXPECT_NEAR(s.pdf, pdf(s.direction), 1e-6 * pdf(s.direction));
  }
  const test::Chi2Result r = test::chi2_sphere_test(
      [&](float, glm::vec2 u) -> std::optional<glm::vec3> { return sampler(u).direction; },
      [&](glm::vec3 w) { return double(pdf(w)); }, warp_options());
  EXPECT_NEAR(r.pdf_integral, mass, 1e-6);
  EXPECT_TRUE(r.passed) << r.report;
}

TEST(Warps, UniformHemisphereChi2) {
  EXPECT_FLOAT_EQ(uniform_hemisphere_pdf(), float(1.0 / (2.0 * kPiD)));
  expect_warp_matches_pdf(sample_uniform_hemisphere,
                          [](glm::vec3 w) { return w.z >= 0.0f ? 1.0 / (2.0 * kPiD) : 0.0; });
}

TEST(Warps, CosineHemisphereChi2) {
  // cos(theta) / pi above the horizon, 0 below.
  for (float c : {-0.5f, 0.0f, 0.1f, 0.7f, 1.0f})
    EXPECT_NEAR(cosine_hemisphere_pdf(c), c > 0.0f ? c / kPiD : 0.0, 1e-7) << c;
  expect_warp_matches_pdf(sample_cosine_hemisphere,
                          [](glm::vec3 w) { return w.z > 0.0f ? double(w.z) / kPiD : 0.0; });
}

TEST(Warps, UniformSphereChi2) {
  EXPECT_FLOAT_EQ(uniform_sphere_pdf(), float(1.0 / (4.0 * kPiD)));
  expect_warp_matches_pdf(sample_uniform_sphere, [](glm::vec3) { return 1.0 / (4.0 * kPiD); });
}

}  // namespace
}  // namespace pbrkit
