// pbrkit compare: image metrics between a test image and a reference (library:
// pbrkit/image/compare.h), optionally inside a mask, with an error heatmap PNG.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/image/image_io.h"

namespace pbrkit::cli {
namespace {

struct CompareOptions {
  std::string a, b, mask, heatmap;
  float heatmap_scale = 0.5f;
};

void run_compare(const CompareOptions& o) {
  const Image a = read_image(o.a);
  const Image b = read_image(o.b);
  Image mask;
  if (!o.mask.empty()) {
    ImageReadOptions raw;
    raw.decode_srgb = false;  // a mask is data, not colour
    mask = read_image(o.mask, raw);
  }
  const Image* m = o.mask.empty() ? nullptr : &mask;
  const CompareMetrics r = compare_images(a, b, m, o.a, o.b, o.mask);
  std::printf("A (test):      %s\n", o.a.c_str());
  std::printf("B (reference): %s\n", o.b.c_str());
  std::printf("pixels:        %zu of %zu%s\n", r.pixels, a.pixel_count(),
              m ? " (inside the mask)" : "");
  std::printf("RMSE:          %.6g\n", r.rmse);
  std::printf("relMSE:        %.6g   (mean (a-b)^2 / (b^2 + 0.01))\n", r.relative_mse);
  if (std::isinf(r.psnr))
    std::printf("PSNR:          inf dB   (identical; peak 1 on linear values)\n");
  else
    std::printf("PSNR:          %.3f dB   (peak 1 on linear values)\n", r.psnr);
  std::printf("mean rel. err: %.6g   (mean |a-b| / (|b| + 0.01))\n", r.mean_relative_error);
  if (!o.heatmap.empty()) {
    const Image heat = error_heatmap(relative_error_image(a, b, m), o.heatmap_scale, m);
    write_png(o.heatmap, heat);
    std::printf("heatmap:       %s   (relative error, viridis: 0 = purple, >= %g = yellow%s)\n",
                o.heatmap.c_str(), o.heatmap_scale, m ? ", grey = outside the mask" : "");
  }
}

}  // namespace

void register_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand(
      "compare",
      "Compare image A (test) with B (reference): RMSE, relative MSE, PSNR (peak 1 on linear "
      "values) and mean relative error, averaged over the RGB channels and the pixels where "
      "the mask is non-zero. Sizes must match.");
  cmd->add_option("A", o->a, "test image (.exr/.hdr/.png/.jpg)")->required();
  cmd->add_option("B", o->b, "reference image (.exr/.hdr/.png/.jpg)")->required();
  cmd->add_option("--mask", o->mask, "mask image: only pixels where it is non-zero count");
  cmd->add_option("--heatmap", o->heatmap,
                  "write a PNG of the per-pixel relative error |a-b|/(|b|+0.01) through the "
                  "viridis colour ramp");
  cmd->add_option("--heatmap-scale", o->heatmap_scale,
                  "relative error shown as the top (yellow) of the ramp")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace pbrkit::cli
