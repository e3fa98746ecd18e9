// The IBL bake (Karis 2013 split sum): equirect -> cube resampling, box-filtered mip chain,
// GGX prefiltering with filtered importance sampling, diffuse irradiance (cube + SH9) and
// the BRDF LUT. See bake.h.
#include "pbrkit/ibl/bake.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <mutex>
#include <vector>

#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/ibl/bake_stages.h"
#include "pbrkit/ibl/brdf_lut.h"
#include "pbrkit/ibl/cube_lookup.h"
#include "pbrkit/ibl/prefilter_kernels.h"
#include "pbrkit/ibl/spherical_harmonics.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Process CPU time (all threads): std::clock on POSIX systems.
double cpu_seconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

// Wall and CPU time of one stage.
struct StageTimer {
  Clock::time_point wall = Clock::now();
  double cpu = cpu_seconds();
  void stop(double& wall_s, double& cpu_s) const {
    wall_s = seconds_since(wall);
    cpu_s = cpu_seconds() - cpu;
  }
};

bool is_power_of_two(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

std::array<Image, 6> make_faces(int size) {
  std::array<Image, 6> faces;
  for (Image& f : faces) f = Image(size, size, 4, 1.0f);
  return faces;
}

// Reports progress from worker threads: `done` units out of `total`, forwarded to the
// callback by whichever thread gets the lock (callers' callbacks need not be thread-safe).
class ProgressCounter {
 public:
  ProgressCounter(const ProgressCallback& callback, double total)
      : callback_(callback), total_(total) {}
  void add(double units, const char* stage) {
    if (!callback_) return;
    const double done = done_.fetch_add(units) + units;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (lock.owns_lock()) callback_(std::min(1.0, done / total_), stage);
  }

 private:
  const ProgressCallback& callback_;
  double total_;
  std::atomic<double> done_{0.0};
  std::mutex mutex_;
};

}  // namespace

int cube_supersampling(int source_width, int face_size) {
  // Source texels per cube texel along one axis: the equator spans 4 faces. Two samples
  // per source texel (at least 2x2 per cube texel) so small bright sources are integrated,
  // not point-sampled; capped at 8x8.
  const int ratio = (source_width + 4 * face_size - 1) / (4 * face_size);
  return std::clamp(2 * ratio, 2, 8);
}

Cubemap resample_to_cube(const Environment& env, int face_size) {
  if (face_size < 1) fail("cube face size must be positive, got {}", face_size);
  Cubemap cube;
  cube.mips.push_back(make_faces(face_size));
  const int ss = cube_supersampling(env.map.width, face_size);
  const float inv = 1.0f / float(face_size * ss);
  const float weight = 1.0f / float(ss * ss);
  tbb::parallel_for(0, 6 * face_size, [&](int r) {
    const int face = r / face_size, y = r % face_size;
    Image& img = cube.mips[0][face];
    for (int x = 0; x < face_size; ++x) {
      // A box filter over the texel's (s, t) square: the texel's average radiance, up to
      // the small variation of the solid-angle element within one texel.
      glm::vec3 sum(0.0f);
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) {
          const glm::vec2 st((float(x * ss + i) + 0.5f) * inv, (float(y * ss + j) + 0.5f) * inv);
          sum += env.eval(cube_direction(face, st));
        }
      img.set_rgb(x, y, sum * weight);
    }
  });
  return cube;
}

void build_mip_chain(Cubemap& cube, int min_size) {
  while (cube.size(cube.levels() - 1) / 2 >= std::max(min_size, 1)) {
    const int src_level = cube.levels() - 1;
    const int size = cube.size(src_level) / 2;
    cube.mips.push_back(make_faces(size));
    const auto& src = cube.mips[src_level];
    auto& dst = cube.mips.back();
    tbb::parallel_for(0, 6, [&](int face) {
      // 2x2 box filter. Texels of one face have nearly equal solid angles at these sizes;
      // the filtered importance sampling only needs a band-limited chain (Colbert &
      // Krivanek 2007, section 20.4).
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const glm::vec3 c = src[face].rgb(2 * x, 2 * y) + src[face].rgb(2 * x + 1, 2 * y) +
                              src[face].rgb(2 * x, 2 * y + 1) + src[face].rgb(2 * x + 1, 2 * y + 1);
          dst[face].set_rgb(x, y, 0.25f * c);
        }
    });
  }
}

float ggx_cone_fraction(float alpha, float cos_theta_h) {
  // The GGX NDF's CDF in theta_h (the inverse of the seeds' sampling formula):
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

namespace {

// Trilinear lookup in a chain stored as RGBA float faces (see cube_lookup.h).
inline glm::vec3 fetch(const Cubemap& src, glm::vec3 d, float lod) {
  const detail::FaceHit hit = detail::cube_face_hit(d);
  const int l0 = int(lod);
  const float f = lod - float(l0);
  const glm::vec3 c0 = detail::bilinear(src.mips[l0][hit.face], hit.sc, hit.tc);
  if (f <= 0.0f) return c0;
  const glm::vec3 c1 = detail::bilinear(src.mips[l0 + 1][hit.face], hit.sc, hit.tc);
  return c0 + f * (c1 - c0);
}

}  // namespace

glm::vec3 prefilter_direction(const Cubemap& source, const std::vector<PrefilterSample>& samples,
                              glm::vec3 R) {
  const Frame frame(R);
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (const PrefilterSample& s : samples) {
    const glm::vec3 l = frame.t * s.l.x + frame.b * s.l.y + frame.n * s.l.z;
    sum += fetch(source, l, s.lod) * s.weight;
    weight += s.weight;
  }
  return weight > 0.0f ? sum / weight : glm::vec3(0.0f);
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
    out.mips.push_back(make_faces(level[0].width));
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
    out.mips.push_back(make_faces(size));
    plans[m] = plan_level(source, options, m, levels, flat);
    row_work[m] = double(size) * (double(plans[m].samples.x.size()) +
                                  0.1 * double(plans[m].texels ? plans[m].texels->x.size() : 0));
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < size; ++y) rows.push_back({m, face, y});
    total_work += 6.0 * size * row_work[m];
  }
  ProgressCounter counter(progress, std::max(total_work, 1.0));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size()), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Row row = rows[i];
      const int size = face_size >> row.level;
      Image& img = out.mips[row.level][row.face];
      for (int x = 0; x < size; ++x) {
        const glm::vec3 R = cube_direction(
            row.face, {(float(x) + 0.5f) / float(size), (float(row.y) + 0.5f) / float(size)});
        img.set_rgb(x, row.y, prefilter_planned(source, plans[row.level], R));
      }
      counter.add(row_work[row.level], "specular");
    }
  });
  return out;
}

Cubemap irradiance_cube(const Cubemap& source, int size) {
  if (size < 1) fail("irradiance cube size must be positive, got {}", size);
  // E(n) = sum over source texels of L(w) max(0, n.w) dOmega(w): a direct quadrature of the
  // cosine convolution over a 64 px level (or the finest one if smaller), which is smooth
  // enough that the texel-centre rule is accurate to ~1e-4 of E.
  int level = 0;
  while (level + 1 < source.levels() && source.size(level) > 64) ++level;
  const detail::QuadratureSource texels = detail::flatten_level(source, level);
  Cubemap out;
  out.mips.push_back(make_faces(size));
  tbb::parallel_for(0, 6 * size, [&](int r) {
    const int face = r / size, y = r % size;
    for (int x = 0; x < size; ++x) {
      const glm::vec3 n =
          cube_direction(face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
      out.mips[0][face].set_rgb(x, y, detail::cosine_sum(texels, n));
    }
  });
  return out;
}

int specular_levels(int face_size, int min_face_size) {
  int levels = 1;
  while ((face_size >> levels) >= std::max(min_face_size, 1)) ++levels;
  return levels;
}

void check_bake_options(const BakeOptions& o) {
  if (!is_power_of_two(o.face_size) || o.face_size > kMaxFaceSize)
    fail("--size: the cube face size must be a power of two in 1..{}, got {}", kMaxFaceSize,
         o.face_size);
  if (!is_power_of_two(o.min_face_size) || o.min_face_size > o.face_size)
    fail("--min-size: the smallest mip must be a power of two in 1..{} (the face size), got {}",
         o.face_size, o.min_face_size);
  if (o.samples < 1 || o.samples > (1 << 20))
    fail("--samples: must be in 1..{}, got {}", 1 << 20, o.samples);
  if (o.irradiance_size < 1 || o.irradiance_size > 1024)
    fail("--irradiance-size: must be in 1..1024, got {}", o.irradiance_size);
  if (o.lut_size < 1 || o.lut_size > 4096)
    fail("--lut-size: must be in 1..4096, got {}", o.lut_size);
}

BakeResult bake_environment(const Environment& env, const BakeOptions& options,
                            const ProgressCallback& progress) {
  check_bake_options(options);
  if (env.map.empty()) fail("{}: the environment map is empty", env.source);
  BakeResult result;
  // Progress weights: the stages' typical share of the run time.
  auto stage = [&](double begin, double end) -> ProgressCallback {
    if (!progress) return {};
    return [&progress, begin, end](double f, const std::string& detail) {
      return progress(begin + (end - begin) * f, detail);
    };
  };

  const StageTimer all;
  StageTimer t;
  result.environment = resample_to_cube(env, options.face_size);
  build_mip_chain(result.environment, 1);
  t.stop(result.timings.cube_s, result.timings.cube_cpu_s);
  if (progress) progress(0.1, "cube");

  t = StageTimer();
  result.specular = prefilter_specular(result.environment, options, stage(0.1, 0.85));
  t.stop(result.timings.specular_s, result.timings.specular_cpu_s);

  t = StageTimer();
  result.sh = project_sh_irradiance(result.environment, 0);
  t.stop(result.timings.sh_s, result.timings.sh_cpu_s);

  t = StageTimer();
  result.irradiance = irradiance_cube(result.environment, options.irradiance_size);
  t.stop(result.timings.irradiance_s, result.timings.irradiance_cpu_s);
  if (progress) progress(0.9, "irradiance");

  t = StageTimer();
  result.lut = compute_brdf_lut(options.model, options.lut_size);
  t.stop(result.timings.lut_s, result.timings.lut_cpu_s);
  if (progress) progress(1.0, "done");

  all.stop(result.timings.total_s, result.timings.total_cpu_s);
  return result;
}

}  // namespace pbrkit
