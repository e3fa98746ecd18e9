// Image I/O and colour: decoding the shared DWAB HDRI, writing EXR/PNG, and the display
// transform per tone mapper. Files go to the system temp directory.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "pbrkit/core/color.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/util/log.h"

namespace {

namespace fs = std::filesystem;

const fs::path kNight = fs::path(PBRKIT_ASSETS_DIR) / "hdri/night.exr";

pbrkit::Image test_image(int w, int h) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> dist(0.0f, 4.0f);
  pbrkit::Image img(w, h, 3);
  for (float& v : img.data) v = dist(rng);
  return img;
}

void BM_ReadDwabExr512x256(benchmark::State& state) {
  pbrkit::set_log_sink([](pbrkit::LogLevel, const std::string&) {});  // no clamp warnings
  for (auto _ : state) benchmark::DoNotOptimize(pbrkit::read_image(kNight));
  state.SetItemsProcessed(state.iterations() * 512 * 256);
}
BENCHMARK(BM_ReadDwabExr512x256)->Unit(benchmark::kMillisecond);

void BM_WriteExr(benchmark::State& state) {
  const pbrkit::Image img = test_image(1024, 512);
  const fs::path p = fs::temp_directory_path() / "pbrkit_bench.exr";
  const auto type = state.range(0) ? pbrkit::ExrPixelType::kFloat : pbrkit::ExrPixelType::kHalf;
  for (auto _ : state) pbrkit::write_exr(p, img, type);
  fs::remove(p);
  state.SetItemsProcessed(state.iterations() * img.pixel_count());
  state.SetLabel(state.range(0) ? "float, ZIP, 1024x512 RGB" : "half, ZIP, 1024x512 RGB");
}
BENCHMARK(BM_WriteExr)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_WritePng8(benchmark::State& state) {
  pbrkit::Image img = test_image(1024, 512);
  for (float& v : img.data) v *= 0.25f;
  const fs::path p = fs::temp_directory_path() / "pbrkit_bench.png";
  for (auto _ : state) pbrkit::write_png(p, img, 8);
  fs::remove(p);
  state.SetItemsProcessed(state.iterations() * img.pixel_count());
}
BENCHMARK(BM_WritePng8)->Unit(benchmark::kMillisecond);

void BM_DisplayTransform(benchmark::State& state) {
  const auto t = static_cast<pbrkit::ToneMapper>(state.range(0));
  const pbrkit::Image img = test_image(256, 256);
  for (auto _ : state) {
    glm::vec3 acc(0.0f);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) acc += pbrkit::display_transform(img.rgb(x, y), 0.0f, t);
    benchmark::DoNotOptimize(acc);
  }
  state.SetItemsProcessed(state.iterations() * img.pixel_count());
  state.SetLabel(std::string(pbrkit::tone_mapper_name(t)));
}
BENCHMARK(BM_DisplayTransform)->DenseRange(0, 3);

}  // namespace

BENCHMARK_MAIN();
