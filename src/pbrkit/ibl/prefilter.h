#pragma once
// The prefiltered specular chain (BakeResult::specular; Karis 2013 split sum with n = v = R):
// each level m >= 1 holds int L(l) D(h) n.l dl / int D(h) n.l dl for the roughness
// mip_roughness(m, levels), by GGX importance sampling with filtered importance sampling
// (Colbert & Krivanek 2007) and, for small rough levels, by direct quadrature over a source
// level. The pieces are exposed for tests, the benchmark and `pbrkit bake --validate`.
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/cubemap.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// Number of specular levels from `face_size` down to `min_face_size` inclusive.
int specular_levels(int face_size, int min_face_size);

/// The constant added to Colbert & Krivanek's lod. Their GPU Gems 3 formula adds +1 (a
/// blur margin for hardware trilinear filtering); measured against the brute-force
/// reference (tests/ibl/prefilter_test.cpp, --validate), 0 is 4x more accurate with our
/// bilinear lookups on a box-filtered chain (0.4-0.8% vs 1.5-3% mean error on a smooth
/// environment, 16% vs 39% at roughness 0.25 on studio.exr) and still noise-free at 1024
/// samples, so we use 0.
inline constexpr float kPrefilterLodBias = 0.0f;

/// The coarsest source level that filtered importance sampling reads has faces of at least
/// this size.
inline constexpr int kMinFisFaceSize = 16;

/// One precomputed prefilter sample in the local frame of R (n = v = R = +Z).
struct PrefilterSample {
  glm::vec3 l;   ///< light direction, local frame
  float weight;  ///< n.l (Karis 2013 weighting)
  float lod;     ///< source mip to read (filtered importance sampling), 0 if disabled
};

/// The `samples` Hammersley GGX samples for `roughness` (alpha = max(roughness,
/// kMinRoughness)^2), those below the horizon dropped, each with its Colbert & Krivanek
/// 2007 lod for a source cube of `source_size` px and `source_levels` levels. With
/// core_cos_h > 0 the half vectors are restricted to theta_h < acos(core_cos_h) (the lobe's
/// core; the lod then uses the conditional pdf).
std::vector<PrefilterSample> prefilter_samples(float roughness, int samples, int source_size,
                                               int source_levels, bool filtered = true,
                                               float lod_bias = kPrefilterLodBias,
                                               float core_cos_h = 0.0f);

/// The GGX NDF's probability of theta_h < acos(cos_theta_h) (1 for cos_theta_h <= 0).
float ggx_cone_fraction(float alpha, float cos_theta_h);

/// The level of `source` the direct quadrature reads for `roughness`: the coarsest whose
/// texels are small against the lobe (and at least 128 px, or the finest level).
int quadrature_source_level(const Cubemap& source, float roughness);
/// Whether a level of `out_size` px at `roughness` is prefiltered by direct quadrature
/// (rough, small levels: exact and cheap there) rather than by importance sampling, as
/// options.quadrature_for_rough_levels and options.quadrature_budget allow.
bool use_quadrature(const Cubemap& source, const BakeOptions& options, float roughness,
                    int out_size);

/// The specular chain: level 0 a copy of the source's level 0, level m prefiltered for
/// roughness mip_roughness(m, levels, options.mapping). `source` needs its full chain.
/// Stopped by `progress` (util/progress.h), it returns the levels finished before the stop
/// (a prefix of the chain, at least level 0).
Cubemap prefilter_specular(const Cubemap& source, const BakeOptions& options,
                           const ProgressCallback& progress = {});

}  // namespace pbrkit
