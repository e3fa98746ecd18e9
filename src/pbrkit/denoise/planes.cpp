#include "planes.h"

#include <algorithm>

#include "pbrkit/util/parallel.h"

namespace pbrkit::denoising {

Plane plane_from(const Image& image, int c, int pad) {
  Plane plane(image.width, image.height, pad);
  for (int y = 0; y < image.height; ++y) {
    float* dst = plane.row(y);
    const float* src = image.data.data() + std::size_t(y) * image.width * image.channels + c;
    for (int x = 0; x < image.width; ++x) dst[x] = src[std::size_t(x) * image.channels];
  }
  fill_padding(plane);
  return plane;
}

void fill_padding(Plane& plane) {
  const int w = plane.width, h = plane.height, p = plane.pad;
  for (int y = 0; y < h; ++y) {
    float* r = plane.row(y);
    for (int x = -p; x < 0; ++x) r[x] = r[0];
    for (int x = w; x < w + p; ++x) r[x] = r[w - 1];
  }
  for (int y = -p; y < 0; ++y) std::copy_n(plane.row(0) - p, plane.stride, plane.row(y) - p);
  for (int y = h; y < h + p; ++y) std::copy_n(plane.row(h - 1) - p, plane.stride, plane.row(y) - p);
}

Plane box_filter(const Plane& in, int r) {
  Plane out(in.width, in.height, in.pad);
  const int w = in.width;
  const float norm = 1.0f / float((2 * r + 1) * (2 * r + 1));
  pbrkit::parallel_for(
      tbb::blocked_range<int>(0, in.height, 16), [&](const tbb::blocked_range<int>& range) {
        std::vector<float> column(std::size_t(w), 0.0f);
        for (int y = range.begin(); y < range.end(); ++y) {
          std::fill(column.begin(), column.end(), 0.0f);
          for (int j = -r; j <= r; ++j) {
            const float* s = in.row(std::clamp(y + j, -in.pad, in.height + in.pad - 1));
            // Sum of the row segment around each x (direct, r is small).
            for (int x = 0; x < w; ++x) {
              float acc = 0.0f;
              for (int i = -r; i <= r; ++i) acc += s[x + i];
              column[std::size_t(x)] += acc;
            }
          }
          float* d = out.row(y);
          for (int x = 0; x < w; ++x) d[x] = column[std::size_t(x)] * norm;
        }
      });
  fill_padding(out);
  return out;
}

void patch_distance(const std::vector<const Plane*>& guide,
                    const std::vector<const Plane*>& variance, int dx, int dy, int patch_radius,
                    int y0, int y1, float* out, std::vector<float>& scratch, bool symmetric) {
  const int f = patch_radius;
  const int w = guide.front()->width;
  const int tw = w + 2 * f;        // term row width: x in [-f, w + f)
  const int th = y1 - y0 + 2 * f;  // term rows: y in [y0 - f, y1 + f)
  scratch.assign(std::size_t(tw) * th * 2, 0.0f);
  float* term = scratch.data();
  float* horizontal = scratch.data() + std::size_t(tw) * th;
  const int channels = int(guide.size());
  const bool shared_variance = variance.size() == 1;
  const float inv_channels = 1.0f / float(channels);
  constexpr float kEps = 1e-10f;
  for (int j = 0; j < th; ++j) {
    const int y = y0 - f + j;
    float* t = term + std::size_t(j) * tw + f;  // t[x] for x in [-f, w + f)
    for (int c = 0; c < channels; ++c) {
      if (c == 0) std::fill_n(t - f, tw, 0.0f);
      const float* up = guide[std::size_t(c)]->row(y);
      const float* uq = guide[std::size_t(c)]->row(y + dy) + dx;
      const Plane* vplane = variance[shared_variance ? 0 : std::size_t(c)];
      const float* vp = vplane->row(y);
      const float* vq = vplane->row(y + dy) + dx;
      for (int x = -f; x < w + f; ++x) {
        const float d = up[x] - uq[x];
        const float a = vp[x], b = vq[x];
        const float v = (d * d - (a + (symmetric ? b : std::min(a, b)))) / (kEps + a + b);
        t[x] += v * inv_channels;
      }
    }
  }
  // Box over the patch: horizontally, then vertically.
  for (int j = 0; j < th; ++j) {
    const float* t = term + std::size_t(j) * tw + f;
    float* hrow = horizontal + std::size_t(j) * w;
    for (int x = 0; x < w; ++x) {
      float acc = 0.0f;
      for (int i = -f; i <= f; ++i) acc += t[x + i];
      hrow[x] = acc;
    }
  }
  const float norm = 1.0f / float((2 * f + 1) * (2 * f + 1));
  for (int y = y0; y < y1; ++y) {
    float* o = out + std::size_t(y - y0) * w;
    const int j0 = y - y0;  // term row of y - f
    for (int x = 0; x < w; ++x) o[x] = 0.0f;
    for (int j = 0; j <= 2 * f; ++j) {
      const float* hrow = horizontal + std::size_t(j0 + j) * w;
      for (int x = 0; x < w; ++x) o[x] += hrow[x];
    }
    for (int x = 0; x < w; ++x) o[x] *= norm;
  }
}

}  // namespace pbrkit::denoising
