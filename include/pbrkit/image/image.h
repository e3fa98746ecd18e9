#pragma once
// Image: a float image in linear scene-referred RGB(A), row 0 at the top, channels
// interleaved. The one pixel container every module shares (loaders, baker, film, GL
// readback).
#include <cassert>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;         ///< 1, 2, 3 or 4
  std::vector<float> data;  ///< width * height * channels floats, row-major, top row first

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(std::size_t(w) * h * c, fill) {}

  bool empty() const { return data.empty(); }
  std::size_t pixel_count() const { return std::size_t(width) * height; }

  float* pixel(int x, int y) {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return data.data() + (std::size_t(y) * width + x) * channels;
  }
  const float* pixel(int x, int y) const {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return data.data() + (std::size_t(y) * width + x) * channels;
  }
  /// RGB of a pixel (a 1-channel image is grey; a 2-channel one has blue = 0).
  glm::vec3 rgb(int x, int y) const {
    const float* p = pixel(x, y);
    if (channels == 1) return glm::vec3(p[0]);
    if (channels == 2) return glm::vec3(p[0], p[1], 0.0f);
    return glm::vec3(p[0], p[1], p[2]);
  }
  void set_rgb(int x, int y, glm::vec3 c) {
    float* p = pixel(x, y);
    for (int i = 0; i < channels && i < 3; ++i) p[i] = c[i];
  }
};

}  // namespace pbrkit
