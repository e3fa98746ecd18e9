#pragma once
// Random numbers, low-discrepancy points and warps from [0,1)^2 to directions.
// Every warp returns its pdf (with respect to solid angle for directions, area for the
// disk), following pbrt-v4's convention that a sampling routine and its density travel
// together.
#include <cstdint>

#include <glm/glm.hpp>
#include <pcg_random.hpp>

namespace pbrkit {

/// PCG32 (O'Neill 2014) through Debian's libpcg-cpp; a thin wrapper so callers see only
/// uniform floats. Deterministic for a given (seed, stream).
class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed = 0x853c49e6748fea9bULL,
                 std::uint64_t stream = 0xda3e39cb94b95bdbULL)
      : rng_(seed, stream) {}
  std::uint32_t next_u32() { return rng_(); }
  /// Uniform in [0, 1), 24 random bits (never returns 1.0f).
  float next_float();
  double next_double();
  glm::vec2 next_2d() {
    const float a = next_float();
    return {a, next_float()};
  }

 private:
  pcg32 rng_;
};

/// Largest float below 1: samples are clamped to this so warps never see u == 1.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

/// Van der Corput radical inverse in base 2 (bit reversal) of i, in [0,1).
float radical_inverse_base2(std::uint32_t i);
/// Point i of an n-point Hammersley set: (i / n, radical_inverse_base2(i)).
glm::vec2 hammersley(std::uint32_t i, std::uint32_t n);

/// Owen-scrambled Sobol sampler (Burley 2020, "Practical Hash-based Owen Scrambling",
/// JCGT 9(4)). Each pixel gets its own decorrelated progressive sequence: the sample index
/// is shuffled by a nested uniform scramble seeded by the pixel, and each dimension is
/// Owen-scrambled with its own seed. Dimensions are drawn in 4D Sobol blocks padded with
/// different seeds ("dimension padding"), so any number of dimensions is available.
/// Deterministic: sample(pixel, index, dim) depends on nothing else, which makes renders
/// independent of thread count and splittable into sample ranges.
///
/// Renderers should draw whole blocks with sample_block(): the index shuffle and the Sobol
/// matrix product are shared by the block's four dimensions (the values are exactly those
/// of sample()).
class OwenSobolSampler {
 public:
  explicit OwenSobolSampler(std::uint32_t seed = 0) : seed_(seed) {}
  /// Value of dimension `dim` of sample `index` for pixel `pixel_id`, in [0,1).
  float sample(std::uint32_t pixel_id, std::uint32_t index, std::uint32_t dim) const;
  glm::vec2 sample_2d(std::uint32_t pixel_id, std::uint32_t index, std::uint32_t dim) const {
    return {sample(pixel_id, index, dim), sample(pixel_id, index, dim + 1)};
  }
  /// The seed of pixel `pixel_id`'s sequence (what sample_block takes; hoist it out of
  /// the sample loop).
  std::uint32_t pixel_seed(std::uint32_t pixel_id) const;
  /// Dimensions 4 block .. 4 block + 3 of sample `index` of the pixel whose pixel_seed()
  /// is `pixel_seed`: component k equals sample(pixel_id, index, 4 block + k).
  glm::vec4 sample_block(std::uint32_t pixel_seed, std::uint32_t index, std::uint32_t block) const;
  std::uint32_t seed() const { return seed_; }

 private:
  std::uint32_t seed_;
};

/// One pixel's sequence of an OwenSobolSampler, for a renderer's sample loop (one object
/// per pixel, or per pixel and pass). A block's five hashed seeds (the block's, for the
/// index shuffle, and one per dimension) depend on the pixel and the block only, so they
/// are hashed once, on first use, for the first kCachedBlocks blocks, instead of once per
/// sample. sample_block() returns exactly OwenSobolSampler's values.
class OwenSobolPixel {
 public:
  OwenSobolPixel(const OwenSobolSampler& sampler, std::uint32_t pixel_id);
  /// Dimensions 4 block .. 4 block + 3 of sample `index`.
  glm::vec4 sample_block(std::uint32_t index, std::uint32_t block);

 private:
  static constexpr std::uint32_t kCachedBlocks = 24;
  struct BlockSeeds {
    std::uint32_t block;
    std::uint32_t dims[4];
  };
  std::uint32_t pixel_seed_;
  std::uint32_t cached_ = 0;  ///< blocks [0, cached_) are in seeds_
  BlockSeeds seeds_[kCachedBlocks];
};

/// A direction and its pdf.
struct DirectionSample {
  glm::vec3 direction;
  float pdf;  ///< with respect to solid angle
};

/// Concentric mapping of the square to the unit disk (Shirley & Chiu 1997); pdf = 1/pi.
glm::vec2 sample_concentric_disk(glm::vec2 u);
inline constexpr float concentric_disk_pdf() {
  return 0.31830988618379067154f;
}

/// Uniform hemisphere about +Z; pdf = 1/(2 pi).
DirectionSample sample_uniform_hemisphere(glm::vec2 u);
float uniform_hemisphere_pdf();

/// Cosine-weighted hemisphere about +Z (Malley's method); pdf = cos(theta)/pi.
DirectionSample sample_cosine_hemisphere(glm::vec2 u);
float cosine_hemisphere_pdf(float cos_theta);

/// Uniform sphere; pdf = 1/(4 pi).
DirectionSample sample_uniform_sphere(glm::vec2 u);
float uniform_sphere_pdf();

}  // namespace pbrkit
