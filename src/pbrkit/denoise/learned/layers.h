#pragma once
// The networks of docs/LEARNED_DENOISER.md ("The network", "kpcn-blend-v2"), as data: their
// layer tables, in the table's order (the order of tools/denoiser/model.py's layers()), read
// by the weights file's checks, the forward pass and the tiles' receptive-field radius.
#include <array>
#include <string_view>

namespace pbrkit::learned {

inline constexpr std::string_view kInputTransform = "log1p-autoexposure-v1";
/// log1p(s * RGB), albedo RGB, normal XYZ; kpcn-blend-v2 adds log1p(s * classic RGB).
inline constexpr int kInputChannels = 9;
inline constexpr int kClassicChannels = 3;
inline constexpr int kKernelWidth = 5;  ///< each scale's kernel is 5x5
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

/// kpcn-unet-v1's table.
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

/// kpcn-blend-v2's: kpcn-unet-v1's but for enc0a, which also reads the classic denoiser's
/// output, and head0, whose 27th channel is the logit of the weight of that output in the
/// final blend.
constexpr std::array<LayerSpec, kLayerCount> blend_layers() {
  std::array<LayerSpec, kLayerCount> layers = kLayers;
  layers[kEnc0a].in = kInputChannels + kClassicChannels;
  layers[kHead0].out = kKernelTaps + 2;
  return layers;
}

/// A network this pbrkit runs, named by the weights file's `network`.
struct NetworkSpec {
  std::string_view name;
  std::array<LayerSpec, kLayerCount> layers;
  /// Reads the classic denoiser's output and blends it with the kernels' (kpcn-blend-v2).
  bool blends_classic = false;
  constexpr int input_channels() const { return layers[kEnc0a].in; }
};

inline constexpr std::array<NetworkSpec, 2> kNetworks = {{
    {"kpcn-unet-v1", kLayers, false},
    {"kpcn-blend-v2", blend_layers(), true},
}};

/// The network named `name`, or nullptr.
constexpr const NetworkSpec* find_network(std::string_view name) {
  for (const NetworkSpec& n : kNetworks)
    if (n.name == name) return &n;
  return nullptr;
}

/// The parameter count the contract states (weights and biases of every layer).
constexpr int parameter_count(const std::array<LayerSpec, kLayerCount>& layers) {
  int n = 0;
  for (const LayerSpec& l : layers) n += l.out * l.in * 9 + l.out;
  return n;
}
static_assert(parameter_count(kLayers) == 367325, "docs/LEARNED_DENOISER.md: 367,325 parameters");
static_assert(parameter_count(blend_layers()) == 367325 + 16 * 3 * 9 + 16 * 9 + 1,
              "kpcn-blend-v2: 3 more inputs of enc0a, one more output of head0");

}  // namespace pbrkit::learned
