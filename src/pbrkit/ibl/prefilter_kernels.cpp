// The specular prefilter's inner loops (see prefilter_kernels.h).
#include "pbrkit/ibl/prefilter_kernels.h"

#include <algorithm>
#include <array>

#include "pbrkit/core/math.h"
#include "pbrkit/ibl/simd.h"
#include "pbrkit/util/error.h"

namespace pbrkit::detail {

SampleSet make_sample_set(const std::vector<PrefilterSample>& samples, const Cubemap& source) {
  if (source.levels() > kMaxSampledLevels)
    fail("prefilter: the source has {} levels, at most {} supported", source.levels(),
         kMaxSampledLevels);
  // Samples that read one level first, then those that read two: the sum does not depend
  // on the order (up to rounding), and the fetch loop's branch on the second level is then
  // taken in one run instead of at random (the lod follows the Hammersley radical inverse).
  std::vector<PrefilterSample> sorted = samples;
  std::stable_partition(sorted.begin(), sorted.end(), [&](const PrefilterSample& p) {
    const int l0 = std::min(int(p.lod), source.levels() - 1);
    return !(l0 + 1 < source.levels() && p.lod - float(l0) > 0.0f);
  });
  SampleSet s;
  const std::size_t n =
      (samples.size() + simd::kLanes - 1) / simd::kLanes * std::size_t(simd::kLanes);
  auto level_size = [&](int level) {
    return float(source.size(std::min(level, source.levels() - 1)));
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Padding: a zero-weight sample at the pole of level 0.
    const PrefilterSample p = i < sorted.size() ? sorted[i] : PrefilterSample{{0, 0, 1}, 0, 0};
    const int l0 = std::min(int(p.lod), source.levels() - 1);
    const float f = l0 + 1 < source.levels() ? p.lod - float(l0) : 0.0f;
    s.x.push_back(p.l.x), s.y.push_back(p.l.y), s.z.push_back(p.l.z);
    s.w0.push_back(p.weight * (1.0f - f));
    s.w1.push_back(f > 0.0f ? p.weight * f : 0.0f);
    s.level.push_back(l0);
    s.half0.push_back(0.5f * level_size(l0)), s.max0.push_back(level_size(l0) - 1.0f);
    s.half1.push_back(0.5f * level_size(l0 + 1)), s.max1.push_back(level_size(l0 + 1) - 1.0f);
    s.weight_sum += p.weight;
  }
  return s;
}

namespace {

using Rgba = simd::stdx::fixed_size_simd<float, 4>;
using intv = simd::stdx::rebind_simd_t<int, simd::floatv>;

// The bilinear taps of kLanes lookups on one level (cube_lookup.h's bilinear: texel centres
// at i + 0.5, clamped within the face), set up with vector arithmetic: per lane the texel
// offset of the top-left tap, the offsets to its right and lower neighbours (0 at the
// face's last column or row), and the four tap weights times the sample's weight.
struct Taps {
  alignas(64) std::array<int, simd::kLanes> offset, right, down;
  alignas(64) std::array<float, simd::kLanes> w00, w10, w01, w11;

  // (s, t) in [0, 2] across the face; half = size / 2, last = size - 1 per lane.
  void set(simd::floatv s, simd::floatv t, simd::floatv half, simd::floatv last, simd::floatv w) {
    using simd::floatv;
    const floatv x = clamp(s * half - 0.5f, floatv(0.0f), last);
    const floatv y = clamp(t * half - 0.5f, floatv(0.0f), last);
    // Truncation is the floor here (x, y >= 0); y size + x < 2^24 is exact in float.
    const floatv x0 = simd::stdx::static_simd_cast<floatv>(simd::stdx::static_simd_cast<intv>(x));
    const floatv y0 = simd::stdx::static_simd_cast<floatv>(simd::stdx::static_simd_cast<intv>(y));
    const floatv fx = x - x0, fy = y - y0;
    const floatv size = last + 1.0f;
    floatv dx = 0.0f, dy = 0.0f;
    where(x0 < last, dx) = 4.0f;
    where(y0 < last, dy) = 4.0f * size;
    (4 * simd::stdx::static_simd_cast<intv>(y0 * size + x0))
        .copy_to(offset.data(), simd::stdx::vector_aligned);
    simd::stdx::static_simd_cast<intv>(dx).copy_to(right.data(), simd::stdx::vector_aligned);
    simd::stdx::static_simd_cast<intv>(dy).copy_to(down.data(), simd::stdx::vector_aligned);
    const floatv wy0 = w * (1.0f - fy), wy1 = w * fy;
    (wy0 * (1.0f - fx)).copy_to(w00.data(), simd::stdx::vector_aligned);
    (wy0 * fx).copy_to(w10.data(), simd::stdx::vector_aligned);
    (wy1 * (1.0f - fx)).copy_to(w01.data(), simd::stdx::vector_aligned);
    (wy1 * fx).copy_to(w11.data(), simd::stdx::vector_aligned);
  }

  // Lane k's weighted bilinear RGBA value from `face`; the taps summed as a tree (short
  // dependency chains).
  Rgba fetch(const float* face, int k) const {
    const float* p = face + offset[std::size_t(k)];
    const int dx = right[std::size_t(k)], dy = down[std::size_t(k)];
    const Rgba top = w00[std::size_t(k)] * Rgba(p, simd::stdx::element_aligned) +
                     w10[std::size_t(k)] * Rgba(p + dx, simd::stdx::element_aligned);
    const Rgba bottom = w01[std::size_t(k)] * Rgba(p + dy, simd::stdx::element_aligned) +
                        w11[std::size_t(k)] * Rgba(p + dy + dx, simd::stdx::element_aligned);
    return top + bottom;
  }
};

}  // namespace

glm::vec3 sample_sum(const Cubemap& source, const SampleSet& set, glm::vec3 R) {
  using simd::floatv;
  using simd::maskv;
  const Frame frame(R);
  const int levels = source.levels();
  // Face data by level, and one accumulator per lane (independent addition chains).
  std::array<std::array<const float*, 6>, kMaxSampledLevels> data{};
  for (int l = 0; l < levels; ++l)
    for (int f = 0; f < 6; ++f) data[l][f] = source.mips[l][f].data.data();
  std::array<Rgba, simd::kLanes> acc;
  acc.fill(0.0f);
  Taps fine, coarse;
  alignas(64) std::array<int, simd::kLanes> faces;
  for (std::size_t i = 0; i < set.x.size(); i += simd::kLanes) {
    const floatv lx = simd::load(&set.x[i]), ly = simd::load(&set.y[i]), lz = simd::load(&set.z[i]);
    const floatv dx = frame.t.x * lx + frame.b.x * ly + frame.n.x * lz;
    const floatv dy = frame.t.y * lx + frame.b.y * ly + frame.n.y * lz;
    const floatv dz = frame.t.z * lx + frame.b.z * ly + frame.n.z * lz;
    // Face selection and (sc, tc) exactly as cube_face_hit, branch-free.
    const floatv ax = abs(dx), ay = abs(dy), az = abs(dz);
    const maskv x_major = ax >= ay && ax >= az;
    const maskv y_major = !x_major && ay >= az;
    floatv face = 4.0f, ma = az, sc = dx, tc = -dy;  // z major
    where(dz <= 0.0f, face) = 5.0f;
    where(dz <= 0.0f, sc) = -dx;
    where(y_major, face) = 2.0f;
    where(y_major && dy <= 0.0f, face) = 3.0f;
    where(y_major, ma) = ay;
    where(y_major, sc) = dx;
    where(y_major, tc) = dz;
    where(y_major && dy <= 0.0f, tc) = -dz;
    where(x_major, face) = 0.0f;
    where(x_major && dx <= 0.0f, face) = 1.0f;
    where(x_major, ma) = ax;
    where(x_major, sc) = -dz;
    where(x_major && dx <= 0.0f, sc) = dz;
    where(x_major, tc) = -dy;
    const floatv inv = 1.0f / ma;  // |l| = 1, so ma >= 1 / sqrt(3)
    const floatv s1 = sc * inv + 1.0f, t1 = tc * inv + 1.0f;
    simd::stdx::static_simd_cast<intv>(face).copy_to(faces.data(), simd::stdx::vector_aligned);
    fine.set(s1, t1, simd::load(&set.half0[i]), simd::load(&set.max0[i]), simd::load(&set.w0[i]));
    coarse.set(s1, t1, simd::load(&set.half1[i]), simd::load(&set.max1[i]), simd::load(&set.w1[i]));
    for (int k = 0; k < simd::kLanes; ++k) {
      const std::size_t j = i + std::size_t(k);
      const int f = faces[std::size_t(k)], l = set.level[j];
      acc[std::size_t(k)] += fine.fetch(data[l][f], k);
      if (set.w1[j] > 0.0f) acc[std::size_t(k)] += coarse.fetch(data[l + 1][f], k);
    }
  }
  Rgba total = 0.0f;
  for (const Rgba& a : acc) total += a;
  return {total[0], total[1], total[2]};
}

QuadratureSource flatten_level(const Cubemap& cube, int level) {
  QuadratureSource q;
  const int size = cube.size(level);
  q.size = size;
  // Texel solid angles are the same on every face: 4 atan2 per texel of one face only.
  std::vector<float> omega(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      omega[std::size_t(y) * size + x] = cube_texel_solid_angle(x, y, size);
  const std::size_t n = std::size_t(6) * size * size;
  for (auto* v : {&q.x, &q.y, &q.z, &q.r, &q.g, &q.b, &q.omega}) v->resize(n);
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y) {
      const float t = (float(y) + 0.5f) / float(size);
      const glm::vec3 p0 = cube_face_point(face, {0.0f, t});
      q.row_a.push_back(p0);
      q.row_b.push_back(cube_face_point(face, {1.0f, t}) - p0);
      for (int x = 0; x < size; ++x) {
        const std::size_t i = (std::size_t(face) * size + y) * size + x;
        const glm::vec3 w = cube_direction(face, {(float(x) + 0.5f) / float(size), t});
        const float dw = omega[std::size_t(y) * size + x];
        const glm::vec3 L = cube.mips[level][face].rgb(x, y) * dw;
        q.x[i] = w.x, q.y[i] = w.y, q.z[i] = w.z;
        q.r[i] = L.x, q.g[i] = L.y, q.b[i] = L.z, q.omega[i] = dw;
      }
    }
  return q;
}

namespace {

constexpr int kBlock = simd::kLanes;

// Calls body(begin, end) for the texels of each row of q that may have R.l > 0, a
// superset: along a row the texel points are p(s) = a + s b (cube_face_point, affine), so
// R.l has the sign of R.a + s R.b and the texels with R.l > 0 are one interval, found with
// a margin of two texels and widened to whole SIMD vectors (in rows of a multiple of
// kBlock texels; smaller faces are summed whole). About half the sphere is skipped; the
// skipped texels have zero weight.
template <class Body>
void for_each_visible_span(const QuadratureSource& q, glm::vec3 R, Body body) {
  const int size = q.size;
  const bool blocks = size % kBlock == 0;
  for (int row = 0; row < 6 * size; ++row) {
    const float A = glm::dot(R, q.row_a[std::size_t(row)]);
    const float B = glm::dot(R, q.row_b[std::size_t(row)]);
    // The whole row behind R (beyond rounding: |A|, |B| <= 2, errors ~1e-7): skipped.
    if (A + std::max(B, 0.0f) < -1e-5f) continue;
    int begin = 0, end = size;
    // Texel x has s = (x + 0.5) / size; R.p(s) > 0 for s > -A / B (B > 0) or s < -A / B
    // (B < 0). Rows nearly perpendicular to R (small |B|, where the rounding of A moves
    // the edge far) are summed whole.
    if (blocks && std::abs(B) > 1e-4f) {
      const float edge = std::clamp(-A / B * float(size) - 0.5f, -4.0f, float(size) + 4.0f);
      if (B > 0.0f) {
        begin = std::clamp(int(std::floor(edge)) - 2, 0, size) / kBlock * kBlock;
      } else {
        end = (std::clamp(int(std::ceil(edge)) + 2, 0, size) + kBlock - 1) / kBlock * kBlock;
      }
    }
    const std::size_t base = std::size_t(row) * size;
    if (begin < end) body(base + begin, base + end);
  }
}

}  // namespace

glm::vec4 quadrature_sums(const QuadratureSource& q, float alpha, glm::vec3 R, float cos_max) {
  using simd::floatv;
  const float a2m1 = alpha * alpha - 1.0f;
  floatv sr = 0.0f, sg = 0.0f, sb = 0.0f, sw = 0.0f;
  glm::vec4 tail(0.0f);  // faces smaller than a vector
  for_each_visible_span(q, R, [&](std::size_t begin, std::size_t end) {
    std::size_t i = begin;
    for (; i + kBlock <= end; i += kBlock) {
      const floatv c =
          R.x * simd::load(&q.x[i]) + R.y * simd::load(&q.y[i]) + R.z * simd::load(&q.z[i]);
      floatv NdotL = max(c, floatv(0.0f));
      where(c >= cos_max, NdotL) = 0.0f;
      const floatv d = (0.5f + 0.5f * c) * a2m1 + 1.0f;
      const floatv weight = NdotL / (d * d);
      sr += weight * simd::load(&q.r[i]);
      sg += weight * simd::load(&q.g[i]);
      sb += weight * simd::load(&q.b[i]);
      sw += weight * simd::load(&q.omega[i]);
    }
    for (; i < end; ++i) {
      const float c = R.x * q.x[i] + R.y * q.y[i] + R.z * q.z[i];
      const float NdotL = c < cos_max ? std::max(c, 0.0f) : 0.0f;
      const float d = (0.5f + 0.5f * c) * a2m1 + 1.0f;
      tail += NdotL / (d * d) * glm::vec4(q.r[i], q.g[i], q.b[i], q.omega[i]);
    }
  });
  return glm::vec4(reduce(sr), reduce(sg), reduce(sb), reduce(sw)) + tail;
}

glm::vec3 cosine_sum(const QuadratureSource& q, glm::vec3 n) {
  using simd::floatv;
  floatv sr = 0.0f, sg = 0.0f, sb = 0.0f;
  glm::vec3 tail(0.0f);
  for_each_visible_span(q, n, [&](std::size_t begin, std::size_t end) {
    std::size_t i = begin;
    for (; i + kBlock <= end; i += kBlock) {
      const floatv c =
          max(n.x * simd::load(&q.x[i]) + n.y * simd::load(&q.y[i]) + n.z * simd::load(&q.z[i]),
              floatv(0.0f));
      sr += c * simd::load(&q.r[i]);
      sg += c * simd::load(&q.g[i]);
      sb += c * simd::load(&q.b[i]);
    }
    for (; i < end; ++i)
      tail += std::max(n.x * q.x[i] + n.y * q.y[i] + n.z * q.z[i], 0.0f) *
              glm::vec3(q.r[i], q.g[i], q.b[i]);
  });
  return glm::vec3(reduce(sr), reduce(sg), reduce(sb)) + tail;
}

}  // namespace pbrkit::detail
