#pragma once
// How both denoisers cut an image into tiles along one axis.
#include <algorithm>
#include <utility>
#include <vector>

namespace pbrkit::denoising {

/// [start, end) of each of the ceil(size / tile) spans covering [0, size), of equal lengths
/// rounded up to a multiple of `align` (the last one shorter): fewer, evener tiles than
/// cutting at every `tile` pixels, so less of the margins around them is repeated.
inline std::vector<std::pair<int, int>> tile_spans(int size, int tile, int align) {
  const int count = (size + tile - 1) / tile;
  const int even = (size + count - 1) / count;
  const int length = (even + align - 1) / align * align;
  std::vector<std::pair<int, int>> out;
  for (int start = 0; start < size; start += length)
    out.emplace_back(start, std::min(start + length, size));
  return out;
}

}  // namespace pbrkit::denoising
