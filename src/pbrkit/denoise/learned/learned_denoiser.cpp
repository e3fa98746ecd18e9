#include "pbrkit/denoise/learned_denoiser.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "pbrkit/denoise/learned/input_transform.h"
#include "pbrkit/denoise/learned/kernels.h"
#include "pbrkit/denoise/learned/network.h"
#include "pbrkit/denoise/learned/tiles.h"
#include "pbrkit/denoise/learned/weights_file.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit {

namespace {

using learned::HeadView;
using learned::RgbBuffer;

void check_input(const Image& image, const char* name, const Image& color) {
  if (image.empty()) fail("learned denoiser: the {} image is empty", name);
  if (image.width != color.width || image.height != color.height)
    fail("learned denoiser: the {} image is {}x{}, the colour {}x{}", name, image.width,
         image.height, color.width, color.height);
  if (image.channels < 3)
    fail("learned denoiser: the {} image has {} channel(s), it needs 3 (or 4)", name,
         image.channels);
}

// The output's last guard: max(r0, 0) as the contract says, NaN as 0 and an overflow to
// infinity as the largest float, so that no input, however extreme, gives a value that is
// not finite.
inline float finite_non_negative(float v) {
  if (std::isnan(v) || v <= 0.0f) return 0.0f;
  return std::min(v, std::numeric_limits<float>::max());
}

// One tile, through the network and the kernels: r0 at the tile's (padded) size.
RgbBuffer denoise_tile(const learned::Network& network, learned::NetworkWorkspace& workspace,
                       const learned::Tile& tile, const Image& color, const Image& albedo,
                       const Image& normal, const Image* classic, double exposure, int threads,
                       const std::function<bool(learned::Layer)>& keep_going, bool* stopped) {
  const int w = tile.width(), h = tile.height();
  const int channels = network.spec().input_channels();
  const bool blend = network.spec().blends_classic;
  RgbBuffer c0(w, h);
  RgbBuffer k0(blend ? w : 0, blend ? h : 0);
  // Past the image, its last column and row repeated (docs/LEARNED_DENOISER.md, "Padding").
  const auto write_input = [&](float* input) {
    pbrkit::parallel_for(0, h, [&](int j) {
      const int y = std::min(tile.ey0 + j, color.height - 1);
      for (int i = 0; i < w; ++i) {
        const int x = std::min(tile.ex0 + i, color.width - 1);
        const std::size_t p = std::size_t(j) * w + i;
        learned::network_input_pixel(color, albedo, normal, exposure, x, y, input + p * channels,
                                     c0.at(i, j));
        if (blend)
          learned::classic_input_pixel(*classic, exposure, x, y,
                                       input + p * channels + learned::kInputChannels, k0.at(i, j));
      }
    });
  };
  const learned::NetworkHeads heads =
      network.run(workspace, w, h, write_input, threads, keep_going);
  *stopped = heads.stopped;
  if (heads.stopped) return {};
  const HeadView head0{heads.head0, network.spec().layers[learned::kHead0].out};
  const HeadView head1{heads.head1, learned::kKernelTaps + 1};
  const HeadView head2{heads.head2, learned::kKernelTaps};

  // r2 = d2; r1 = d1 - a1 U(D(d1)) + a1 U(r2); r0 = d0 - a0 U(D(d0)) + a0 U(r1).
  RgbBuffer r1;
  {
    const RgbBuffer c1 = learned::box_down(c0);
    const RgbBuffer r2 = learned::apply_kernels(head2, learned::box_down(c1));
    r1 = learned::blend_scales(learned::apply_kernels(head1, c1), head1, r2);
  }
  const RgbBuffer d0 = learned::apply_kernels(head0, c0);
  const RgbBuffer r0 = learned::blend_scales(d0, head0, r1);
  return blend ? learned::blend_classic(r0, head0, k0) : r0;
}

}  // namespace

std::filesystem::path default_learned_denoiser_weights() {
  return data_dir() / "denoiser" / "kpcn-blend-v2.pbnn";
}

struct LearnedDenoiser::Impl {
  LearnedWeightsInfo info;
  learned::Network network;
  int tile = kDefaultLearnedDenoiserTile;
  int threads = 0;

  explicit Impl(const learned::NetworkWeights& weights) : info(weights.info), network(weights) {}
};

LearnedDenoiser::LearnedDenoiser(const LearnedDenoiserOptions& options) {
  if (options.tile < 0) fail("learned denoiser: tile {} is negative", options.tile);
  if (options.threads < 0) fail("learned denoiser: threads {} is negative", options.threads);
  const std::filesystem::path path =
      options.weights.empty() ? default_learned_denoiser_weights() : options.weights;
  impl_ = std::make_unique<Impl>(learned::read_weights_file(path));
  if (options.tile > 0) impl_->tile = learned::Tile::round_up(options.tile);
  impl_->threads = options.threads;
}

LearnedDenoiser::~LearnedDenoiser() = default;
LearnedDenoiser::LearnedDenoiser(LearnedDenoiser&&) noexcept = default;
LearnedDenoiser& LearnedDenoiser::operator=(LearnedDenoiser&&) noexcept = default;

const LearnedWeightsInfo& LearnedDenoiser::info() const {
  return impl_->info;
}

bool LearnedDenoiser::blends_classic() const {
  return impl_->network.spec().blends_classic;
}

Image LearnedDenoiser::denoise(const Image& color, const Image& albedo, const Image& normal,
                               const ProgressCallback& progress, LearnedDenoiseStats* stats) const {
  if (blends_classic())
    fail("learned denoiser: {} ({}) needs the classic denoiser's output of the image too",
         impl_->info.file.string(), impl_->info.network);
  return denoise(color, albedo, normal, Image{}, progress, stats);
}

Image LearnedDenoiser::denoise(const Image& color, const Image& albedo, const Image& normal,
                               const Image& classic, const ProgressCallback& progress,
                               LearnedDenoiseStats* stats) const {
  check_input(color, "colour", color);
  check_input(albedo, "albedo", color);
  check_input(normal, "normal", color);
  if (blends_classic()) check_input(classic, "classic denoiser's", color);
  const auto start = std::chrono::steady_clock::now();
  LearnedDenoiseStats local;
  LearnedDenoiseStats& st = stats ? *stats : local;
  st = {};
  Image out(color.width, color.height, 3);

  const auto run = [&] {
    st.exposure = learned::autoexposure(color);
    const std::vector<learned::Tile> tiles =
        learned::plan_tiles(color.width, color.height, impl_->tile);
    learned::NetworkWorkspace workspace;  // reused by every tile
    for (std::size_t i = 0; i < tiles.size(); ++i) {
      if (progress && !progress(double(i) / double(tiles.size()),
                                fmt::format("tile {}/{}", i + 1, tiles.size()))) {
        st.interrupted = true;
        return;
      }
      const learned::Tile& tile = tiles[i];
      // Asked again before each layer: a stop is seen within one convolution.
      const auto keep_going = [&](learned::Layer layer) {
        return !progress ||
               progress((double(i) + double(int(layer)) / double(int(learned::kLayerCount))) /
                            double(tiles.size()),
                        fmt::format("tile {}/{}", i + 1, tiles.size()));
      };
      bool stopped = false;
      const RgbBuffer r0 = denoise_tile(impl_->network, workspace, tile, color, albedo, normal,
                                        blends_classic() ? &classic : nullptr, st.exposure,
                                        impl_->threads, keep_going, &stopped);
      if (stopped) {
        st.interrupted = true;
        return;
      }
      pbrkit::parallel_for(tile.y0, tile.y1, [&](int y) {
        for (int x = tile.x0; x < tile.x1; ++x) {
          const float* r = r0.at(x - tile.ex0, y - tile.ey0);
          float* o = out.pixel(x, y);
          for (int c = 0; c < 3; ++c) o[c] = finite_non_negative(r[c]);
        }
      });
      ++st.tiles;
    }
    if (progress) progress(1.0, "done");
  };
  if (impl_->threads > 0) {
    tbb::task_arena arena(impl_->threads);
    arena.execute(run);
  } else {
    run();
  }

  if (st.interrupted) {
    // What it has that could not pass for a denoised image: the input, undenoised.
    for (int y = 0; y < color.height; ++y)
      for (int x = 0; x < color.width; ++x)
        for (int c = 0; c < 3; ++c)
          out.pixel(x, y)[c] = learned::sanitize_color(color.pixel(x, y)[c]);
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace pbrkit
