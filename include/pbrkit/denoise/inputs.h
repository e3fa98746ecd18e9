#pragma once
// Where the denoiser's input comes from: a path tracer's Film (render --denoise, merge
// --denoise) or an EXR written with the `denoise` AOV (pbrkit denoise).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

/// The film's two half buffers of colour, albedo, normal and depth.
DenoiseInput denoise_input(const Film& film);

/// The mean of a DenoiseInput's two half buffers of one quantity (colour, albedo, normal
/// or depth): the render's own image but for the odd half's one sample fewer.
Image mean_of_halves(const Image (&halves)[2]);

/// An EXR without some of the layers the denoiser reads: what() names the file and every
/// missing layer; `layers` lists them, so that a front end can say how it writes them.
class MissingDenoiseLayers : public Error {
 public:
  MissingDenoiseLayers(const std::string& message, std::vector<std::string> missing)
      : Error(message), layers(std::move(missing)) {}
  std::vector<std::string> layers;
};

/// Reads the layers color_a, color_b, albedo_a, ..., depth_b (denoise_layer_names()) of
/// an EXR; MissingDenoiseLayers when any is absent. The normal layers are decoded from
/// 0.5 n + 0.5. The file is read under the input policy of image_io.h (negative, NaN and
/// Inf samples become 0 with a warning naming the file).
DenoiseInput read_denoise_input(const std::filesystem::path& path);

}  // namespace pbrkit
