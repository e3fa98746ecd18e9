#pragma once
// The network of docs/LEARNED_DENOISER.md ("The network (`kpcn-unet-v1`)"), as data: its
// layer table, in the table's order (the order of tools/denoiser/model.py's LAYERS), read by
// the weights file's checks, the forward pass and the tiles' receptive-field radius.
#include <array>
#include <string_view>

namespace pbrkit::learned {

inline constexpr std::string_view kNetworkName = "kpcn-unet-v1";
inline constexpr std::string_view kInputTransform = "log1p-autoexposure-v1";
inline constexpr int kInputChannels = 9;  ///< log1p(s * RGB), albedo RGB, normal XYZ
inline constexpr int kKernelWidth = 5;    ///< each scale's kernel is 5x5
inline constexpr int kKernelTaps = kKernelWidth * kKernelWidth;
inline constexpr int kLevels = 5;      ///< L0 (full resolution) to L4 (1/16)
inline constexpr int kAlignment = 16;  ///< 2^(kLevels - 1): four 2x2 poolings

/// One 3x3 convolution (stride 1, zero padding 1, with a bias; weights OIHW).
struct LayerSpec {
  std::string_view name;
  int in = 0;
  int out = 0;
  int level = 0;     ///< runs at 1 / 2^level of the full resolution
  bool relu = true;  ///< false for the three heads
};

enum Layer {
  kEnc0a,
  kEnc0b,
  kEnc1,
  kEnc2,
  kEnc3,
  kBotA,
  kBotB,
  kDec3a,
  kDec3b,
  kDec2a,
  kDec2b,
  kHead2,
  kDec1a,
  kDec1b,
  kHead1,
  kDec0a,
  kDec0b,
  kHead0,
  kLayerCount
};

inline constexpr std::array<LayerSpec, kLayerCount> kLayers = {{
    {"enc0a", 9, 16, 0},
    {"enc0b", 16, 16, 0},
    {"enc1", 16, 32, 1},
    {"enc2", 32, 48, 2},
    {"enc3", 48, 64, 3},
    {"bot_a", 64, 64, 4},
    {"bot_b", 64, 64, 4},
    {"dec3a", 128, 64, 3},
    {"dec3b", 64, 64, 3},
    {"dec2a", 112, 48, 2},
    {"dec2b", 48, 48, 2},
    {"head2", 48, 25, 2, false},
    {"dec1a", 80, 32, 1},
    {"dec1b", 32, 32, 1},
    {"head1", 32, 26, 1, false},
    {"dec0a", 48, 16, 0},
    {"dec0b", 16, 16, 0},
    {"head0", 16, 26, 0, false},
}};

/// The parameter count the contract states (weights and biases of every layer).
constexpr int parameter_count() {
  int n = 0;
  for (const LayerSpec& l : kLayers) n += l.out * l.in * 9 + l.out;
  return n;
}
static_assert(parameter_count() == 367325, "docs/LEARNED_DENOISER.md: 367,325 parameters");

}  // namespace pbrkit::learned
