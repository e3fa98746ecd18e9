// The denoiser's features: albedo, normal and depth come from the first vertex that is
// not near-specular, so a mirror shows the features of what it reflects.
#include <gtest/gtest.h>

#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/primitives.h"
#include "pt_test_util.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

// A 2x2 quad at z = 0 facing the orthographic camera at z = 5, and behind the camera a
// double-sided red diffuse quad at z = 6 that only reflected rays can reach.
Film render_aovs(float mirror_roughness) {
  Scene scene;
  scene.source = "test:mirror";
  scene.materials.push_back(test::make_material(glm::vec3(0.9f), 1.0f, mirror_roughness));
  scene.materials.push_back(
      test::make_material(glm::vec3(0.8f, 0.2f, 0.1f), 0.0f, 1.0f, glm::vec3(0.0f), true));
  add_mesh_instance(
      scene, make_quad(glm::vec3(-1.0f, -1.0f, 0.0f), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0)), 0);
  add_mesh_instance(
      scene, make_quad(glm::vec3(-3.0f, -3.0f, 6.0f), glm::vec3(6, 0, 0), glm::vec3(0, 6, 0)), 1);
  PathTracerSettings s = test::small_settings(16, 4);
  return test::render_path(scene, nullptr, test::ortho_camera(0.5f), s).film;
}

TEST(PathTracerAovs, MirrorShowsTheFeaturesOfWhatItReflects) {
  const Film film = render_aovs(0.0f);
  const glm::vec3 albedo = film.albedo_image().rgb(8, 8);
  const glm::vec3 normal = film.normal_image().rgb(8, 8);
  const float depth = film.depth_image().rgb(8, 8).x;
  // The red quad's albedo tinted by the mirror's reflectance (0.9 at normal incidence for
  // a metal of base colour 0.9): (0.72, 0.18, 0.09); the ratios are the red quad's.
  EXPECT_NEAR(albedo.x, 0.72f, 0.05f);
  EXPECT_NEAR(albedo.x / albedo.y, 4.0f, 0.01f);
  EXPECT_NEAR(albedo.x / albedo.z, 8.0f, 0.02f);
  // The red quad's normal, turned towards the ray that reached it (-Z), and the length of
  // the path to it: 5 to the mirror, 6 back.
  EXPECT_NEAR(normal.z, -1.0f, 1e-3f);
  EXPECT_NEAR(depth, 11.0f, 1e-3f);
}

TEST(PathTracerAovs, RoughMetalKeepsItsOwnFeatures) {
  const Film film = render_aovs(0.5f);
  const glm::vec3 albedo = film.albedo_image().rgb(8, 8);
  EXPECT_NEAR(albedo.x, 0.9f, 1e-4f);
  EXPECT_NEAR(albedo.y, 0.9f, 1e-4f);
  EXPECT_NEAR(film.normal_image().rgb(8, 8).z, 1.0f, 1e-3f);
  EXPECT_NEAR(film.depth_image().rgb(8, 8).x, 5.0f, 1e-3f);
}

TEST(PathTracerAovs, FeatureHalfBuffersAverageToTheFullMeans) {
  const Film film = render_aovs(0.3f);
  const Image full = film.albedo_image(), a = film.albedo_half(0), b = film.albedo_half(1);
  for (std::size_t i = 0; i < full.data.size(); ++i)
    EXPECT_NEAR(0.5f * (a.data[i] + b.data[i]), full.data[i], 1e-5f);  // 4 spp: 2 + 2
}

// An accumulation file from before the features' half buffers: it loads, with each half
// given its share of the totals (the denoiser then sees noise-free features).
TEST(PathTracerAovs, OlderAccumulationFilesLoadWithoutFeatureHalves) {
  const Film film = render_aovs(0.3f);
  const auto path = test::scratch_dir() / "old.exr";
  write_film(path, film);
  std::vector<std::pair<std::string, Image>> layers = read_exr_layers(path);
  std::vector<ExrLayer> kept;
  for (const auto& [name, image] : layers)
    if (name.find("even_sum") == std::string::npos || name == "pbrkit_sum_even")
      kept.push_back({name,
                      image.channels == 3 ? std::vector<std::string>{"R", "G", "B"}
                                          : std::vector<std::string>{"Y"},
                      &image, ExrPixelType::kFloat});
  ASSERT_EQ(kept.size(), layers.size() - 3);
  write_exr_layers(path, kept);
  const Film old = read_film(path);
  EXPECT_EQ(old.sum, film.sum);
  const Image a = old.albedo_half(0), b = old.albedo_half(1), full = film.albedo_image();
  for (std::size_t i = 0; i < full.data.size(); ++i) {
    EXPECT_NEAR(a.data[i], full.data[i], 1e-5f);
    EXPECT_NEAR(b.data[i], full.data[i], 1e-5f);
  }
}

}  // namespace
}  // namespace pbrkit
