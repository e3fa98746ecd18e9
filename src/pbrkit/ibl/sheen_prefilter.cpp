// The Charlie-prefiltered sheen chain (see sheen_prefilter.h). Reuses the GGX prefilter's
// vectorised sample loop (prefilter_kernels.h) with Charlie samples.
#include "pbrkit/ibl/sheen_prefilter.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sheen.h"
#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

int sheen_grid_size(const BakeOptions& options, int level) {
  return std::min(options.face_size >> level, options.sheen_grid_size);
}

int sheen_source_level(const Cubemap& source, const BakeOptions& options, float roughness) {
  // Rough kernels (>= 0.4: at least ~60 degrees wide) read a level half as fine.
  const int max_size =
      roughness >= 0.4f ? std::max(options.sheen_source_size / 2, 8) : options.sheen_source_size;
  int level = 0;
  while (level + 1 < source.levels() && source.size(level) > max_size) ++level;
  return level;
}

SheenKernel::SheenKernel(float roughness) : k(kSize + 1) {
  const float r = std::clamp(roughness, kMinSheenRoughness, 1.0f);
  // With n = v = R: (n.h)^2 = (1 + c) / 2, so sin^2(theta_h) = (1 - c) / 2, and
  // D_Charlie(h) c = (2 + 1/r) / (2 pi) ((1 - c) / 2)^(1 / (2r)) c; the constant cancels.
  for (int i = 0; i <= kSize; ++i) {
    const float c = float(i) / float(kSize);
    k[std::size_t(i)] = std::pow(0.5f * (1.0f - c), 0.5f / r) * c;
  }
}

glm::vec3 sheen_quadrature(const detail::QuadratureSource& q, const SheenKernel& kernel,
                           glm::vec3 R) {
  float num_r = 0.0f, num_g = 0.0f, num_b = 0.0f, den = 0.0f;
  const float scale = float(SheenKernel::kSize);
  for (std::size_t i = 0; i < q.x.size(); ++i) {
    const float c = R.x * q.x[i] + R.y * q.y[i] + R.z * q.z[i];
    if (c <= 0.0f) continue;
    // Linear interpolation in the kernel's table (c in (0, 1]).
    const float t = std::min(c, 1.0f) * scale;
    const int j = std::min(int(t), SheenKernel::kSize - 1);
    const float f = t - float(j);
    const float w =
        kernel.k[std::size_t(j)] + f * (kernel.k[std::size_t(j) + 1] - kernel.k[std::size_t(j)]);
    num_r += w * q.r[i];
    num_g += w * q.g[i];
    num_b += w * q.b[i];
    den += w * q.omega[i];
  }
  return den > 0.0f ? glm::vec3(num_r, num_g, num_b) / den : glm::vec3(0.0f);
}

Cubemap prefilter_sheen(const Cubemap& source, const BakeOptions& options,
                        const ProgressCallback& progress) {
  if (source.mips.empty()) fail("prefilter_sheen: the source cube is empty");
  // The GGX chain's sizes and levels (so one lod formula serves both chains); level m is
  // computed on a grid of sheen_grid_size(options, m) px and, where the level is larger,
  // bilinearly upsampled from it.
  const int levels = specular_levels(options.face_size, options.min_face_size);
  std::map<int, detail::QuadratureSource> flat;  // by source level
  std::vector<const detail::QuadratureSource*> texels;
  std::vector<SheenKernel> kernels;
  Cubemap grid;  // level m: the computed grid
  struct Row {
    int level, face, y;
  };
  std::vector<Row> rows;
  for (int m = 0; m < levels; ++m) {
    const float roughness = mip_roughness(m, levels, options.mapping);
    const int src_level = sheen_source_level(source, options, roughness);
    auto it = flat.find(src_level);
    if (it == flat.end())
      it = flat.emplace(src_level, detail::flatten_level(source, src_level)).first;
    texels.push_back(&it->second);
    kernels.emplace_back(roughness);
    const int size = sheen_grid_size(options, m);
    grid.mips.push_back(make_rgba_faces(size));
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < size; ++y) rows.push_back({m, face, y});
  }
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  std::atomic<bool> stopped{false};
  std::vector<std::atomic<int>> rows_done(static_cast<std::size_t>(levels));
  pbrkit::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size()), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (stopped.load(std::memory_order_relaxed)) return;
      const Row row = rows[i];
      const int size = grid.size(row.level);
      const std::size_t m = std::size_t(row.level);
      Image& img = grid.mips[m][std::size_t(row.face)];
      for (int x = 0; x < size; ++x) {
        const glm::vec3 R = cube_direction(
            row.face, {(float(x) + 0.5f) / float(size), (float(row.y) + 0.5f) / float(size)});
        img.set_rgb(x, row.y, sheen_quadrature(*texels[m], kernels[m], R));
      }
      rows_done[m].fetch_add(1, std::memory_order_relaxed);
    }
    const std::size_t n = done.fetch_add(range.size()) + range.size();
    // The callback need not be thread-safe: whichever thread gets the lock reports.
    std::unique_lock lock(progress_mutex, std::try_to_lock);
    if (progress && lock.owns_lock() && !progress(double(n) / double(rows.size()), "sheen"))
      stopped = true;
  });
  // Stopped (util/progress.h): the levels done, the first ones.
  int complete_levels = levels;
  if (stopped.load())
    for (int m = 0; m < levels; ++m)
      if (rows_done[std::size_t(m)].load() < 6 * grid.size(m)) {
        complete_levels = m;
        break;
      }
  Cubemap out;
  for (int m = 0; m < complete_levels; ++m) {
    const int size = options.face_size >> m;
    if (size == grid.size(m)) {
      out.mips.push_back(std::move(grid.mips[std::size_t(m)]));
      continue;
    }
    // Upsampled: each texel the bilinear lookup of the grid level in its direction.
    Cubemap one;
    one.mips.push_back(grid.mips[std::size_t(m)]);
    out.mips.push_back(make_rgba_faces(size));
    auto& faces = out.mips.back();
    pbrkit::parallel_for(0, 6 * size, [&](int k) {
      const int face = k / size, y = k % size;
      for (int x = 0; x < size; ++x)
        faces[std::size_t(face)].set_rgb(
            x, y,
            sample_cubemap(one, cube_direction(face, {(float(x) + 0.5f) / float(size),
                                                      (float(y) + 0.5f) / float(size)})));
    });
  }
  return out;
}

}  // namespace pbrkit
