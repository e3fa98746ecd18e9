#pragma once
// The viewer's screenshots, private to the viewer: the view shown, as a PNG and a linear
// EXR.
#include <string>

#include "pbrkit/image/image.h"
#include "viewer_state.h"

namespace pbrkit::viewer {

/// The view shown, saved as `path` (a .png or .exr: both are written, image/output_paths.h):
/// the raster frame, the path-traced image,
/// the split of the two, or the raster image's error against the truth.
void save_view(const ViewerState& s, const std::string& path, const Image& frame, int fb_w);

}  // namespace pbrkit::viewer
