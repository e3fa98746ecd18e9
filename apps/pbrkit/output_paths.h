#pragma once
// The image outputs of `render` and `merge`: one -o path, a PNG or an EXR, and the other
// written beside it with the same stem.
#include <string>
#include <string_view>

namespace pbrkit::cli {

struct ImageOutputs {
  std::string png;  ///< tone-mapped, 8-bit sRGB
  std::string exr;  ///< linear
};

/// "out/x.png" or "out/x.exr" (any case) -> both paths. Any other extension (or none) is
/// an Error naming `flag` and the path, before any work is done.
ImageOutputs image_outputs(const std::string& output, std::string_view flag = "-o");

/// Creates the directory the outputs go into (nothing for a bare file name).
void create_output_directory(const ImageOutputs& outputs);

}  // namespace pbrkit::cli
