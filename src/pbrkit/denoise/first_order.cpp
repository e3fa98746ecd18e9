// The first-order candidates' per-pixel solve (Bitterli et al. 2016, "Nonlinearly Weighted
// First-order Regression for Denoising Monte Carlo Renderings", EGSR 2016). Instead of
// averaging the neighbours that look alike, the colour is fitted as a linear function of
// the shading normal, the depth and the screen position over the window, with the cross
// filter's weights, and the fit's value at the pixel is the output. On curved surfaces shading
// follows the normal smoothly, so the normal need not keep the window small (as a feature
// weight it must, or the average mixes shades); albedo and depth stay weights, since
// across their edges nothing is linear. cross_filter.cpp accumulates the sums.
#include <algorithm>
#include <cmath>

#include "stages.h"

namespace pbrkit::denoising::first_order {

void solve(const float sums[kSums], float ridge, float rgb[3], float& dfdc) {
  double a[kDim][kDim];
  int k = 0;
  for (int i = 0; i < kDim; ++i)
    for (int j = i; j < kDim; ++j) a[i][j] = a[j][i] = double(sums[k++]);
  const double weight = a[0][0];  // >= 1: the pixel itself weighs 1
  for (int i = 1; i < kDim; ++i) a[i][i] += double(ridge) * weight;
  // Right-hand sides: the three channels and e0 (A^-1 e0 gives [A^-1]_00).
  double b[kDim][4];
  for (int i = 0; i < kDim; ++i) b[i][3] = i == 0 ? 1.0 : 0.0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kDim; ++i) b[i][c] = double(sums[kUpper + c * kDim + i]);
  // Cholesky, A = L L^T.
  double l[kDim][kDim] = {};
  for (int i = 0; i < kDim; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = a[i][j];
      for (int m = 0; m < j; ++m) s -= l[i][m] * l[j][m];
      if (i == j) {
        if (!(s > 1e-12 * weight)) {
          // Not positive definite (cannot happen with a positive ridge, but a NaN-free
          // answer matters more): the weighted mean.
          for (int c = 0; c < 3; ++c) rgb[c] = float(b[0][c] / weight);
          dfdc = float(1.0 / weight);
          return;
        }
        l[i][i] = std::sqrt(s);
      } else {
        l[i][j] = s / l[j][j];
      }
    }
  for (int c = 0; c < 4; ++c) {
    double y[kDim];
    for (int i = 0; i < kDim; ++i) {
      double s = b[i][c];
      for (int m = 0; m < i; ++m) s -= l[i][m] * y[m];
      y[i] = s / l[i][i];
    }
    for (int i = kDim - 1; i >= 0; --i) {
      double s = y[i];
      for (int m = i + 1; m < kDim; ++m) s -= l[m][i] * b[m][c];
      b[i][c] = s / l[i][i];
    }
  }
  for (int c = 0; c < 3; ++c) rgb[c] = float(b[0][c]);
  dfdc = float(b[0][3]);
}

void restore_energy(Channels& fit, const Channels& reference, int radius, float lowest,
                    float highest) {
  if (radius <= 0) return;
  const int w = fit.front().width, h = fit.front().height;
  for (std::size_t c = 0; c < fit.size(); ++c) {
    Plane residual(w, h, radius);
    Plane& f = fit[c];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) residual.at(x, y) = reference[c].at(x, y) - f.at(x, y);
    fill_padding(residual);
    const Plane local = box_filter(residual, radius);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        f.at(x, y) = std::clamp(f.at(x, y) + local.at(x, y), lowest, highest);
  }
}

}  // namespace pbrkit::denoising::first_order
