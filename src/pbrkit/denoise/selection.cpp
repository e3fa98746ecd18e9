// Selection among the candidate filters (Rousselle et al. 2013, section 4.3): the SURE
// error estimates are noisy per pixel, so they are smoothed (as relative errors, the
// metric the benchmark reports) before the per-pixel best candidate is chosen, and the
// binary choice is smoothed before blending so that no seam shows where it changes.
//
// By default one choice, from the mean of both halves' estimates, blends both halves.
// With options.cross_selection each half is blended with a choice made from the OTHER
// half's estimates, as its weights come from the other half's colour: SURE at p contains
// |F(p) - c_p|^2 with c_p the data being filtered, so a choice made from half a's own
// estimate avoids, around a bright sample of half a, the candidates that received its
// energy. Measured on the heavy-tailed benchmark scenes it moved more energy, not less
// (docs/DENOISER.md, "Energy under heavy-tailed noise"), so it is off.
// Every step is a convex combination of the candidates: the result stays a weighted mean
// of input pixels.
#include <algorithm>

#include "pbrkit/util/parallel.h"
#include "stages.h"

namespace pbrkit::denoising {

namespace {
// The smoothed one-hot choice among the candidates from their errors `error` relative to
// the level of `color` (the mean over candidates and channels): per candidate a plane in
// [0, 1] summing to 1 over the candidates. `wins` gets each candidate's pixel count;
// `chosen` (when set) adds `weight` times the smoothed relative error of the candidate
// chosen at each pixel, clamped at 0 (SURE less the variance can be negative).
std::vector<Plane> choose(const std::vector<const Channels*>& color,
                          const std::vector<const Plane*>& error, const DenoiseOptions& options,
                          std::vector<std::size_t>& wins, Image* chosen = nullptr,
                          float weight = 1.0f) {
  const int k_count = int(color.size());
  const int w = error.front()->width, h = error.front()->height;
  const int er = std::max(0, options.error_radius), sr = std::max(0, options.selection_radius);
  // Relative errors: err / (m^2 + 0.01).
  std::vector<Plane> relative;
  for (int k = 0; k < k_count; ++k) relative.emplace_back(w, h, er);
  pbrkit::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float m = 0.0f;
      for (int k = 0; k < k_count; ++k)
        for (int c = 0; c < 3; ++c) m += (*color[std::size_t(k)])[std::size_t(c)].at(x, y);
      m /= float(3 * k_count);
      const float inv = 1.0f / (m * m + 0.01f);
      for (int k = 0; k < k_count; ++k)
        relative[std::size_t(k)].at(x, y) = error[std::size_t(k)]->at(x, y) * inv;
    }
  });
  for (Plane& p : relative) {
    fill_padding(p);
    if (er > 0) p = box_filter(p, er);
  }
  std::vector<Plane> choice;
  for (int k = 0; k < k_count; ++k) choice.emplace_back(w, h, sr);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int best = 0;
      for (int k = 1; k < k_count; ++k)
        if (relative[std::size_t(k)].at(x, y) < relative[std::size_t(best)].at(x, y)) best = k;
      choice[std::size_t(best)].at(x, y) = 1.0f;
      ++wins[std::size_t(best)];
      if (chosen)
        chosen->pixel(x, y)[0] += weight * std::max(0.0f, relative[std::size_t(best)].at(x, y));
    }
  for (Plane& p : choice) {
    fill_padding(p);
    if (sr > 0) p = box_filter(p, sr);
  }
  return choice;
}

// Adds weight * sum_k choice_k color_k / sum_k choice_k to `out`.
void blend(const std::vector<Plane>& choice, const std::vector<const Channels*>& color,
           float weight, Image& out) {
  const int w = out.width, h = out.height;
  pbrkit::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float total = 0.0f, rgb[3] = {0.0f, 0.0f, 0.0f};
      for (std::size_t k = 0; k < choice.size(); ++k) {
        const float s = choice[k].at(x, y);
        total += s;
        for (int c = 0; c < 3; ++c) rgb[c] += s * (*color[k])[std::size_t(c)].at(x, y);
      }
      float* px = out.pixel(x, y);
      for (int c = 0; c < 3; ++c) px[c] += weight * rgb[c] / total;  // total > 0: a one-hot's box
    }
  });
}
}  // namespace

Image select_candidates(const Candidates& candidates, const DenoiseOptions& options,
                        std::vector<double>* share, Image* error_out) {
  const std::size_t k_count = candidates.size();
  const int w = candidates.error[0].front().width, h = candidates.error[0].front().height;
  std::vector<const Channels*> color[2];
  std::vector<const Plane*> error[2];
  for (int half = 0; half < 2; ++half)
    for (std::size_t k = 0; k < k_count; ++k) {
      color[half].push_back(&candidates.color[half][k]);
      error[half].push_back(&candidates.error[half][k]);
    }
  std::vector<std::size_t> wins(k_count, 0);
  Image out(w, h, 3);
  if (error_out) *error_out = Image(w, h, 1);
  std::size_t choices = 0;
  if (options.cross_selection) {
    for (int half = 0; half < 2; ++half) {
      const int other = 1 - half;
      blend(choose(color[other], error[other], options, wins, error_out, 0.5f), color[half], 0.5f,
            out);
    }
    choices = 2;
  } else {
    // One choice for both halves from both halves' estimates (their mean).
    std::vector<Channels> mean_color(k_count);
    std::vector<Plane> mean_error;
    std::vector<const Channels*> mean_color_ptr;
    std::vector<const Plane*> mean_error_ptr;
    for (std::size_t k = 0; k < k_count; ++k) {
      for (int c = 0; c < 3; ++c) {
        Plane m(w, h, 0);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            m.at(x, y) = 0.5f * (candidates.color[0][k][std::size_t(c)].at(x, y) +
                                 candidates.color[1][k][std::size_t(c)].at(x, y));
        mean_color[k].push_back(std::move(m));
      }
      Plane e(w, h, 0);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          e.at(x, y) = 0.5f * (candidates.error[0][k].at(x, y) + candidates.error[1][k].at(x, y));
      mean_error.push_back(std::move(e));
    }
    for (std::size_t k = 0; k < k_count; ++k) {
      mean_color_ptr.push_back(&mean_color[k]);
      mean_error_ptr.push_back(&mean_error[k]);
    }
    const std::vector<Plane> choice =
        choose(mean_color_ptr, mean_error_ptr, options, wins, error_out);
    blend(choice, mean_color_ptr, 1.0f, out);
    choices = 1;
  }
  if (share) {
    share->assign(k_count, 0.0);
    for (std::size_t k = 0; k < k_count; ++k)
      (*share)[k] = double(wins[k]) / double(choices * std::size_t(w) * std::size_t(h));
  }
  return out;
}

}  // namespace pbrkit::denoising
