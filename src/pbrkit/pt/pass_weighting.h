#pragma once
// A guided render's image (PathTracerSettings::guiding): its training passes weighted by
// their sample counts. Pass k samples with the guide learned in pass k - 1 (pass k has 2^k
// samples per pixel, its guide learned from half as many), so the early passes are noisier
// than the late ones. Weighting every sample alike, as a film does, lets the passes guided by
// a guide learned from a few samples carry about half of the image; keeping the last pass
// only (Mueller, Gross & Novak 2017, section 5) throws that half away; the later "inverse
// variance" combination (Mueller 2019, "Practical Path Guiding in Production", SIGGRAPH
// course notes) weights each pass by 1 / its image's estimated variance, which is biased
// (the weights depend on the samples they weight) and, estimated from 2 or 4 samples a
// pixel, far too low for the early passes of a scene lit by rare paths: those passes got the
// largest weights on `interior`. Here a sample of pass k has the weight n_k, its pass's
// sample count (as if each pass halved the variance per sample; where the guide has stopped
// improving this keeps 78% of the equal weights' efficiency): weights fixed by the schedule
// before any sample is taken, so the image stays unbiased and deterministic.
//
// The film's sums are rewritten after every pass so that sum / count is the average of its
// two half buffers' weighted means and sum_even / ceil(n / 2) the even half's: the film's
// counts stay the samples taken, and everything that reads a film (adaptive sampling, the
// noise estimate, checkpoints, the denoiser's half buffers) reads the weighted image.
//
// Private to the path tracer.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/pt/film.h"

namespace pbrkit {

class PassWeighting {
 public:
  /// `film`: what the render starts from; each pixel's samples already in it (a resumed
  /// checkpoint) count as one pass of that many samples.
  explicit PassWeighting(const Film& film);

  /// One sample of the current pass at pixel `i` (its film count is updated by the caller):
  /// `even`, whether it goes to the even half buffer. Pixels are written by one thread each.
  void add(std::size_t i, glm::vec3 L, bool even) { pass_[even ? 0 : 1][i] += L; }

  /// The end of a pass (complete or stopped), its samples weighted by `weight`: folded into
  /// `film`'s sums.
  void end_pass(Film& film, float weight);

 private:
  // The current pass: per half buffer the sum of its samples, and the film's count when it
  // began.
  std::vector<glm::vec3> pass_[2];
  std::vector<float> start_count_;
  // The passes folded so far: per half buffer sum_k w_k S_k and sum_k w_k n_k.
  std::vector<glm::vec3> weighted_[2];
  std::vector<float> weight_[2];
  std::uint32_t sample_begin_ = 0;
};

}  // namespace pbrkit
