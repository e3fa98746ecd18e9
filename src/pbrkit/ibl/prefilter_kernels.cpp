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
  SampleSet s;
  const std::size_t n =
      (samples.size() + simd::kLanes - 1) / simd::kLanes * std::size_t(simd::kLanes);
  auto level_size = [&](int level) {
    return float(source.size(std::min(level, source.levels() - 1)));
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Padding: a zero-weight sample at the pole of level 0.
    const PrefilterSample p = i < samples.size() ? samples[i] : PrefilterSample{{0, 0, 1}, 0, 0};
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

// w times the bilinear RGBA lookup at texel coordinates (x, y) (already clamped to
// [0, size - 1]) of a face of `size` px, clamped at the face's edges (cube_lookup.h). The
// four taps are summed as a tree: short dependency chains.
inline Rgba bilinear(const float* face, int size, float x, float y, float w) {
  const int x0 = int(x), y0 = int(y);
  const float fx = x - float(x0), fy = y - float(y0);
  const int dx = x0 + 1 < size ? 4 : 0;
  const int dy = y0 + 1 < size ? 4 * size : 0;
  const float* p = face + 4 * (std::size_t(y0) * size + x0);
  const float wy0 = w * (1.0f - fy), wy1 = w * fy;
  const Rgba top = (wy0 * (1.0f - fx)) * Rgba(p, simd::stdx::element_aligned) +
                   (wy0 * fx) * Rgba(p + dx, simd::stdx::element_aligned);
  const Rgba bottom = (wy1 * (1.0f - fx)) * Rgba(p + dy, simd::stdx::element_aligned) +
                      (wy1 * fx) * Rgba(p + dy + dx, simd::stdx::element_aligned);
  return top + bottom;
}

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
  alignas(64) std::array<float, simd::kLanes> u0, v0, u1, v1, faces;
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
    // Texel coordinates on both levels (cube_lookup.h's bilinear: centres at i + 0.5).
    const floatv max0 = simd::load(&set.max0[i]), half0 = simd::load(&set.half0[i]);
    const floatv max1 = simd::load(&set.max1[i]), half1 = simd::load(&set.half1[i]);
    clamp(s1 * half0 - 0.5f, floatv(0.0f), max0).copy_to(u0.data(), simd::stdx::vector_aligned);
    clamp(t1 * half0 - 0.5f, floatv(0.0f), max0).copy_to(v0.data(), simd::stdx::vector_aligned);
    clamp(s1 * half1 - 0.5f, floatv(0.0f), max1).copy_to(u1.data(), simd::stdx::vector_aligned);
    clamp(t1 * half1 - 0.5f, floatv(0.0f), max1).copy_to(v1.data(), simd::stdx::vector_aligned);
    face.copy_to(faces.data(), simd::stdx::vector_aligned);
    for (int k = 0; k < simd::kLanes; ++k) {
      const std::size_t j = i + k;
      const int f = int(faces[k]), l = set.level[j];
      const int size = int(set.max0[j]) + 1;
      acc[k] += bilinear(data[l][f], size, u0[k], v0[k], set.w0[j]);
      if (set.w1[j] > 0.0f) acc[k] += bilinear(data[l + 1][f], size / 2, u1[k], v1[k], set.w1[j]);
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
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec3 w = cube_direction(
            face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
        const float dw = cube_texel_solid_angle(x, y, size);
        const glm::vec3 L = cube.mips[level][face].rgb(x, y) * dw;
        q.x.push_back(w.x), q.y.push_back(w.y), q.z.push_back(w.z);
        q.r.push_back(L.x), q.g.push_back(L.y), q.b.push_back(L.z), q.omega.push_back(dw);
      }
  return q;
}

glm::vec4 quadrature_sums(const QuadratureSource& q, float alpha, glm::vec3 R, float cos_max) {
  constexpr int kLanes = 8;  // independent partial sums: lets the compiler vectorise
  float sr[kLanes] = {}, sg[kLanes] = {}, sb[kLanes] = {}, sw[kLanes] = {};
  const float a2m1 = alpha * alpha - 1.0f;
  const std::size_t n = q.x.size(), blocks = n / kLanes * kLanes;
  auto term = [&](std::size_t i, float& r, float& g, float& b, float& w) {
    const float c = R.x * q.x[i] + R.y * q.y[i] + R.z * q.z[i];
    const float NdotL = c < cos_max ? std::max(c, 0.0f) : 0.0f;
    const float d = (0.5f + 0.5f * c) * a2m1 + 1.0f;
    const float weight = NdotL / (d * d);
    r += weight * q.r[i];
    g += weight * q.g[i];
    b += weight * q.b[i];
    w += weight * q.omega[i];
  };
  for (std::size_t i = 0; i < blocks; i += kLanes)
    for (int k = 0; k < kLanes; ++k) term(i + k, sr[k], sg[k], sb[k], sw[k]);
  for (std::size_t i = blocks; i < n; ++i) term(i, sr[0], sg[0], sb[0], sw[0]);
  float r = 0, g = 0, b = 0, w = 0;
  for (int k = 0; k < kLanes; ++k) r += sr[k], g += sg[k], b += sb[k], w += sw[k];
  return {r, g, b, w};
}

}  // namespace pbrkit::detail
