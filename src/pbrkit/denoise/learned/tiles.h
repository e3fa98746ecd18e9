#pragma once
// The learned denoiser's tiles (docs/LEARNED_DENOISER.md, "Tiles"): inner rectangles on a
// grid of multiples of 16, each run extended by kTileMargin on every side that has image.
#include <vector>

#include "pbrkit/denoise/learned/layers.h"

namespace pbrkit::learned {

/// The output's receptive-field radius, in full-resolution pixels: the farthest input
/// pixel (along x or y) that can change an output pixel. Derivation, from kLayers:
/// - a 3x3 convolution at level l reaches 2^l pixels further. The longest path to the
///   output is the one through head0 (every layer but head1 and head2): 5 convolutions at
///   L0 (enc0a, enc0b, dec0a, dec0b, head0), 3 at each of L1, L2, L3 (enc, deca, decb) and 2
///   at L4 (bot_a, bot_b): 5*1 + 3*2 + 3*4 + 3*8 + 2*16 = 79;
/// - pooling and nearest upsampling move by whole cells: a level-4 cell covers 16 pixels,
///   so a pixel's cell reaches up to 15 pixels past it on one side, 94 for head0;
/// - the scale compositor's D(d0) reads the other pixel of the 2x2 cell, whose head0 reaches
///   one pixel further: 95. The colour the kernels read lies far inside (at most 2 cells of
///   L2 around a pixel's 4x4 cell: 11 pixels); head1 and head2 have fewer L0 and L1 layers.
/// Checked by interval propagation over the 16 alignments of a pixel (the worst is 95, at
/// x = 0 and 15 mod 16) and by tests/denoise/learned_denoiser_test.cpp, which changes one
/// input pixel and finds no output pixel beyond this radius changed.
constexpr int receptive_field_radius() {
  int reach = 0;
  for (const LayerSpec& l : kLayers)
    if (l.name != "head1" && l.name != "head2") reach += 1 << l.level;
  return reach + (kAlignment - 1) + 1;
}
static_assert(receptive_field_radius() == 95);

/// The margin each tile runs with: the radius rounded up to a multiple of 16, so that an
/// extended tile starts on the pooling grid (its origin is a multiple of 16) and sees every
/// input pixel its inner pixels see in the whole image.
inline constexpr int kTileMargin =
    (receptive_field_radius() + kAlignment - 1) / kAlignment * kAlignment;
static_assert(kTileMargin == 96);

struct Tile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the inner rectangle [x0, x1) x [y0, y1)
  /// The rectangle the network runs on: the inner one extended by kTileMargin, clamped to
  /// the image; its origin is a multiple of 16.
  int ex0 = 0, ey0 = 0, ex1 = 0, ey1 = 0;
  /// The network's input size: the extended rectangle rounded up to multiples of 16 (the
  /// rows and columns past the image repeat its last ones, as the whole image is padded).
  int width() const { return round_up(ex1 - ex0); }
  int height() const { return round_up(ey1 - ey0); }
  static constexpr int round_up(int v) { return (v + kAlignment - 1) / kAlignment * kAlignment; }
};

/// The tiles covering a width x height image with inner squares of side at most `tile`
/// (rounded up to a multiple of 16): ceil(width / tile) columns of equal width (rounded up
/// to a multiple of 16, the last one narrower), the same for the rows. Row-major order.
std::vector<Tile> plan_tiles(int width, int height, int tile);

}  // namespace pbrkit::learned
