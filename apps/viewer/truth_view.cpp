#include "truth_view.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <epoxy/gl.h>

#include "pbrkit/core/color.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

ViewMode parse_view_mode(std::string_view name) {
  for (ViewMode m : {ViewMode::kRaster, ViewMode::kPath, ViewMode::kSplit, ViewMode::kDifference})
    if (view_mode_name(m) == name) return m;
  fail("unknown view mode '{}' (raster, path, split, difference)", name);
}

std::string_view view_mode_name(ViewMode mode) {
  switch (mode) {
    case ViewMode::kRaster:
      return "raster";
    case ViewMode::kPath:
      return "path";
    case ViewMode::kSplit:
      return "split";
    case ViewMode::kDifference:
      return "difference";
  }
  return "raster";
}

ErrorView luminance_error(const Image& raster, const Image& truth) {
  ErrorView v;
  if (raster.width != truth.width || raster.height != truth.height) return v;
  v.error = Image(truth.width, truth.height, 1);
  std::vector<float> sorted(truth.pixel_count());
  double sum = 0.0;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      const float yr = luminance(raster.rgb(x, y)), yt = luminance(truth.rgb(x, y));
      const float e = std::fabs(yr - yt) / (std::max(yt, 0.0f) + 0.01f);
      v.error.pixel(x, y)[0] = e;
      sorted[std::size_t(y) * truth.width + x] = e;
      sum += e;
    }
  v.mean = sorted.empty() ? 0.0 : sum / double(sorted.size());
  if (!sorted.empty()) {
    const std::size_t k = std::min(sorted.size() - 1, std::size_t(0.95 * double(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    v.p95 = sorted[k];
  }
  return v;
}

Image split_image(const Image& left, const Image& right, int column) {
  Image out(right.width, right.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      out.set_rgb(x, y, x < column ? left.rgb(x, y) : right.rgb(x, y));
  return out;
}

DisplayTexture::~DisplayTexture() {
  if (texture_) {
    GLuint t = texture_;
    glDeleteTextures(1, &t);
  }
}

void DisplayTexture::upload(const Image& display) {
  std::vector<std::uint8_t> bytes(display.pixel_count() * 4);
  for (int y = 0; y < display.height; ++y)
    for (int x = 0; x < display.width; ++x) {
      const glm::vec3 c = display.rgb(x, y);
      std::uint8_t* p = &bytes[(std::size_t(y) * display.width + x) * 4];
      for (int i = 0; i < 3; ++i)
        p[i] = std::uint8_t(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255.0f));
      p[3] = 255;
    }
  if (!texture_ || width_ != display.width || height_ != display.height) {
    if (texture_) {
      GLuint t = texture_;
      glDeleteTextures(1, &t);
    }
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_RGBA8, display.width, display.height);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    texture_ = t;
    width_ = display.width;
    height_ = display.height;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture_, 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
}

}  // namespace pbrkit
