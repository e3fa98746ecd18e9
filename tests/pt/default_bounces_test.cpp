// What the default bounce count (PathTracerSettings::max_bounces, the CLI's --max-bounces
// default) costs against a converged render: light that needs more interactions than the
// limit allows (through a glass object's two interfaces and its internal reflections, a
// liquid inside a tumbler) is dropped, so a truncated render is darker. Both renders use
// the same seed, so their paths agree up to the shallower limit and the per-pixel
// difference holds only what the deeper one adds: its standard error over the pixels is
// the noise of the measured deficit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pbrkit/core/color.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

namespace pbrkit::test {
namespace {

// 64 bounces stand for converged: no built-in scene gains more than its noise from 64 to
// 128 (README, "Bounces").
constexpr int kConverged = 64;

// Per-pixel luminance of a built-in scene at `width` (the height from the camera's aspect),
// in the built-in environment, `spp` samples without adaptive sampling, seed 0.
struct Luminance {
  int width = 0, height = 0;
  std::vector<double> y;
};
Luminance render_luminance(const Scene& scene, int width, std::uint32_t spp, int bounces) {
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  const RenderView view = select_view(scene, std::nullopt, width, std::nullopt);
  PathTracerSettings s;
  s.width = view.size.width;
  s.height = view.size.height;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.max_bounces = bounces;
  const Image image = render_path(scene, &env, view.camera, s).color;
  Luminance out{image.width, image.height, {}};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) out.y.push_back(luminance(image.rgb(x, y)));
  return out;
}

struct Deficit {
  double deficit = 0.0;      ///< 1 - mean(shallow) / mean(deep) over the image
  double std_error = 0.0;    ///< of the deficit, from the per-pixel differences
  double worst_block = 0.0;  ///< the largest deficit of any 16x16 block (mean > 0.01)
};

Deficit deficit(const Luminance& shallow, const Luminance& deep) {
  double sum_deep = 0.0, sum_d = 0.0, sum_d2 = 0.0;
  const double n = double(deep.y.size());
  for (std::size_t i = 0; i < deep.y.size(); ++i) {
    const double d = deep.y[i] - shallow.y[i];
    sum_deep += deep.y[i];
    sum_d += d;
    sum_d2 += d * d;
  }
  Deficit out;
  out.deficit = sum_d / sum_deep;
  const double mean_d = sum_d / n;
  const double var_d = std::max(0.0, (sum_d2 / n - mean_d * mean_d) * n / (n - 1.0));
  out.std_error = std::sqrt(var_d / n) / (sum_deep / n);
  constexpr int kBlock = 16;
  for (int by = 0; by + kBlock <= deep.height; by += kBlock)
    for (int bx = 0; bx + kBlock <= deep.width; bx += kBlock) {
      double a = 0.0, b = 0.0;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(deep.width) + std::size_t(x);
          a += shallow.y[i];
          b += deep.y[i];
        }
      if (b / (kBlock * kBlock) > 0.01) out.worst_block = std::max(out.worst_block, 1.0 - a / b);
    }
  return out;
}

// The built-in transmissive scenes at the default bounce count are within 1% of converged:
// `glass` (two interfaces per object, total internal reflection in the prism and the thick
// sphere) and `liquid` (a liquid inside a tumbler: four interfaces before the backdrop; at
// 8 bounces it is 6% dark).
void expect_default_within_one_percent(const std::string& name) {
  const int bounces = PathTracerSettings{}.max_bounces;
  const Scene scene = builtin_scene(name);
  const Deficit d = deficit(render_luminance(scene, 64, 16, bounces),
                            render_luminance(scene, 64, 16, kConverged));
  std::printf("%s: %d bounces %.4f +- %.4f below %d (worst 16x16 block %.4f)\n", name.c_str(),
              bounces, d.deficit, d.std_error, kConverged, d.worst_block);
  EXPECT_LT(d.deficit, 0.01) << name << ": +- " << d.std_error;
}

TEST(DefaultBounces, GlassSceneWithinOnePercentOfConverged) {
  expect_default_within_one_percent("glass");
}

TEST(DefaultBounces, LiquidSceneWithinOnePercentOfConverged) {
  expect_default_within_one_percent("liquid");
}

// The table of the README's "Bounces": every built-in scene at 8, 12, 16 and 24 bounces
// against 64, and 64 against 128 (convergence of the reference). Several CPU minutes, so
// run on demand: pt_tests --gtest_also_run_disabled_tests --gtest_filter='*BounceTable*'.
TEST(DefaultBounces, DISABLED_BounceTable) {
  std::printf(
      "deficit of the image's mean luminance against %d bounces, +- its standard error; in "
      "brackets the worst 16x16 block's\n",
      kConverged);
  for (const std::string& name : builtin_scene_names()) {
    const Scene scene = builtin_scene(name);
    const Luminance deep = render_luminance(scene, 128, 64, kConverged);
    std::string row;
    for (int shallow : {8, 12, 16, 24}) {
      const Deficit d = deficit(render_luminance(scene, 128, 64, shallow), deep);
      char cell[64];
      std::snprintf(cell, sizeof cell, " | %.2f%% +- %.2f%% (%.1f%%)", 100.0 * d.deficit,
                    100.0 * d.std_error, 100.0 * d.worst_block);
      row += cell;
    }
    const Deficit c = deficit(deep, render_luminance(scene, 128, 64, 2 * kConverged));
    std::printf("| %s%s | %.2f%% +- %.2f%% (%.1f%%) |\n", name.c_str(), row.c_str(),
                100.0 * c.deficit, 100.0 * c.std_error, 100.0 * c.worst_block);
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace pbrkit::test
