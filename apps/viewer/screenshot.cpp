#include "screenshot.h"

#include "pbrkit/image/compare.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/log.h"
#include "truth_view.h"

namespace pbrkit::viewer {

namespace {

// Writes `linear` as a float EXR and, through the display transform, a PNG (or, for the
// error view, `display` as is): `path` names either, the other goes beside it, as for
// every image output.
void save_screenshot(const std::string& path, const Image& linear, const DisplaySettings& settings,
                     const Image* display = nullptr) {
  const ImageOutputPaths out = image_output_paths(path, "screenshot");
  create_output_directory(out);
  write_exr(out.exr, linear.channels == 1 ? linear : rgb_channels(linear), ExrPixelType::kFloat);
  if (display)
    write_png(out.png, *display);
  else
    write_display_png(out.png, linear, settings);
  note("wrote {} and {}", out.png, out.exr);
}

}  // namespace

void save_view(const ViewerState& s, const std::string& path, const Image& frame, int fb_w) {
  if (s.mode == ViewMode::kRaster && !frame.empty()) {
    save_screenshot(path, frame, raster_display(s));
  } else if (s.mode == ViewMode::kPath && s.snapshot) {
    const Image linear = path_linear(s);
    const Image shown = path_display(s);
    save_screenshot(path, linear, s.display, &shown);
  } else if (s.mode == ViewMode::kSplit && s.snapshot && !frame.empty()) {
    save_screenshot(
        path, split_image(rgb_channels(frame), s.snapshot->color, split_column(s.split, fb_w)),
        s.display);
  } else if (s.mode == ViewMode::kDifference && s.snapshot && !frame.empty()) {
    const ErrorView e = luminance_error(frame, s.snapshot->color);
    const Image heat = error_heatmap(e.error, 0.5f);
    save_screenshot(path, e.error, s.display, &heat);
    note("view: relative luminance error mean {:.4f}, 95th percentile {:.4f}", e.mean, e.p95);
  }
}

}  // namespace pbrkit::viewer
