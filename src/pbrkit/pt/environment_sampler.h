#pragma once
// Importance sampling of an equirectangular environment (pbrt-v3 section 14.2.4): a
// piecewise-constant 2D distribution over the map's texels with weights luminance x
// sin(theta), sampled in (u, v) and mapped to directions with the project's one
// orientation convention (core/equirect.h), including the environment's rotation, so that
// pdf() is the density of sample() with respect to solid angle and matches what
// Environment::eval returns for the same direction.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/environment.h"

namespace pbrkit {

/// A piecewise-constant 1D distribution on [0,1) (pbrt's Distribution1D).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<float> weights);
  /// Continuous sample in [0,1); `pdf` (density on [0,1)) and `index` are returned too.
  float sample(float u, float& pdf, std::size_t& index) const;
  /// Discrete sample: the index, with probability weight / total.
  std::size_t sample_discrete(float u, float& probability) const;
  float pdf(std::size_t index) const;  ///< density of the continuous sample in bin index
  float probability(std::size_t index) const { return pdf(index) / float(size()); }
  std::size_t size() const { return weights_.size(); }
  double total() const { return total_; }

 private:
  std::vector<float> weights_;
  std::vector<float> cdf_;  ///< size() + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  float inv_total_ = 0.0f;
  /// guide_[k]: the bin containing u = k / size(), where the search for u starts (a guide
  /// table, Chen & Asau 1974): one or two steps instead of a binary search.
  std::vector<std::uint32_t> guide_;
  double total_ = 0.0;
};

class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const Environment& env);

  struct Sample {
    glm::vec3 direction{0.0f};  ///< world space, unit
    glm::vec3 radiance{0.0f};   ///< env.eval(direction)
    float pdf = 0.0f;           ///< solid angle
  };
  Sample sample(glm::vec2 u) const;
  /// Solid-angle density of sample() at world direction `d` (unit).
  float pdf(glm::vec3 d) const;
  /// Average radiance luminance over the sphere (for light selection by power).
  float mean_luminance() const { return mean_luminance_; }

 private:
  const Environment& env_;
  int width_ = 0, height_ = 0;
  Distribution1D marginal_;                  ///< over rows
  std::vector<Distribution1D> conditional_;  ///< per row, over columns
  float mean_luminance_ = 0.0f;
};

}  // namespace pbrkit
