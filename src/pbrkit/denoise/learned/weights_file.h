#pragma once
// The learned denoiser's weights file (docs/LEARNED_DENOISER.md, "The weights file"; the
// writer is tools/denoiser/model.py's write_weights): read and checked whole, every
// refusal a pbrkit::Error naming the file and the problem.
#include <array>
#include <filesystem>
#include <vector>

#include "pbrkit/denoise/learned/layers.h"
#include "pbrkit/denoise/learned_denoiser.h"

namespace pbrkit::learned {

/// One convolution's parameters, as PyTorch stores them.
struct ConvWeights {
  std::vector<float> weight;  ///< [out][in][3][3] (OIHW)
  std::vector<float> bias;    ///< [out]
};

struct NetworkWeights {
  LearnedWeightsInfo info;
  const NetworkSpec* spec = &kNetworks[0];      ///< the header's network (static)
  std::array<ConvWeights, kLayerCount> layers;  ///< in spec->layers' order
};

/// Reads `path`. Throws pbrkit::Error ("<path>: <problem>") for a missing or unreadable
/// file, a wrong magic or format version, a header that is not JSON or lacks a field (or
/// has one of the wrong type), another network or input transform, a tensor missing, of
/// another shape, lying outside the data or holding a non-finite value, a file shorter
/// than its data, or a CRC-32 mismatch. Tensors the network does not use are ignored.
NetworkWeights read_weights_file(const std::filesystem::path& path);

}  // namespace pbrkit::learned
