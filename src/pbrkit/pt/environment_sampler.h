#pragma once
// Importance sampling of an equirectangular environment (pbrt-v3 section 14.2.4): a
// piecewise-constant 2D distribution over the map's texels with weights luminance x
// sin(theta), sampled in (u, v) and mapped to directions with the project's one
// orientation convention (core/equirect.h), including the environment's rotation, so that
// pdf() is the density of sample() with respect to solid angle and matches what
// Environment::eval returns for the same direction.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/math.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/fast_atan.h"

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
  std::size_t size() const { return guide_.size(); }
  double total() const { return total_; }
  /// The normalised CDF at the start of bin i (i <= size(); cdf(size()) = 1).
  float cdf(std::size_t i) const { return bins_[i].cdf; }

 private:
  /// Bin i's CDF value (the start of its interval) beside its weight: a sample reads
  /// cdf[i], cdf[i + 1] and weight[i], which this layout keeps in one cache line (large
  /// distributions, such as many emissive triangles, do not fit in the caches).
  struct Bin {
    float cdf;
    float weight;
  };
  std::vector<Bin> bins_;  ///< size() + 1 entries, cdf 0 first and 1 last (weight 0)
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

  /// Where a direction falls in the map: the bilinear footprint of its (u, v)
  /// (core/equirect.h's convention, after the rotation), the texel that contains it, and
  /// sin(theta); everything eval() needs, so that the conversion can be done (and the
  /// texels prefetched) before a ray is traced and reused after it missed.
  struct Location {
    const glm::vec4* texel = nullptr;       ///< footprint's first texel; next: +1, +stride
    const glm::vec4* containing = nullptr;  ///< the texel containing (u, v) (its pdf)
    float fx = 0.0f, fy = 0.0f;             ///< bilinear weights
    float sin_theta = 0.0f;
  };
  /// The location of map coordinates `uv` in [0, 1]^2 with the given sin(theta).
  Location at(glm::vec2 uv, float sin_theta) const {
    Location l;
    // Environment::eval's bilinear lookup, texel centres at (i + 0.5) / size: the
    // footprint starts at texel floor(u w - 0.5), which in the padded table (one border
    // texel before the first) is column int(u w + 0.5); likewise for rows. The clamps
    // only guard against NaN (and u or v slightly outside [0, 1]).
    float xs = uv.x * fw_ + 0.5f, ys = uv.y * fh_ + 0.5f;
    xs = xs > 0.0f ? std::min(xs, fw_ + 0.5f) : 0.0f;
    ys = ys > 0.0f ? std::min(ys, fh_ + 0.5f) : 0.0f;
    const int xi = int(xs), yi = int(ys);
    l.fx = xs - float(xi);
    l.fy = ys - float(yi);
    l.texel = texels_.data() + std::size_t(yi) * stride_ + std::size_t(xi);
    // The containing texel: column floor(u w), row floor(v h), one of the footprint's.
    const int xc = std::min(int(xs - 0.5f), width_ - 1), yc = std::min(int(ys - 0.5f), height_ - 1);
    l.containing = texels_.data() + std::size_t(yc + 1) * stride_ + std::size_t(xc + 1);
    l.sin_theta = sin_theta;
    return l;
  }
  /// equirect_uv(world_to_env(d, rotation)), with the rotation's sine and cosine computed
  /// once and fast_atan2 for libm's atan2 and acos (within 4e-7 rad, a thousandth of a
  /// texel of the largest map).
  Location locate(glm::vec3 d) const {
    const glm::vec3 local = to_env(d);
    // sqrt(x^2 + z^2) rather than sqrt(1 - y^2): no cancellation near the poles; and
    // theta = atan2(sin, cos) rather than acos(y), accurate everywhere. u = 1 (the seam)
    // needs no wrapping: the padded table's last column is the first.
    const float sin_theta = std::sqrt(local.x * local.x + local.z * local.z);
    const float u = 0.5f + fast_atan2(local.x, -local.z) * (0.5f * kInvPi);
    return at({u, fast_atan2(sin_theta, local.y) * kInvPi}, sin_theta);
  }
  /// Environment::eval at `l` (its bilinear lookup), and, unless `pdf` is null, pdf()
  /// there, from the same cache lines.
  glm::vec3 eval(const Location& l, float* pdf = nullptr) const {
    if (pdf) {
      // The containing texel's p(u, v) converted to solid angle.
      *pdf = l.sin_theta > 0.0f ? l.containing->w / (2.0f * kPi * kPi * l.sin_theta) : 0.0f;
    }
    const glm::vec4* row1 = l.texel + stride_;
    const glm::vec3 c = glm::mix(glm::mix(glm::vec3(l.texel[0]), glm::vec3(l.texel[1]), l.fx),
                                 glm::mix(glm::vec3(row1[0]), glm::vec3(row1[1]), l.fx), l.fy);
    return c * intensity_;
  }
  glm::vec3 eval(glm::vec3 d, float* pdf = nullptr) const { return eval(locate(d), pdf); }
  /// Starts loading what eval(l) reads (call it before tracing a ray that may escape,
  /// so the lookup after the miss finds the texels in cache).
  void prefetch(const Location& l) const {
    // Two texels of 16 bytes in each of two rows: one or two cache lines per row.
    __builtin_prefetch(l.texel);
    __builtin_prefetch(l.texel + 1);
    __builtin_prefetch(l.texel + stride_);
    __builtin_prefetch(l.texel + stride_ + 1);
  }
  /// Average radiance luminance over the sphere (for light selection by power).
  float mean_luminance() const { return mean_luminance_; }

 private:
  /// world_to_env(d, rotation) with the rotation's cosine and sine computed once.
  glm::vec3 to_env(glm::vec3 d) const {
    return {cos_rot_ * d.x + sin_rot_ * d.z, d.y, -sin_rot_ * d.x + cos_rot_ * d.z};
  }
  /// env_to_world(d, rotation), likewise.
  glm::vec3 to_world(glm::vec3 d) const {
    return {cos_inv_ * d.x + sin_inv_ * d.z, d.y, -sin_inv_ * d.x + cos_inv_ * d.z};
  }
  /// Samples a column of row `row` from p(u | v) by inverting the row's CDF (as
  /// Distribution1D::sample does): returns u in [0, 1) and the texel's p(u, v) in
  /// `pdf_uv`. Prefetches the texels that eval at the sample will read, in rows
  /// `footprint_row` and `footprint_row` + 1.
  float sample_column(std::size_t row, int footprint_row, float u, float& pdf_uv) const;

  int width_ = 0, height_ = 0;
  float fw_ = 0.0f, fh_ = 0.0f;  ///< float(width_), float(height_)
  std::size_t stride_ = 0;       ///< texels per row of texels_: width + 2
  float intensity_ = 1.0f;
  /// world_to_env's rotation (cos, sin), computed once.
  float cos_rot_ = 1.0f, sin_rot_ = 0.0f;
  float cos_inv_ = 1.0f, sin_inv_ = 0.0f;  ///< the inverse rotation's
  /// The map with a one-texel border (the wrapped columns left and right, the first and
  /// last rows repeated above and below), so a bilinear lookup needs no wrapping or
  /// clamping: (width + 2) x (height + 2) texels of RGB radiance and, in w, the texel's
  /// sampling density p(u, v) = p(v) p(u | v) (0 in the border). A ray that escapes reads
  /// its radiance and its pdf from the same cache lines: the texel containing a point is
  /// one of its four bilinear neighbours.
  std::vector<glm::vec4> texels_;
  Distribution1D marginal_;  ///< p(v), over rows (small: stays in cache)
  /// p(u | v), per row: the row's CDF (cdf[i], i = 0..width, 0 first and 1 last) in two
  /// levels, so that inverting it costs one cache miss: the fine level holds the CDF in
  /// 64-byte lines of 16 values (entries past width are 2, above every u), the coarse
  /// level every 16th value (cdf[16 j], j = 0..lines), small enough to stay in cache
  /// (256 rows x 33 floats for a 512-wide map). A sample finds its line by a binary
  /// search of the coarse level and its bin by counting the line's values <= u. The bin
  /// weights are not stored: the texels' p(u, v) stands for them.
  struct alignas(64) CdfLine {
    float cdf[16];
  };
  std::size_t lines_per_row_ = 0;
  std::vector<CdfLine> fine_cdf_;
  std::vector<float> coarse_cdf_;  ///< lines_per_row_ + 1 per row
  float mean_luminance_ = 0.0f;
};

}  // namespace pbrkit
