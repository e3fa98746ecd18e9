#include "pbrkit/denoise/learned/tiles.h"

#include <algorithm>

#include "../tile_spans.h"

namespace pbrkit::learned {

std::vector<Tile> plan_tiles(int width, int height, int tile) {
  tile = Tile::round_up(std::max(tile, 1));
  std::vector<Tile> tiles;
  for (const auto& [y0, y1] : denoising::tile_spans(height, tile, kAlignment))
    for (const auto& [x0, x1] : denoising::tile_spans(width, tile, kAlignment)) {
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
