#include "pbrkit/core/sampling.h"

#include <array>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pbrkit/core/math.h"
#include "pbrkit/core/sobol.h"

namespace pbrkit {

float Pcg32::next_float() {
  // 24 high-quality bits -> exactly representable floats in [0, 1).
  return float(next_u32() >> 8) * 0x1p-24f;
}

double Pcg32::next_double() {
  const std::uint64_t hi = next_u32(), lo = next_u32();
  return double(((hi << 32) | lo) >> 11) * 0x1p-53;
}

namespace {

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

}  // namespace

float radical_inverse_base2(std::uint32_t i) {
  // Keep 24 bits: float(reverse_bits(i)) rounds values above 2^32 - 2^7 up to 2^32, which
  // made the result 1.0 (e.g. i = 0xffffffff) although it must lie in [0, 1). Identical to
  // the old result whenever i < 2^24 (every Hammersley set the library builds).
  return float(reverse_bits(i) >> 8) * 0x1p-24f;
}

glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
  return {float(i) / float(n), radical_inverse_base2(i)};
}

namespace {

// Sobol generator matrices (direction numbers) for the first four dimensions, from the
// primitive polynomials and initial m_k of Joe & Kuo's "new-joe-kuo-6.21201" table:
// dim 0 is van der Corput; dim 1: s=1, a=0, m={1}; dim 2: s=2, a=1, m={1,3};
// dim 3: s=3, a=1, m={1,3,1}.
using SobolMatrices = std::array<std::array<std::uint32_t, 32>, 4>;

constexpr SobolMatrices make_sobol_matrices() {
  SobolMatrices v{};
  for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
  struct Poly {
    int s;
    std::uint32_t a;
    std::array<std::uint32_t, 3> m;
  };
  const Poly polys[3] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
  for (int d = 1; d < 4; ++d) {
    const Poly& p = polys[d - 1];
    auto& dv = v[d];
    for (int k = 0; k < p.s; ++k) dv[k] = p.m[k] << (31 - k);
    for (int k = p.s; k < 32; ++k) {
      std::uint32_t x = dv[k - p.s] ^ (dv[k - p.s] >> p.s);
      for (int j = 1; j < p.s; ++j)
        if ((p.a >> (p.s - 1 - j)) & 1u) x ^= dv[k - j];
      dv[k] = x;
    }
  }
  return v;
}

// The Sobol matrix-vector product as byte tables (a standard speed-up of the bit loop,
// e.g. Keller & Grünschloß 2012), arranged for Burley's scramble, which works on
// bit-reversed values: for the reversed index r = reverse(i) and each dimension d,
//   reverse(sobol(i, d)) = T[0][r & 255][d] ^ T[1][(r >> 8) & 255][d] ^ ...
// Both reversals are folded into the tables, so the scrambles below need no reversal of
// their input; all four dimensions come from one 16-byte row. 16 KiB, built at compile time.
using SobolTables = std::array<std::array<std::array<std::uint32_t, 4>, 256>, 4>;

constexpr SobolTables make_sobol_tables() {
  const SobolMatrices v = make_sobol_matrices();
  SobolTables t{};
  for (int j = 0; j < 4; ++j)
    for (int byte = 0; byte < 256; ++byte)
      for (int d = 0; d < 4; ++d) {
        std::uint32_t x = 0;
        // Bit b of byte j of r is bit 31 - 8 j - b of the index.
        for (int b = 0; b < 8; ++b)
          if ((byte >> b) & 1) x ^= reverse_bits(v[d][31 - 8 * j - b]);
        t[j][byte][d] = x;
      }
  return t;
}

alignas(64) constexpr SobolTables kSobolTables = make_sobol_tables();

// reverse(sobol(reverse(r), d)) for the four dimensions d at once.
inline std::array<std::uint32_t, 4> sobol_reversed(std::uint32_t r) {
  std::array<std::uint32_t, 4> x = kSobolTables[0][r & 255u];
  for (int j = 1; j < 4; ++j) {
    const auto& row = kSobolTables[j][(r >> (8 * j)) & 255u];
    for (int d = 0; d < 4; ++d) x[d] ^= row[d];
  }
  return x;
}

// Chris Wellons' "lowbias32" integer hash: a cheap, well-mixed 32-bit finaliser.
inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

inline std::uint32_t hash_combine(std::uint32_t seed, std::uint32_t v) {
  return hash32(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

// Burley 2020, listing 3: the Laine-Karras style hash that acts as an Owen scramble on
// bit-reversed input (each bit flipped by a hash of the bits below it).
inline std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// The scalar fallback's conversion (scrambled_block uses SSE2 where it can; clang warns
// about the unused function there).
[[maybe_unused]] inline float to_unit_float(std::uint32_t x) {
  return std::min(float(x >> 8) * 0x1p-24f, kOneMinusEpsilon);
}

}  // namespace

std::uint32_t sobol_u32(std::uint32_t index, std::uint32_t dim) {
  return reverse_bits(sobol_reversed(reverse_bits(index))[dim & 3u]);
}

std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

std::uint32_t OwenSobolSampler::pixel_seed(std::uint32_t pixel_id) const {
  return hash_combine(seed_, pixel_id);
}

namespace {

// The seeds of one block of one pixel: the block's (index shuffle) and one per dimension.
inline void block_seeds(std::uint32_t pixel_seed, std::uint32_t block, std::uint32_t& block_seed,
                        std::uint32_t dims[4]) {
  block_seed = hash_combine(pixel_seed, block);
  for (std::uint32_t d = 0; d < 4; ++d) dims[d] = hash_combine(block_seed, d + 1u);
}

#if defined(__SSE2__)
// SSE2 (the x86-64 baseline) has no 32-bit lane multiply (pmulld is SSE4.1): two
// 32 x 32 -> 64-bit products (lanes 0, 2 and 1, 3), low halves merged.
inline __m128i mullo32(__m128i a, __m128i b) {
  const __m128i even = _mm_mul_epu32(a, b);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
  return _mm_or_si128(_mm_and_si128(even, _mm_set_epi32(0, -1, 0, -1)), _mm_slli_epi64(odd, 32));
}

inline __m128i swap_bits(__m128i x, int shift, int mask) {
  const __m128i m = _mm_set1_epi32(mask);
  return _mm_or_si128(_mm_and_si128(_mm_srli_epi32(x, shift), m),
                      _mm_slli_epi32(_mm_and_si128(x, m), shift));
}

inline __m128i reverse_bits4(__m128i x) {
  x = swap_bits(x, 1, 0x55555555);
  x = swap_bits(x, 2, 0x33333333);
  x = swap_bits(x, 4, 0x0f0f0f0f);
  x = swap_bits(x, 8, 0x00ff00ff);
  return _mm_or_si128(_mm_srli_epi32(x, 16), _mm_slli_epi32(x, 16));
}

inline __m128i laine_karras_permutation4(__m128i x, __m128i seed) {
  x = _mm_add_epi32(x, seed);
  for (std::uint32_t c : {0x6c50b47cu, 0xb82f1e52u, 0xc7afe638u, 0x8d22f6e6u})
    x = _mm_xor_si128(x, mullo32(x, _mm_set1_epi32(int(c))));
  return x;
}
#endif

// Dimensions come in 4D Sobol blocks; each block has its own seed ("padding"), and the
// index shuffle is shared inside a block so the 4D stratification is kept (Burley 2020,
// section 4). In Burley's terms the value of dimension d is
//   nested_uniform_scramble(sobol(nested_uniform_scramble(index, block_seed), d), seed_d);
// written out with the reversals cancelled against the tables'. The four dimensions are
// computed side by side in SSE2 lanes where available (the same integer operations).
inline glm::vec4 scrambled_block(std::uint32_t index, std::uint32_t block_seed,
                                 const std::uint32_t dims[4]) {
  const std::uint32_t r = laine_karras_permutation(reverse_bits(index), block_seed);
#if defined(__SSE2__)
  __m128i x = _mm_load_si128(reinterpret_cast<const __m128i*>(kSobolTables[0][r & 255u].data()));
  for (int j = 1; j < 4; ++j)
    x = _mm_xor_si128(x, _mm_load_si128(reinterpret_cast<const __m128i*>(
                             kSobolTables[j][(r >> (8 * j)) & 255u].data())));
  x = laine_karras_permutation4(x, _mm_loadu_si128(reinterpret_cast<const __m128i*>(dims)));
  x = _mm_srli_epi32(reverse_bits4(x), 8);
  // to_unit_float: 24 bits convert exactly (as signed), and (2^24 - 1) 2^-24 is already
  // kOneMinusEpsilon.
  glm::vec4 out;
  _mm_storeu_ps(&out[0], _mm_mul_ps(_mm_cvtepi32_ps(x), _mm_set1_ps(0x1p-24f)));
  return out;
#else
  const std::array<std::uint32_t, 4> x = sobol_reversed(r);
  glm::vec4 out;
  for (int d = 0; d < 4; ++d)
    out[d] = to_unit_float(reverse_bits(laine_karras_permutation(x[std::size_t(d)], dims[d])));
  return out;
#endif
}

}  // namespace

glm::vec4 OwenSobolSampler::sample_block(std::uint32_t pixel_seed, std::uint32_t index,
                                         std::uint32_t block) const {
  std::uint32_t block_seed, dims[4];
  block_seeds(pixel_seed, block, block_seed, dims);
  return scrambled_block(index, block_seed, dims);
}

OwenSobolPixel::OwenSobolPixel(const OwenSobolSampler& sampler, std::uint32_t pixel_id)
    : pixel_seed_(sampler.pixel_seed(pixel_id)) {}

glm::vec4 OwenSobolPixel::sample_block(std::uint32_t index, std::uint32_t block) {
  if (block >= kCachedBlocks) {
    std::uint32_t block_seed, dims[4];
    block_seeds(pixel_seed_, block, block_seed, dims);
    return scrambled_block(index, block_seed, dims);
  }
  for (; cached_ <= block; ++cached_)
    block_seeds(pixel_seed_, cached_, seeds_[cached_].block, seeds_[cached_].dims);
  return scrambled_block(index, seeds_[block].block, seeds_[block].dims);
}

float OwenSobolSampler::sample(std::uint32_t pixel_id, std::uint32_t index,
                               std::uint32_t dim) const {
  return sample_block(pixel_seed(pixel_id), index, dim >> 2)[int(dim & 3u)];
}

glm::vec2 sample_concentric_disk(glm::vec2 u) {
  // Shirley & Chiu 1997: maps concentric squares to concentric circles (area preserving).
  const glm::vec2 o = 2.0f * u - 1.0f;
  if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * glm::vec2(std::cos(theta), std::sin(theta));
}

DirectionSample sample_uniform_hemisphere(glm::vec2 u) {
  const float z = u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {{r * std::cos(phi), r * std::sin(phi), z}, kInv2Pi};
}

float uniform_hemisphere_pdf() {
  return kInv2Pi;
}

DirectionSample sample_cosine_hemisphere(glm::vec2 u) {
  // Malley's method: project uniform disk points up to the hemisphere.
  const glm::vec2 d = sample_concentric_disk(u);
  const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
  return {{d.x, d.y, z}, z * kInvPi};
}

float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f;
}

DirectionSample sample_uniform_sphere(glm::vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {{r * std::cos(phi), r * std::sin(phi), z}, kInv4Pi};
}

float uniform_sphere_pdf() {
  return kInv4Pi;
}

}  // namespace pbrkit
