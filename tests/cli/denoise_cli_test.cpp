// `pbrkit render --denoise`, `pbrkit merge --denoise` and `pbrkit denoise` end to end.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "pbrkit/denoise/learned_denoiser.h"
#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

int pbrkit_cli(const std::string& args, std::string* log) {
  return test::run_command(test::cli_path().string() + " " + args, log);
}

const Image* layer(const std::vector<std::pair<std::string, Image>>& layers,
                   const std::string& name) {
  for (const auto& [n, image] : layers)
    if (n == name) return &image;
  return nullptr;
}

const std::string kRender = "render cornell --renderer path --spp 8 --width 40 --height 40 ";

TEST(DenoiseCli, RenderDenoiseWritesTheDenoisedImageAndKeepsTheRawOne) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  ASSERT_EQ(pbrkit_cli(kRender + "--denoise -o " + (dir / "d.exr").string(), &log), 0) << log;
  EXPECT_TRUE(fs::exists(dir / "d.png"));
  const auto layers = read_exr_layers(dir / "d.exr");
  for (const char* name : {"", "raw", "albedo", "normal", "depth"})
    ASSERT_NE(layer(layers, name), nullptr) << "layer '" << name << "' missing";
  const Image& main = *layer(layers, "");
  const Image& raw = *layer(layers, "raw");
  ASSERT_EQ(main.data.size(), raw.data.size());
  EXPECT_NE(main.data, raw.data);
  // Denoising smooths: the sum of squared differences between horizontal neighbours drops.
  // Values are clamped to 1 first: the light (at 15) is an edge either way, and a filter
  // that blurred it into the ceiling would pass for a smoother image (its rows alone outweigh
  // the lit surfaces' noise at this size).
  auto roughness = [](const Image& im) {
    double s = 0.0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 1; x < im.width; ++x) {
        const double d = std::min(im.pixel(x, y)[1], 1.0f) - std::min(im.pixel(x - 1, y)[1], 1.0f);
        s += d * d;
      }
    return s;
  };
  EXPECT_LT(roughness(main), 0.5 * roughness(raw));
}

TEST(DenoiseCli, DenoiseCommandEqualsRenderDenoise) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  ASSERT_EQ(pbrkit_cli(kRender + "--denoise -o " + (dir / "direct.exr").string(), &log), 0) << log;
  ASSERT_EQ(pbrkit_cli(kRender + "--aov denoise -o " + (dir / "layers.exr").string(), &log), 0)
      << log;
  ASSERT_EQ(
      pbrkit_cli("denoise " + (dir / "layers.exr").string() + " -o " + (dir / "later.png").string(),
                 &log),
      0)
      << log;
  EXPECT_TRUE(fs::exists(dir / "later.png"));
  const auto direct = read_exr_layers(dir / "direct.exr");
  const auto later = read_exr_layers(dir / "later.exr");
  ASSERT_NE(layer(later, "raw"), nullptr);
  // The same film through the EXR's float half-buffer layers: the same denoised image.
  EXPECT_EQ(layer(direct, "")->data, layer(later, "")->data);
}

TEST(DenoiseCli, MissingLayersAreAClearErrorAndWriteNothing) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  ASSERT_EQ(pbrkit_cli(kRender + "--aov albedo -o " + (dir / "plain.exr").string(), &log), 0);
  const int code = pbrkit_cli(
      "denoise " + (dir / "plain.exr").string() + " -o " + (dir / "out.png").string(), &log);
  EXPECT_EQ(code, 1) << log;
  EXPECT_NE(log.find("missing the layers the denoiser needs: color_a, color_b, albedo_a"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("--aov denoise"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(DenoiseCli, MergedPartsDenoiseLikeOneRender) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  ASSERT_EQ(pbrkit_cli(kRender + "--denoise -o " + (dir / "whole.exr").string(), &log), 0);
  for (const char* range : {"0:3", "3:8"})
    ASSERT_EQ(pbrkit_cli(kRender + "--sample-range " + range + " -o " +
                             (dir / (std::string("part") + range[0] + ".exr")).string(),
                         &log),
              0)
        << log;
  ASSERT_EQ(
      pbrkit_cli("merge " + (dir / "part0.exr").string() + " " + (dir / "part3.exr").string() +
                     " --denoise -o " + (dir / "merged.exr").string(),
                 &log),
      0)
      << log;
  const auto whole = read_exr_layers(dir / "whole.exr");
  const auto merged = read_exr_layers(dir / "merged.exr");
  ASSERT_NE(layer(merged, "raw"), nullptr);
  const Image& a = *layer(whole, "");
  const Image& b = *layer(merged, "");
  ASSERT_EQ(a.data.size(), b.data.size());
  // Sums of parts equal the whole to float rounding; the denoised images agree as closely
  // (half-float output: 2^-10 relative).
  double worst = 0.0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    worst = std::max(worst, double(std::abs(a.data[i] - b.data[i])) / (1e-3 + a.data[i]));
  EXPECT_LT(worst, 4e-3);
}

TEST(DenoiseCli, SampleRangeWithDenoiseIsRefused) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  EXPECT_EQ(
      pbrkit_cli(kRender + "--sample-range 0:4 --denoise -o " + (dir / "p.exr").string(), &log), 1);
  EXPECT_NE(log.find("pbrkit merge --denoise"), std::string::npos) << log;
}

// --adaptive denoised: the image is denoised (raw layer kept), the sample counts vary from
// pixel to pixel with --spp as their mean at most, and a sample range is refused.
TEST(DenoiseCli, AdaptiveDenoisedVariesTheCountsWithinTheBudget) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  ASSERT_EQ(pbrkit_cli(kRender + "--adaptive denoised --aov samples -o " + (dir / "a.exr").string(),
                       &log),
            0)
      << log;
  const auto layers = read_exr_layers(dir / "a.exr");
  for (const char* name : {"", "raw", "samples"})
    ASSERT_NE(layer(layers, name), nullptr) << "layer '" << name << "' missing";
  EXPECT_NE(layer(layers, "")->data, layer(layers, "raw")->data);
  const Image& samples = *layer(layers, "samples");
  double total = 0.0;
  float lowest = 1e30f, highest = 0.0f;
  for (std::size_t i = 0; i < samples.pixel_count(); ++i) {
    const float v = samples.data[i * std::size_t(samples.channels)];
    total += v;
    lowest = std::min(lowest, v);
    highest = std::max(highest, v);
  }
  EXPECT_LE(total, 8.0 * double(samples.pixel_count()));
  EXPECT_LT(lowest, 8.0f);
  EXPECT_GT(highest, 8.0f);
  EXPECT_EQ(
      pbrkit_cli(kRender + "--adaptive denoised --sample-range 0:4 -o " + (dir / "p.exr").string(),
                 &log),
      1);
  EXPECT_NE(log.find("--sample-range"), std::string::npos) << log;
}

// --adaptive denoised --checkpoint: the checkpoint resumes to the same image as the
// uninterrupted render, and only with --adaptive denoised.
TEST(DenoiseCli, AdaptiveDenoisedCheckpointResumesToTheSameImage) {
  const fs::path dir = test::scratch_dir();
  const std::string driven = kRender + "--adaptive denoised --float ";
  std::string log;
  ASSERT_EQ(pbrkit_cli(driven + "--checkpoint " + (dir / "c.exr").string() +
                           " --checkpoint-interval 1e-9 -o " + (dir / "whole.exr").string(),
                       &log),
            0)
      << log;
  ASSERT_EQ(pbrkit_cli(driven + "--resume " + (dir / "c.exr").string() + " -o " +
                           (dir / "resumed.exr").string(),
                       &log),
            0)
      << log;
  const auto whole = read_exr_layers(dir / "whole.exr");
  const auto resumed = read_exr_layers(dir / "resumed.exr");
  ASSERT_NE(layer(whole, ""), nullptr);
  ASSERT_NE(layer(resumed, ""), nullptr);
  EXPECT_EQ(layer(whole, "")->data, layer(resumed, "")->data);
  EXPECT_EQ(pbrkit_cli(kRender + "--resume " + (dir / "c.exr").string() + " -o " +
                           (dir / "n.exr").string(),
                       &log),
            1);
  EXPECT_NE(log.find("--adaptive denoised"), std::string::npos) << log;
}

// --denoiser learned: the network (docs/LEARNED_DENOISER.md) from the shipped or a given
// weights file; a bad file is refused, naming it, before the render starts, and the
// classic denoiser needs no file.
// Runs the command with `-o exr` and returns the EXR's layers.
std::vector<std::pair<std::string, Image>> run_to_exr(const std::string& args,
                                                      const fs::path& exr) {
  std::string log;
  EXPECT_EQ(pbrkit_cli(args + " -o " + exr.string(), &log), 0) << log;
  return read_exr_layers(exr);
}

TEST(DenoiseCli, LearnedDenoiserAndItsWeightsFile) {
  const fs::path dir = test::scratch_dir();
  std::string log;
  const auto learned =
      run_to_exr(kRender + "--denoise --denoiser learned --float", dir / "learned.exr");
  const auto classic =
      run_to_exr(kRender + "--denoise --denoiser classic --float", dir / "classic.exr");
  ASSERT_NE(layer(learned, ""), nullptr);
  ASSERT_NE(layer(classic, ""), nullptr);
  // The same samples (the raw layers equal), two denoisers (the images differ).
  EXPECT_EQ(layer(learned, "raw")->data, layer(classic, "raw")->data);
  EXPECT_NE(layer(learned, "")->data, layer(classic, "")->data);
  // `pbrkit denoise --denoiser learned` on the half buffers gives what render gave.
  run_to_exr(kRender + "--aov denoise --float", dir / "halves.exr");
  const auto again =
      run_to_exr("denoise " + (dir / "halves.exr").string() + " --denoiser learned --float",
                 dir / "again.exr");
  ASSERT_NE(layer(again, ""), nullptr);
  EXPECT_EQ(layer(again, "")->data, layer(learned, "")->data);

  // A missing file and a truncated one: exit 1, the file named, nothing written.
  const fs::path truncated = dir / "truncated.pbnn";
  {
    const fs::path shipped = default_learned_denoiser_weights();
    fs::copy_file(shipped, truncated);
    fs::resize_file(truncated, fs::file_size(shipped) / 2);
  }
  for (const fs::path& bad : {dir / "missing.pbnn", truncated}) {
    const fs::path out = dir / ("bad_" + bad.stem().string() + ".png");
    EXPECT_EQ(pbrkit_cli(kRender + "--denoise --denoiser learned --denoiser-weights " +
                             bad.string() + " -o " + out.string(),
                         &log),
              1)
        << log;
    EXPECT_NE(log.find(bad.string()), std::string::npos) << log;
    EXPECT_EQ(log.find("path tracing"), std::string::npos) << "checked after the render: " << log;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(pbrkit_cli("denoise " + (dir / "halves.exr").string() +
                             " --denoiser learned --denoiser-weights " + bad.string() + " -o " +
                             out.string(),
                         &log),
              1)
        << log;
    EXPECT_NE(log.find(bad.string()), std::string::npos) << log;
  }
  // The classic denoiser reads no weights file.
  EXPECT_EQ(pbrkit_cli(kRender + "--denoise --denoiser classic --denoiser-weights " +
                           (dir / "missing.pbnn").string() + " -o " + (dir / "c2.png").string(),
                       &log),
            0)
      << log;
}

}  // namespace
}  // namespace pbrkit
