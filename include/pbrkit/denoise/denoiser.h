#pragma once
// The denoiser: feature-guided cross-filtering of a Monte Carlo render's two interleaved
// half buffers, after Rousselle, Manzi and Zwicker 2013, "Robust Denoising using Feature
// and Color Information" (Pacific Graphics 2013), with a first-order candidate after
// Bitterli et al. 2016, "Nonlinearly Weighted First-order Regression for Denoising Monte
// Carlo Renderings" (EGSR 2016). docs/DENOISER.md says what each stage does and why this
// method was chosen.
//
//  1. Variance from the half buffers: the squared difference of the two halves' means,
//     box-smoothed, estimates each pixel's noise (colour and every feature).
//  2. Feature prefilter: the albedo, normal and depth features are NL-means filtered with
//     their own variance, each half with the same weights; the residual variance of the
//     prefiltered features comes from the difference of the filtered halves.
//  3. Candidate filters: each half is filtered with weights from the other half's colour
//     (NL-means patch distance normalised by the variance) and from the features (their
//     distance normalised by their variance and gradient); the weight is the smaller of
//     the two. Zero-order candidates are weighted means (normalised weights: no energy is
//     added and the mean of a region is kept); the first-order one fits the colour as a
//     linear function of the normal, depth and screen position with the same weights
//     (less the normal's), which follows shading across curved surfaces, clamped to the
//     input's range.
//  4. Selection: Stein's unbiased risk estimate (SURE) of each candidate's error, which
//     is exact for a cross filter (its weights do not depend on the half it filters),
//     smoothed; the per-pixel best is chosen and the choice is smoothed.
//
// The work runs on oneTBB (pbrkit::parallel_for) with per-pixel independent sums in a
// fixed order: the output is bit-identical whatever the thread count.
#include <string>
#include <vector>

#include "pbrkit/image/image.h"
#include "pbrkit/util/progress.h"

namespace pbrkit {

/// What the denoiser reads: the two interleaved half buffers of a render (the mean of the
/// even-indexed samples and of the odd-indexed ones), for the colour and each feature.
/// Every image has the same size; colour and albedo have 3 channels, normal 3 (XYZ in
/// [-1, 1]), depth 1 (distance along the camera ray, 0 for a miss). The denoised image
/// estimates the mean of the two halves.
struct DenoiseInput {
  Image color[2];
  Image albedo[2];
  Image normal[2];
  Image depth[2];
};

/// One candidate filter: its colour sensitivity (larger mixes more; 0 or a negative value
/// means infinity, a filter guided by the features alone).
struct DenoiseCandidate {
  float color_k = 0.45f;
  /// Its window radius (0: DenoiseOptions::radius, at most that): a smaller spatial
  /// bandwidth where neither features nor colour separate what should stay apart
  int radius = 0;
};

/// The default zero-order candidates: k_c 1.0 with a 7x7 window and k_c 0.45 with the full
/// one. (A function rather than a braced initialiser: GCC 12 at -O2 reports the copy of an
/// initializer_list of this struct as maybe-uninitialized in callers that edit the list.)
std::vector<DenoiseCandidate> default_denoise_candidates();

struct DenoiseOptions {
  int radius = 7;        ///< filter window radius in pixels ((2r+1)^2 neighbours)
  int patch_radius = 1;  ///< NL-means colour patch radius
  /// The colour distance's variance cancellation: Var_p + Var_q (symmetric: the weight of
  /// q in p's mean is the weight of p in q's) instead of Rousselle et al. 2012's Var_p +
  /// min(Var_p, Var_q) (docs/DENOISER.md, "Energy")
  bool symmetric_colour_distance = false;
  float feature_k = 1.0f;     ///< feature sensitivity (Rousselle et al. 2013's k_f; they use 0.6)
  float feature_tau = 1e-3f;  ///< floor of the feature normalisation (their tau)
  /// The normal's own floor (0: feature_tau): shading changes slowly with the normal on
  /// curved surfaces (docs/DENOISER.md)
  float normal_tau = 3e-3f;
  /// Scale of the squared feature gradient in the normalisation (1: Rousselle et al.;
  /// less keeps silhouettes from leaking, docs/DENOISER.md)
  float feature_gradient = 0.25f;
  /// Zero-order candidates (weighted means): one with a 7x7 window (a smaller spatial
  /// bandwidth, as the filters SURE chooses among in Li et al. 2012) and Rousselle et al.
  /// 2013's detail-keeping FIRST with the full window (docs/DENOISER.md)
  std::vector<DenoiseCandidate> candidates = default_denoise_candidates();
  /// First-order candidates (Bitterli et al. 2016): the colour fitted as a linear function
  /// of the normal, the depth and the screen position over the full window, one per colour
  /// sensitivity (0: the features alone); they come after `candidates` in
  /// DenoiseStats::candidate_share
  std::vector<float> first_order_k{1.0f};
  /// Ridge of the first-order fits, relative to the sum of the weights: where a regressor
  /// does not vary over the window its slope goes to 0 and the fit to the weighted mean
  float first_order_ridge = 1e-3f;
  /// Box radius over which each first-order fit gets back the energy it lost against the
  /// first zero-order candidate (docs/DENOISER.md; 0: off): the mean of a region larger
  /// than the box is kept
  int first_order_energy_radius = 7;
  /// Box radius over which the other zero-order candidates get the energy of the first one
  /// too (docs/DENOISER.md, "Energy"; 0: off): a weighted mean whose weights differ from
  /// pixel to pixel (the colour distance is normalised by each pixel's own variance) does
  /// not keep a region's mean, and over the full window it moves most; the 7x7 candidate
  /// moves far less. Off: a box small enough not to cross silhouettes into noise-free
  /// regions gives the candidate the reference's noise, which its SURE estimate (taken
  /// before) does not see, and the selection then prefers it (BENCHMARKS.md)
  int zero_order_energy_radius = 0;
  /// Firefly treatment (docs/DENOISER.md): a half's pixel more than outlier_k robust
  /// standard deviations above the second largest value of both halves in its
  /// (2 outlier_radius + 1)^2 window (and above the other half) is scaled down and its
  /// excess spread over the feature-alike pixels within outlier_spread_radius (energy is
  /// kept). outlier_k <= 0 turns it off.
  float outlier_k = 3.0f;
  /// The quantile of the window's values (both halves) that a pixel must exceed by
  /// outlier_k robust sigmas (docs/DENOISER.md): 0.9 ignores up to a tenth of the window
  /// being rare bright samples; 1 - 1 / (window size - 1) is the second largest value
  float outlier_quantile = 0.9f;
  int outlier_radius = 2;
  int outlier_spread_radius = 7;
  int variance_radius = 2;  ///< box radius smoothing the half-buffer variance estimates
  /// Smooth the colour's relative variance and scale it by each pixel's own level
  /// (docs/DENOISER.md), rather than the variance itself
  bool relative_variance = true;
  /// With relative_variance: smooth each pixel's relative variance only over the pixels
  /// of the box whose level (plus 0.1) is within this factor of its own (0: the whole box).
  /// A quiet pixel beside a much brighter or darker noisy one (the edge of a light seen
  /// directly) otherwise takes in that one's relative variance, and the colour distance
  /// then lets it average with its neighbours across the edge (docs/DENOISER.md, "Energy")
  float variance_level_ratio = 1.5f;
  int prefilter_radius = 3;  ///< feature prefilter window radius (0: no prefilter)
  int error_radius = 2;      ///< box radius smoothing the per-candidate error estimates
  int selection_radius = 1;  ///< box radius smoothing the per-pixel choice of candidate
  /// Choose each half's candidates from the other half's error estimates rather than one
  /// choice from both (docs/DENOISER.md, "Selection": it moved more energy in the
  /// heavy-tailed benchmark scenes, so it is off)
  bool cross_selection = false;
  /// Also offer the unfiltered image as a candidate (last in DenoiseStats::candidate_share);
  /// off: it changed no scene of denoise_bench measurably (docs/benchmarks_archive.md, "the
  /// denoiser")
  bool raw_candidate = false;
  /// Pass through the pixels whose every sample saw the environment directly (depth 0 in
  /// both halves: no sample hit the scene). Their colour is a lookup of the environment,
  /// noise-free but for the pixel filter's sampling of its detail, so filtering can only
  /// blur it; and their variance, smoothed over a box that reaches across a silhouette,
  /// takes in the scene's, which lets the filters blur them freely (docs/DENOISER.md,
  /// "Energy": those blocks moved by many of their tiny standard errors).
  bool keep_direct_environment = true;
  /// Images wider or taller than `tile` pixels are denoised in tiles of at most that side,
  /// each with a margin of denoise_tile_margin(options) pixels of image around it, so that
  /// peak memory follows the tile, not the image (`pbrkit denoise` of a 1920x1080 image:
  /// 799 MB whole, 416 MB in tiles; docs/DENOISER.md, "Tiles"). Every stage reads a bounded
  /// neighbourhood, so the image is the same bit for bit (DenoiseStats's candidate_share
  /// and outliers then count the margins too). 0: always whole.
  int tile = 1024;
};

/// The margin each tile of DenoiseOptions::tile runs with: the radius of the neighbourhood
/// of input pixels that can change an output pixel, the sum of the radii along the
/// longest chain of stages (denoiser.cpp derives it).
int denoise_tile_margin(const DenoiseOptions& options);

/// Diagnostics of one run.
struct DenoiseStats {
  double seconds = 0.0;
  std::vector<double> candidate_share;  ///< fraction of the image each candidate won
  int outliers = 0;                     ///< half-buffer pixels the firefly treatment changed
  /// The progress callback stopped it: the image returned is the input's mean (the two
  /// halves' average, the undenoised image), and candidate_share is empty.
  bool interrupted = false;
};

/// Checks `input`: eight images present, one size, the channel counts above, every value
/// finite. Throws pbrkit::Error naming the offending layer (`color_a`, `albedo_b`, ...)
/// and, for a non-finite value, the pixel.
void validate_denoise_input(const DenoiseInput& input);

/// The layer names the checks and `pbrkit denoise` use: color_a, color_b, albedo_a, ...
std::vector<std::string> denoise_layer_names();

/// Denoises `input` (validated first). `progress` gets the fraction done; when it
/// returns false the work stops early and returns what it has (util/progress.h): the
/// input's mean, undenoised, with DenoiseStats::interrupted set (pass `stats` to tell the
/// two apart). Returns the denoised RGB image (every value finite and >= the smallest
/// input value).
///
/// `error` (when set) gets the denoiser's own per-pixel estimate of the output's error
/// (one channel): the SURE estimate of the candidate chosen at the pixel, relative to the
/// pixel's level, (F - truth)^2 / (m^2 + 0.01) averaged over the channels, box-smoothed as
/// the selection smooths it and clamped at 0 (what denoised-error adaptive sampling reads,
/// denoise/denoiser_driven_sampling.h). It does not change the image. Left untouched when
/// the work was interrupted.
Image denoise(const DenoiseInput& input, const DenoiseOptions& options = {},
              const ProgressCallback& progress = {}, DenoiseStats* stats = nullptr,
              Image* error = nullptr);

}  // namespace pbrkit
