#include "pbrkit/denoise/learned/tiles.h"

#include <algorithm>

namespace pbrkit::learned {

namespace {

// [start, end) of each of the ceil(size / tile) spans covering [0, size), of equal
// lengths rounded up to a multiple of 16 (the last shorter): fewer, evener tiles than
// cutting at every `tile` pixels, so less of the margins is repeated.
std::vector<std::pair<int, int>> spans(int size, int tile) {
  const int count = (size + tile - 1) / tile;
  const int length = Tile::round_up((size + count - 1) / count);
  std::vector<std::pair<int, int>> out;
  for (int start = 0; start < size; start += length)
    out.emplace_back(start, std::min(start + length, size));
  return out;
}

}  // namespace

std::vector<Tile> plan_tiles(int width, int height, int tile) {
  tile = Tile::round_up(std::max(tile, 1));
  std::vector<Tile> tiles;
  for (const auto& [y0, y1] : spans(height, tile))
    for (const auto& [x0, x1] : spans(width, tile)) {
      Tile t;
      t.x0 = x0, t.x1 = x1, t.y0 = y0, t.y1 = y1;
      t.ex0 = std::max(x0 - kTileMargin, 0);
      t.ey0 = std::max(y0 - kTileMargin, 0);
      t.ex1 = std::min(x1 + kTileMargin, width);
      t.ey1 = std::min(y1 + kTileMargin, height);
      tiles.push_back(t);
    }
  return tiles;
}

}  // namespace pbrkit::learned
