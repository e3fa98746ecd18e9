#pragma once
// The denoiser's stages (include/pbrkit/denoise/denoiser.h gives the overview and
// docs/DENOISER.md the method): the half-buffer variance estimate, the feature
// prefilter, the candidate cross filters and the selection among them.
#include <atomic>
#include <functional>
#include <vector>

#include "pbrkit/denoise/denoiser.h"
#include "planes.h"

namespace pbrkit::denoising {

/// A multi-channel padded image: one Plane per channel.
using Channels = std::vector<Plane>;

Channels channels_from(const Image& image, int pad);

/// The variance of each half's mean from the two halves a and b (same channels):
/// E[(a - b)^2] = Var(a) + Var(b) = 2 Var(a) for halves of equal sample counts, so
/// box_r((a - b)^2 / 2), per channel. The variance of the mean of the two halves is half
/// of it.
Channels half_variance(const Channels& a, const Channels& b, int r);
/// As half_variance, but box-smooths the relative variance (a - b)^2 / 2 / (m^2 + floor),
/// m the pixel's mean of the halves, and scales the result back by the pixel's own m^2 +
/// floor: Monte Carlo noise grows with the signal, so across an intensity edge the relative
/// variance is the smoother quantity, and a dim pixel next to a bright one does not take
/// the bright one's variance.
Channels half_variance_relative(const Channels& a, const Channels& b, int r, float level_ratio);
/// The mean over channels of `per_channel` (one plane, same padding).
Plane channel_mean(const Channels& per_channel);

/// A feature after prefiltering: its mean (the two filtered halves averaged, one plane
/// per channel), the variance left in it (one plane: the channel mean of the filtered
/// halves' variance of the mean) and 1 / (k_f^2 max(tau, variance, |gradient|^2)), the
/// normalisation of Rousselle et al. 2013, eq. 9.
struct Feature {
  Channels mean;
  Plane variance;
  Plane inv_norm;
};

/// NL-means prefilter of one feature's halves with weights from their mean and its
/// variance (Rousselle et al. 2013, section 4.1). The halves carry the output's padding;
/// `tau` is the floor of the feature's distance normalisation.
Feature prefilter_feature(const Channels& a, const Channels& b, const DenoiseOptions& options,
                          float tau);

/// Energy-conserving firefly treatment (outliers.cpp): per half, pixels far above a robust
/// estimate from their neighbourhood and the other half are scaled down and their excess
/// is spread over the feature-alike pixels of the window, half into each half buffer, so
/// the mean of the halves keeps its energy. Returns the number of outliers treated.
/// `direct_environment` (when set, one flag per pixel, row-major) marks the pixels that saw
/// only the environment: they are neither treated nor given any other pixel's excess (the
/// denoiser passes them through, DenoiseOptions::keep_direct_environment).
int spread_outliers(Channels color[2], const std::vector<const Feature*>& features,
                    const DenoiseOptions& options,
                    const std::vector<unsigned char>* direct_environment = nullptr);

/// The candidates' outputs, per half: each filtered half (RGB) and the error of the
/// average of the two filtered halves as estimated from that half alone (its SURE less
/// half its variance, channel mean): the halves are alike, so either estimates the
/// error of their average, and the selection can take each half's choice from the
/// other half's estimate (selection.cpp).
struct Candidates {
  std::vector<Channels> color[2];  ///< [half][candidate][channel]
  std::vector<Plane> error[2];     ///< [half][candidate]
  std::size_t size() const { return color[0].size(); }
};

struct CrossFilterInput {
  const Channels* color[2];     ///< the halves
  const Channels* variance[2];  ///< the variance of each half's mean, per channel
  std::vector<const Feature*> features;
  /// The features the first-order candidates regress on (indices into `features`; -1:
  /// no first-order candidates), and the range their fits are clamped to (the input
  /// colour's). The normal leaves their weights; the depth stays a weight too (across a
  /// silhouette nothing is linear).
  int normal = -1, depth = -1;
  float lowest = 0.0f, highest = 0.0f;
};

/// First-order candidates (Bitterli et al. 2016; first_order.cpp): per pixel the colour is
/// fitted as a linear function of the normal, the depth and the screen position over the
/// window, by weighted least squares with the cross filter's weights (without the
/// normal's distance); the fit's value at the pixel is the output.
namespace first_order {
/// The regressors of q relative to p: 1, n_q - n_p (3), (d_q - d_p) kDepthScale, dx / r,
/// dy / r. Depth is normalised by its largest value; the scale brings a few per cent of
/// depth across the window to the spread of the other regressors, so that the ridge
/// treats them alike (the benchmark is insensitive to it between 3 and 30).
constexpr int kDim = 7;
constexpr float kDepthScale = 10.0f;
constexpr int kUpper = kDim * (kDim + 1) / 2;  ///< the normal matrix's upper triangle
constexpr int kSums = kUpper + 3 * kDim;       ///< + the right-hand sides of 3 channels
/// From one pixel's sums (A's upper triangle row by row, then b per channel), the fitted
/// colour at the pixel (the intercept) and its derivative in c_p ([A^-1]_00). `ridge`
/// times A_00 is added to the slopes' diagonal, so that where a regressor does not vary
/// the fit falls back to the weighted mean.
void solve(const float sums[kSums], float ridge, float rgb[3], float& dfdc);
/// Adds to the fit the box mean (radius `radius`) of its difference from `reference`, an
/// estimate that keeps energy (the first zero-order candidate, a weighted mean; the mean of
/// the halves when there is none): a linear fit is not a weighted mean and loses energy
/// where the colour is concave in the regressors (a highlight's peak is under-fitted and
/// nothing raises its neighbours in exchange). The difference of two filtered images is
/// mostly that loss, not noise, so giving it back locally keeps the mean of a region much
/// larger than the box without adding the input's noise again. The result is clamped to
/// [lowest, highest], the input's range, as the fit is. Unpadded planes.
void restore_energy(Channels& fit, const Channels& reference, int radius, float lowest,
                    float highest);
}  // namespace first_order

/// Filters each half with weights from the other half's colour and from the features
/// (min of the two, Rousselle et al. 2013, eq. 10), once per candidate. `tick` is called
/// once per finished strip of rows and returns false to stop: the strips not started are
/// then left unfiltered, and the caller, which knows it stopped, discards the result.
Candidates cross_filter(const CrossFilterInput& input, const DenoiseOptions& options,
                        const std::function<bool()>& tick, int* strips);

/// Chooses per pixel among the candidates by their smoothed relative error, smooths the
/// choice and blends, each half with a choice made from the other half's error estimate
/// when options.cross_selection is on (from both halves' otherwise). Returns the RGB mean
/// of the blended halves; `share` gets the fraction each candidate won and `error` (when
/// set) the smoothed relative error estimate of the candidate chosen at each pixel (one
/// channel; with cross_selection the mean of the two halves' choices).
Image select_candidates(const Candidates& candidates, const DenoiseOptions& options,
                        std::vector<double>* share, Image* error = nullptr);

}  // namespace pbrkit::denoising
