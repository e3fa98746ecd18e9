#pragma once
// The one rule for the names of pbrkit's image outputs, which every writer of a rendered
// image follows (`pbrkit render`, `merge`, `denoise`, the viewer's screenshots): an image
// is written twice, as a tone-mapped PNG and as a linear EXR, with one stem. The name given
// is either of the two; the other goes beside it.
#include <string>
#include <string_view>

namespace pbrkit {

/// Where the two files of one image output go.
struct ImageOutputPaths {
  std::string png;  ///< tone-mapped, 8-bit sRGB
  std::string exr;  ///< linear
};

/// The two files of the output named `path`: a path ending in .png or .exr (in any case)
/// is that file, and the other is written beside it with the same stem ("out/x.exr" ->
/// out/x.png and out/x.exr). Any other extension (or none) throws pbrkit::Error naming
/// `what` (where the name came from: a flag, an argument) and the path, so a caller checks
/// the name before it does any work.
ImageOutputPaths image_output_paths(const std::string& path, std::string_view what);

/// The files of frame `frame` of a sequence written to `base`: the frame number, four
/// digits at least, before the extension ("out/x.png" -> "out/x_0007.png"), the numbering
/// Blender and ffmpeg read as an image sequence.
ImageOutputPaths frame_output_paths(const ImageOutputPaths& base, int frame);

/// Creates the directory the outputs go into (nothing for a bare file name).
void create_output_directory(const ImageOutputPaths& outputs);

}  // namespace pbrkit
