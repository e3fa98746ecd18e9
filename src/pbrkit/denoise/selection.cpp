// Selection among the candidate filters (Rousselle et al. 2013, section 4.3): the SURE
// error estimates are noisy per pixel, so they are smoothed (as relative errors, the
// metric the benchmark reports) before the per-pixel best candidate is chosen, and the
// binary choice is smoothed before blending so that no seam shows where it changes.
// Every step is a convex combination of the candidates: the result stays a weighted mean
// of input pixels.
#include <algorithm>

#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

Image select_candidates(const Candidates& candidates, const DenoiseOptions& options,
                        std::vector<double>* share) {
  const int k_count = int(candidates.color.size());
  const int w = candidates.error.front().width, h = candidates.error.front().height;
  const int er = std::max(0, options.error_radius), sr = std::max(0, options.selection_radius);
  // Relative errors: err / (m^2 + 0.01) with m the mean over candidates and channels.
  std::vector<Plane> relative;
  for (int k = 0; k < k_count; ++k) relative.emplace_back(w, h, er);
  pbrkit::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float m = 0.0f;
      for (int k = 0; k < k_count; ++k)
        for (int c = 0; c < 3; ++c) m += candidates.color[std::size_t(k)][std::size_t(c)].at(x, y);
      m /= float(3 * k_count);
      const float inv = 1.0f / (m * m + 0.01f);
      for (int k = 0; k < k_count; ++k)
        relative[std::size_t(k)].at(x, y) = candidates.error[std::size_t(k)].at(x, y) * inv;
    }
  });
  for (Plane& p : relative) {
    fill_padding(p);
    if (er > 0) p = box_filter(p, er);
  }
  std::vector<Plane> choice;
  for (int k = 0; k < k_count; ++k) choice.emplace_back(w, h, sr);
  std::vector<std::size_t> wins(std::size_t(k_count), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int best = 0;
      for (int k = 1; k < k_count; ++k)
        if (relative[std::size_t(k)].at(x, y) < relative[std::size_t(best)].at(x, y)) best = k;
      choice[std::size_t(best)].at(x, y) = 1.0f;
      ++wins[std::size_t(best)];
    }
  for (Plane& p : choice) {
    fill_padding(p);
    if (sr > 0) p = box_filter(p, sr);
  }
  Image out(w, h, 3);
  pbrkit::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float total = 0.0f, rgb[3] = {0.0f, 0.0f, 0.0f};
      for (int k = 0; k < k_count; ++k) {
        const float s = choice[std::size_t(k)].at(x, y);
        total += s;
        for (int c = 0; c < 3; ++c)
          rgb[c] += s * candidates.color[std::size_t(k)][std::size_t(c)].at(x, y);
      }
      float* px = out.pixel(x, y);
      for (int c = 0; c < 3; ++c) px[c] = rgb[c] / total;  // total > 0: the box of a one-hot
    }
  });
  if (share) {
    share->assign(std::size_t(k_count), 0.0);
    for (int k = 0; k < k_count; ++k)
      (*share)[std::size_t(k)] = double(wins[std::size_t(k)]) / double(std::size_t(w) * h);
  }
  return out;
}

}  // namespace pbrkit::denoising
