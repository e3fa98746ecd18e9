// What the path tracer cannot represent is counted and reported, never dropped silently: a
// sample whose radiance is not finite (set to 0 so the pixel stays usable) and a path
// inside more nested volumes than the medium stack holds. Each is counted in the render's
// stats, warned about once per render on the log, carried by the film into its EXRs'
// headers, and summed when films merge. These tests call pbrkit::render_path itself: the
// tests' checked render_path (pt_test_util.h) fails on exactly these counts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pbrkit/image/environment.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "pt/pt_test_util.h"
#include "support/test_paths.h"

namespace pbrkit::test {
namespace {

// Collects the warnings logged while it lives.
struct CapturedWarnings {
  std::vector<std::string> lines;
  LogSink previous;
  CapturedWarnings() {
    previous = set_log_sink([this](LogLevel level, const std::string& m) {
      if (level == LogLevel::kWarning) lines.push_back(m);
    });
  }
  ~CapturedWarnings() { set_log_sink(previous); }
  CapturedWarnings(const CapturedWarnings&) = delete;
  CapturedWarnings& operator=(const CapturedWarnings&) = delete;
  int count(const std::string& text) const {
    int n = 0;
    for (const std::string& l : lines) n += l.find(text) != std::string::npos ? 1 : 0;
    return n;
  }
};

TEST(PathTracerWarnings, NonFiniteSamplesAreCountedWarnedAndWrittenToTheExr) {
  // A sphere whose base colour is NaN in a uniform environment: the camera samples that hit
  // it have a NaN radiance (a few end at 0 instead, where the NaN never meets the light).
  // The sphere (radius 1) fills pi / (2 x 1.1)^2 = 64.9% of the orthographic view (the box
  // filter spreads the samples uniformly): at most that share of the samples is counted
  // (the UV sphere's polygon covers 0.04% less), and most of them are.
  Material m = make_material(glm::vec3(std::numeric_limits<float>::quiet_NaN()), 0.0f, 0.5f);
  const Scene scene = sphere_scene(m);
  const Environment env = Environment::constant(glm::vec3(1.0f));
  CapturedWarnings warnings;
  const PathTracerResult res =
      pbrkit::render_path(scene, &env, ortho_camera(1.1f), small_settings(32, 16));
  const double total = 32.0 * 32.0 * 16.0;
  const double share = double(res.stats.non_finite_samples) / total;
  std::printf("NaN sphere: %llu of %.0f samples not finite (%.4f; disc share %.4f)\n",
              static_cast<unsigned long long>(res.stats.non_finite_samples), total, share,
              kPi / (4.0 * 1.1 * 1.1));
  EXPECT_LT(share, kPi / (4.0 * 1.1 * 1.1) + 0.005);
  EXPECT_GT(share, 0.9 * kPi / (4.0 * 1.1 * 1.1));
  EXPECT_EQ(res.film.non_finite_samples, res.stats.non_finite_samples);
  // The image stays finite: the dropped samples are 0.
  for (float v : res.color.data) ASSERT_TRUE(std::isfinite(v));
  // One warning for the render, with the count.
  EXPECT_EQ(warnings.count("not finite"), 1);
  EXPECT_EQ(warnings.count(std::to_string(res.stats.non_finite_samples) + " of 16384 samples"), 1);
  EXPECT_EQ(warnings.lines.size(), 1u);

  // The count goes into the EXR header (render EXR and accumulation EXR) and merges add.
  const std::filesystem::path dir = scratch_dir();
  write_render_exr(dir / "render.exr", res.film, {}, ExrPixelType::kHalf);
  ExrAttributes attributes;
  read_exr_layers(dir / "render.exr", &attributes);
  EXPECT_EQ(attributes[kNonFiniteSamplesAttribute], std::to_string(res.stats.non_finite_samples));
  EXPECT_EQ(attributes.count(kMediumOverflowsAttribute), 0u);  // none: not written
  write_film(dir / "film.exr", res.film);
  Film merged = read_film(dir / "film.exr");
  EXPECT_EQ(merged.non_finite_samples, res.stats.non_finite_samples);
  merged.merge(read_film(dir / "film.exr"));
  EXPECT_EQ(merged.non_finite_samples, 2 * res.stats.non_finite_samples);

  // A clean render counts nothing, warns nothing and writes no attribute.
  const std::size_t warned = warnings.lines.size();
  const Scene clean = sphere_scene(make_material(glm::vec3(0.5f), 0.0f, 0.5f));
  const PathTracerResult ok =
      pbrkit::render_path(clean, &env, ortho_camera(1.1f), small_settings(16, 4));
  EXPECT_EQ(ok.stats.non_finite_samples, 0u);
  EXPECT_EQ(warnings.lines.size(), warned);
  write_render_exr(dir / "clean.exr", ok.film, {}, ExrPixelType::kHalf);
  ExrAttributes clean_attributes;
  read_exr_layers(dir / "clean.exr", &clean_attributes);
  EXPECT_EQ(clean_attributes.count(kNonFiniteSamplesAttribute), 0u);
}

TEST(PathTracerWarnings, NonFiniteCountsSurviveCheckpointsResumeAndSampleRanges) {
  // The count of a render equals the sum over its parts, and a render resumed from a
  // checkpoint taken between passes ends with the uninterrupted render's count.
  const Scene scene =
      sphere_scene(make_material(glm::vec3(std::numeric_limits<float>::quiet_NaN()), 0.0f, 0.5f));
  const Environment env = Environment::constant(glm::vec3(1.0f));
  const CapturedWarnings quiet;
  PathTracerSettings s = small_settings(16, 32);
  s.min_spp = 4;  // passes at 4, 6, 9, ... samples
  const PathTracerResult full = pbrkit::render_path(scene, &env, ortho_camera(1.1f), s);
  ASSERT_GT(full.stats.non_finite_samples, 0u);

  std::vector<Film> checkpoints;
  PathTracerSettings c = s;
  c.checkpoint_interval = 1e-9;
  c.checkpoint = [&](const Film& film) { checkpoints.push_back(film); };
  pbrkit::render_path(scene, &env, ortho_camera(1.1f), c);
  ASSERT_GE(checkpoints.size(), 2u);
  EXPECT_GT(checkpoints.front().non_finite_samples, 0u);
  EXPECT_LT(checkpoints.front().non_finite_samples, full.stats.non_finite_samples);
  PathTracerSettings r = s;
  r.resume = &checkpoints.front();
  const PathTracerResult resumed = pbrkit::render_path(scene, &env, ortho_camera(1.1f), r);
  EXPECT_EQ(resumed.film.non_finite_samples, full.stats.non_finite_samples);
  EXPECT_EQ(resumed.film.non_finite_samples,
            checkpoints.front().non_finite_samples + resumed.stats.non_finite_samples);

  PathTracerSettings a = s, b = s;
  a.sample_end = 12;
  b.sample_begin = 12;
  Film merged = pbrkit::render_path(scene, &env, ortho_camera(1.1f), a).film;
  merged.merge(pbrkit::render_path(scene, &env, ortho_camera(1.1f), b).film);
  EXPECT_EQ(merged.non_finite_samples, full.stats.non_finite_samples);
}

TEST(PathTracerWarnings, MalformedCountAttributeIsAnErrorNamingTheFile) {
  const std::filesystem::path path = scratch_dir() / "bad.exr";
  Film film(2, 2);
  film.non_finite_samples = 3;
  write_film(path, film);
  // Rewrite the attribute with text that is not a count.
  ExrAttributes attributes;
  auto layers = read_exr_layers(path, &attributes);
  std::vector<ExrLayer> out;
  for (auto& [name, image] : layers) {
    ExrLayer l;
    l.name = name;
    l.image = &image;
    l.type = ExrPixelType::kFloat;
    for (int c = 0; c < image.channels; ++c)
      l.channel_names.push_back(image.channels == 1 ? "Y" : std::string(1, "RGB"[c]));
    out.push_back(l);
  }
  write_exr_layers(path, out, {{kNonFiniteSamplesAttribute, "-1"}});
  try {
    read_film(path);
    FAIL() << "a malformed count was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(kNonFiniteSamplesAttribute), std::string::npos)
        << e.what();
  }
}

// `n` nested closed boxes of clear glass of ior 1 (no interface: the paths go straight
// through, entering one volume at each box), the outermost 2 wide, seen from above.
Scene nested_volumes(int n) {
  Scene scene;
  scene.source = "test:nested volumes";
  Material m = make_material(glm::vec3(1.0f), 0.0f, 0.0f);
  m.ior = 1.0f;
  m.transmission = TransmissionExtension{};
  m.transmission->factor = 1.0f;
  m.volume = VolumeExtension{};
  m.volume->thickness_factor = 1.0f;
  scene.materials.push_back(m);
  for (int k = 0; k < n; ++k) {
    const float h = 1.0f - 0.05f * float(k);
    add_mesh_instance(scene, make_box(glm::vec3(-h), glm::vec3(h)), 0);
  }
  return scene;
}

TEST(PathTracerWarnings, MediumStackOverflowIsCountedAndWarnedNamingTheLimit) {
  const Environment env = Environment::constant(glm::vec3(1.0f));
  PathTracerSettings s = small_settings(8, 2);
  s.max_bounces = 64;  // two interfaces per box
  for (int n : {kMaxNestedVolumes, kMaxNestedVolumes + 1}) {
    CapturedWarnings warnings;
    // The camera sees only the innermost box's top (half 0.5 < its half size 0.6).
    const PathTracerResult res =
        pbrkit::render_path(nested_volumes(n), &env, ortho_camera(0.5f), s);
    const bool over = n > kMaxNestedVolumes;
    // Every camera path enters all n volumes on its way down.
    EXPECT_EQ(res.stats.medium_overflows, over ? 8u * 8u * 2u : 0u) << n << " volumes";
    EXPECT_EQ(res.film.medium_overflows, res.stats.medium_overflows);
    EXPECT_EQ(warnings.count("more than 8 nested volumes"), over ? 1 : 0) << n << " volumes";
    // ior 1 everywhere: the image is the environment whatever the stack did.
    for (float v : res.color.data) EXPECT_NEAR(v, 1.0f, 1e-4f);
  }
}

}  // namespace
}  // namespace pbrkit::test
