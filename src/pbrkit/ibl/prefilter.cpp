// The GGX-prefiltered specular chain (Karis 2013 split sum): importance sampling with
// filtered importance sampling (Colbert & Krivanek 2007) for sharp levels, direct quadrature
// for small rough ones. See prefilter.h.
#include "pbrkit/ibl/prefilter.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {

// Reports progress from worker threads: `done` units out of `total`, forwarded to the
// callback by whichever thread gets the lock (callers' callbacks need not be thread-safe);
// stopped() once the callback has returned false.
class ProgressCounter {
 public:
  ProgressCounter(const ProgressCallback& callback, double total)
      : callback_(callback), total_(total) {}
  void add(double units, const char* stage) {
    if (!callback_) return;
    const double done = done_.fetch_add(units) + units;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (lock.owns_lock() && !callback_(std::min(1.0, done / total_), stage)) stopped_ = true;
  }
  bool stopped() const { return stopped_.load(std::memory_order_relaxed); }

 private:
  const ProgressCallback& callback_;
  double total_;
  std::atomic<double> done_{0.0};
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;
};

}  // namespace

int specular_levels(int face_size, int min_face_size) {
  int levels = 1;
  while ((face_size >> levels) >= std::max(min_face_size, 1)) ++levels;
  return levels;
}

float ggx_cone_fraction(float alpha, float cos_theta_h) {
  // The GGX NDF's CDF in theta_h (the inverse of Karis 2013's sampling formula):
  // P(theta_h < t) = tan^2 t / (alpha^2 + tan^2 t).
  if (cos_theta_h <= 0.0f) return 1.0f;
  const float c2 = cos_theta_h * cos_theta_h;
  const float tan2 = (1.0f - c2) / c2;
  return tan2 / (alpha * alpha + tan2);
}

std::vector<PrefilterSample> prefilter_samples(float roughness, int samples, int source_size,
                                               int source_levels, bool filtered, float lod_bias,
                                               float core_cos_h) {
  std::vector<PrefilterSample> out;
  out.reserve(samples);
  const float alpha = sqr(std::max(roughness, kMinRoughness));
  // Omega_p: solid angle of one texel of the source mip 0 (the average over the cube).
  const float omega_p = 4.0f * kPi / (6.0f * float(source_size) * float(source_size));
  // Never read levels below kMinFisFaceSize px: lookups clamp at face edges (no cross-face
  // filtering), so a 1-4 px face is a constant and sparse tail samples reading it draw the
  // cube's face boundaries into the result as sharp-edged facets (seen in the previews).
  int coarsest = source_levels - 1;
  while (coarsest > 0 && (source_size >> coarsest) < kMinFisFaceSize) --coarsest;
  const float max_lod = float(coarsest);
  // Samples restricted to the cone theta_h < acos(core_cos_h): u.y scaled by the cone's
  // probability, so the conditional pdf is pdf / fraction.
  const float fraction = ggx_cone_fraction(alpha, core_cos_h);
  for (int i = 0; i < samples; ++i) {
    glm::vec2 u = hammersley(std::uint32_t(i), std::uint32_t(samples));
    u.y *= fraction;
    const glm::vec3 h = sample_ggx_ndf(u, alpha).h;
    // n = v = R = +Z (Karis 2013): l = reflect(-v, h) = 2 (v.h) h - v.
    const glm::vec3 l(2.0f * h.z * h.x, 2.0f * h.z * h.y, 2.0f * h.z * h.z - 1.0f);
    if (l.z <= 0.0f) continue;
    float lod = 0.0f;
    if (filtered) {
      // pdf(l) = D(h) (n.h) / (4 v.h) = D(h) / 4 when n = v. Colbert & Krivanek 2007
      // (GPU Gems 3, ch. 20, eq. 13): lod = 0.5 log2(Omega_s / Omega_p) + 1,
      // Omega_s = 1 / (N pdf).
      const float pdf = DistributionGGX(h, alpha) * 0.25f / fraction;
      const float omega_s = 1.0f / (float(samples) * pdf);
      lod = std::clamp(0.5f * std::log2(omega_s / omega_p) + lod_bias, 0.0f, max_lod);
    }
    out.push_back({l, l.z, lod});
  }
  return out;
}

int quadrature_source_level(const Cubemap& source, float roughness) {
  // Source texels (pi/2 / S rad across) at most alpha / 8, alpha being the angular scale
  // of the lobe of l (about 2 alpha wide), and at least 128 px (or the finest level): small
  // bright sources must not be smeared over a texel that spans a large part of the lobe
  // (with 64 px, the studio map's softboxes put one roughness-0.8 texel 1% off).
  const float alpha = sqr(std::max(roughness, kMinRoughness));
  int level = source.levels() - 1;
  while (level > 0 &&
         (0.5f * kPi / float(source.size(level)) > 0.125f * alpha || source.size(level) < 128))
    --level;
  return level;
}

bool use_quadrature(const Cubemap& source, const BakeOptions& options, float roughness,
                    int out_size) {
  if (!options.quadrature_for_rough_levels) return false;
  const double S = source.size(quadrature_source_level(source, roughness));
  // Texel pairs (6 faces each side); the half behind R is skipped, so a level costs about
  // 0.7 s per 2^32 on one core. Only the small rough levels fit.
  return roughness >= 0.25f &&
         36.0 * double(out_size) * out_size * S * S <= options.quadrature_budget;
}

namespace {

// How one specular level is computed.
struct LevelPlan {
  bool quadrature = false;  // direct quadrature over `texels` (all of the sphere)
  float alpha = 0.0f;
  // Importance-sampled levels: GGX samples restricted to the cone R.l >= cos_core, which
  // holds `core_fraction` of the lobe, plus the tail (R.l < cos_core) by quadrature over
  // the coarse `texels`: the sparse tail samples of a narrow lobe alias on small bright
  // lights (streaks and facets in the previews); a quadrature has no such noise.
  detail::SampleSet samples;
  int sample_count = 0;
  float core_fraction = 1.0f;
  float cos_core = -2.0f;
  const detail::QuadratureSource* texels = nullptr;  // see FlatLevels
};

// Source levels flattened for the quadratures, each once (levels 2 to 5 of the default bake
// all read the 128 px level).
class FlatLevels {
 public:
  explicit FlatLevels(const Cubemap& source) : source_(source) {}
  const detail::QuadratureSource* get(int level) {
    auto it = levels_.find(level);
    if (it == levels_.end())
      it = levels_.emplace(level, detail::flatten_level(source_, level)).first;
    return &it->second;
  }

 private:
  const Cubemap& source_;
  std::map<int, detail::QuadratureSource> levels_;  // nodes never move
};

LevelPlan plan_level(const Cubemap& source, const BakeOptions& options, int level, int levels,
                     FlatLevels& flat) {
  LevelPlan plan;
  const int size = source.size(0) >> level;
  const float roughness = mip_roughness(level, levels, options.mapping);
  plan.alpha = sqr(std::max(roughness, kMinRoughness));
  if (use_quadrature(source, options, roughness, size)) {
    plan.quadrature = true;
    plan.texels = flat.get(quadrature_source_level(source, roughness));
    return plan;
  }
  float core_cos_h = 0.0f;  // whole hemisphere of h: no tail
  if (options.quadrature_for_rough_levels) {
    // The tail's source level: the finest with at most 2^28 texel pairs for this level.
    int tail_level = 0;
    while (tail_level + 1 < source.levels() &&
           36.0 * double(size) * size * double(source.size(tail_level)) * source.size(tail_level) >
               double(1 << 28))
      ++tail_level;
    // The core cone spans 4 tail texels (pi/2 / S rad each) in l, half that in h.
    const float theta_l = std::min(4.0f * 0.5f * kPi / float(source.size(tail_level)), 1.2f);
    plan.cos_core = std::cos(theta_l);
    core_cos_h = std::cos(0.5f * theta_l);
    plan.texels = flat.get(tail_level);
  }
  plan.samples = detail::make_sample_set(
      prefilter_samples(roughness, options.samples, source.size(0), source.levels(),
                        options.filtered_importance_sampling, kPrefilterLodBias, core_cos_h),
      source);
  plan.sample_count = options.samples;
  plan.core_fraction = ggx_cone_fraction(plan.alpha, core_cos_h);
  return plan;
}

glm::vec3 prefilter_planned(const Cubemap& source, const LevelPlan& plan, glm::vec3 R) {
  if (plan.quadrature) {
    const glm::vec4 s = detail::quadrature_sums(*plan.texels, plan.alpha, R, 2.0f);
    return s.w > 0.0f ? glm::vec3(s) / s.w : glm::vec3(0.0f);
  }
  // Core: int_core L D/4 n.l dl ~= fraction / N sum L(l_i) n.l_i (l_i drawn from the
  // conditional pdf D / (4 fraction)); the same without L for the normalisation.
  const float core_scale = plan.core_fraction / float(plan.sample_count);
  glm::vec3 num = detail::sample_sum(source, plan.samples, R) * core_scale;
  float den = plan.samples.weight_sum * core_scale;
  if (plan.texels) {
    // Tail: D/4 n.l dOmega = alpha^2 / (4 pi) * w (see quadrature_sums).
    const glm::vec4 s = detail::quadrature_sums(*plan.texels, plan.alpha, R, plan.cos_core);
    const float k = plan.alpha * plan.alpha * 0.25f * kInvPi;
    num += glm::vec3(s) * k;
    den += s.w * k;
  }
  return den > 0.0f ? num / den : glm::vec3(0.0f);
}

// A copy of `cube` with 4 channels (A = 1).
Cubemap to_rgba(const Cubemap& cube) {
  Cubemap out;
  for (const auto& level : cube.mips) {
    out.mips.push_back(make_rgba_faces(level[0].width));
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < level[face].height; ++y)
        for (int x = 0; x < level[face].width; ++x)
          out.mips.back()[face].set_rgb(x, y, level[face].rgb(x, y));
  }
  return out;
}

}  // namespace

Cubemap prefilter_specular(const Cubemap& input, const BakeOptions& options,
                           const ProgressCallback& progress) {
  // The sampled core loads each texel as one RGBA vector: other channel counts are copied
  // to RGBA first (bake_environment's cubes are RGBA already).
  Cubemap rgba;
  if (!input.mips.empty() && input.mips[0][0].channels != 4) rgba = to_rgba(input);
  const Cubemap& source = rgba.mips.empty() ? input : rgba;
  const int face_size = source.size(0);
  const int levels = specular_levels(face_size, options.min_face_size);
  Cubemap out;
  out.mips.push_back(source.mips[0]);  // roughness 0: the mirror, a copy of the source
  struct Row {
    int level, face, y;
  };
  std::vector<Row> rows;
  std::vector<LevelPlan> plans(levels);
  FlatLevels flat(source);
  std::vector<double> row_work(levels, 0.0);
  double total_work = 0.0;
  for (int m = 1; m < levels; ++m) {
    const int size = face_size >> m;
    out.mips.push_back(make_rgba_faces(size));
    plans[m] = plan_level(source, options, m, levels, flat);
    row_work[m] = double(size) * (double(plans[m].samples.x.size()) +
                                  0.1 * double(plans[m].texels ? plans[m].texels->x.size() : 0));
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < size; ++y) rows.push_back({m, face, y});
    total_work += 6.0 * size * row_work[m];
  }
  ProgressCounter counter(progress, std::max(total_work, 1.0));
  std::vector<std::atomic<int>> rows_done(static_cast<std::size_t>(levels));
  pbrkit::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size()), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (counter.stopped()) return;
      const Row row = rows[i];
      const int size = face_size >> row.level;
      Image& img = out.mips[row.level][row.face];
      for (int x = 0; x < size; ++x) {
        const glm::vec3 R = cube_direction(
            row.face, {(float(x) + 0.5f) / float(size), (float(row.y) + 0.5f) / float(size)});
        img.set_rgb(x, row.y, prefilter_planned(source, plans[row.level], R));
      }
      rows_done[std::size_t(row.level)].fetch_add(1, std::memory_order_relaxed);
      counter.add(row_work[row.level], "specular");
    }
  });
  // Stopped (util/progress.h): the levels done, the first ones (level 0 always).
  if (counter.stopped())
    for (int m = 1; m < levels; ++m)
      if (rows_done[std::size_t(m)].load() < 6 * (face_size >> m)) {
        out.mips.resize(std::size_t(m));
        break;
      }
  return out;
}

}  // namespace pbrkit
