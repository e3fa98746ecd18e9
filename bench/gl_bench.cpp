// OpenGL renderer benchmarks (issue #6): the frame time of the built-in `spheres` scene
// with IBL and two punctual lights at 1280x720 (wall clock with glFinish, and GPU time from
// timestamp queries), and the time to the first image of a headless render including
// context creation, shader compilation, the IBL bake and the readback; the frame time
// against the number of punctual lights, clustered and not.
// Run with LP_NUM_THREADS=2 on llvmpipe; figures go to BENCHMARKS.md ("## OpenGL").
#include <sys/resource.h>

#include <chrono>
#include <memory>
#include <random>

#include <benchmark/benchmark.h>
#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"

namespace {

using namespace pbrkit;

Scene spheres_with_two_lights() {
  Scene scene = builtin_scene("spheres");
  Light key;
  key.name = "key";
  key.position = glm::vec3(4.0f, 5.0f, 8.0f);
  key.intensity = 60.0f;
  Light fill;
  fill.name = "fill";
  fill.position = glm::vec3(-6.0f, -2.0f, 6.0f);
  fill.color = glm::vec3(0.6f, 0.7f, 1.0f);
  fill.intensity = 30.0f;
  scene.lights = {key, fill};
  return scene;
}

// Process CPU time (all threads, llvmpipe's rasteriser threads included): the frame's cost
// even when other work shares the cores and wall-clock time is inflated.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

BakeOptions viewer_bake() {
  return gl::realtime_bake_options();  // what `pbrkit render --renderer gl` uses by default
}

// Times frames of `scene` at width x height with the default environment and the viewer's
// bake (a current GL context is needed): one warm-up frame (llvmpipe compiles the shaders'
// machine code at the first draw), then the timed frames, with the GPU timer's and the
// process CPU time per frame as counters.
void time_frames(benchmark::State& state, const Scene& scene, int width, int height,
                 const gl::RenderSettings& settings) {
  gl::Renderer renderer;
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  renderer.set_scene(scene);
  renderer.set_environment_light(&env, viewer_bake());
  const Camera camera = select_camera(scene, std::nullopt, float(width) / float(height));
  renderer.render(camera, width, height, settings);
  glFinish();
  double gpu_ms = 0.0;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    renderer.render(camera, width, height, settings);
    glFinish();
    gpu_ms += renderer.gpu_time_ms();
  }
  state.counters["gpu_ms"] = gpu_ms / double(state.iterations());
  state.counters["cpu_ms"] = (process_cpu_seconds() - cpu0) * 1e3 / double(state.iterations());
}

void BM_GlFrameSpheresIblTwoLights(benchmark::State& state) {
  const int width = int(state.range(0)), height = int(state.range(1));
  gl::HeadlessContext context;
  gl::RenderSettings settings;  // SH irradiance, reference model
  settings.msaa = int(state.range(2));
  // A fourth argument 0: no compensation (the default before the energy-compensated
  // layers, to compare like with like across that change).
  if (state.range(3) == 0) settings.brdf.multiscatter = false;
  time_frames(state, spheres_with_two_lights(), width, height, settings);
  state.SetLabel(gl::describe_current_context());
}
// width, height, MSAA samples (4 is the renderer's default).
BENCHMARK(BM_GlFrameSpheresIblTwoLights)
    ->ArgNames({"w", "h", "msaa", "ms"})
    ->Args({1280, 720, 4, 1})
    ->Args({1280, 720, 1, 1})
    ->Args({1280, 720, 1, 0})
    ->Args({320, 180, 4, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

// Where the 1280x720 frame's time goes (MSAA 1): the same frame without one part at a
// time. 0: everything; 1: no IBL; 2: no punctual lights; 3: colour background; 4: the
// background alone (no spheres); 5: the spheres unlit (no IBL, no lights, colour
// background: geometry and rasterisation of the 194k triangles); 6: everything, with
// spheres of 32 x 16 segments instead of 64 x 32 (4x fewer, larger triangles); 7: the
// 32 x 16 spheres unlit (how the unlit cost scales with the triangle count).
void BM_GlFrameBreakdown(benchmark::State& state) {
  const int variant = int(state.range(0));
  constexpr int kWidth = 1280, kHeight = 720;
  gl::HeadlessContext context;
  gl::Renderer renderer;
  Scene scene = spheres_with_two_lights();
  const Camera camera = select_camera(scene, std::nullopt, float(kWidth) / float(kHeight));
  if (variant == 4) scene = Scene{};
  if (variant == 6 || variant == 7)
    for (Mesh& mesh : scene.meshes) {
      const int material = mesh.material;
      mesh = make_uv_sphere(0.4f, 32, 16);
      mesh.material = material;
    }
  const Environment env = load_environment_or_default("", 0.0f, 1.0f);
  renderer.set_scene(scene);
  renderer.set_environment_light(&env, viewer_bake());
  gl::RenderSettings settings;
  settings.msaa = 1;
  const bool unlit = variant == 5 || variant == 7;
  settings.ibl = variant != 1 && !unlit;
  settings.lights = variant != 2 && !unlit;
  if (variant == 3 || unlit) settings.background.mode = gl::Background::Mode::kColor;
  renderer.render(camera, kWidth, kHeight, settings);
  glFinish();
  for (auto _ : state) {
    renderer.render(camera, kWidth, kHeight, settings);
    glFinish();
  }
  static const char* const kNames[] = {
      "everything",      "no IBL",        "no lights",     "colour background",
      "background only", "unlit spheres", "32x16 spheres", "unlit 32x16 spheres"};
  state.SetLabel(kNames[variant]);
}
BENCHMARK(BM_GlFrameBreakdown)
    ->DenseRange(0, 7)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The cost of the layered material (docs/benchmarks_archive.md, "the material extensions"). The
// 1280x720 frame (MSAA 1) of `spheres` as is (0) and with KHR_materials_clearcoat and
// KHR_materials_sheen on every sphere (1: its own shader permutation, the coat's and the sheen's
// lobes per light and their IBL lookups). Goal: 1 at most 1.3x 0.
void BM_GlFrameLayers(benchmark::State& state) {
  constexpr int kWidth = 1280, kHeight = 720;
  gl::HeadlessContext context;
  Scene scene = spheres_with_two_lights();
  if (state.range(0) == 1)
    for (Material& m : scene.materials) {
      ClearcoatExtension coat;
      coat.factor = 1.0f;
      coat.roughness_factor = 0.1f;
      m.clearcoat = coat;
      SheenExtension sheen;
      sheen.color_factor = glm::vec3(0.5f);
      sheen.roughness_factor = 0.5f;
      m.sheen = sheen;
    }
  gl::RenderSettings settings;
  settings.msaa = 1;
  time_frames(state, scene, kWidth, kHeight, settings);
  state.SetLabel(state.range(0) == 1 ? "clearcoat + sheen" : "plain");
}
BENCHMARK(BM_GlFrameLayers)
    ->DenseRange(0, 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

// A built-in scene's 1280x720 frame (MSAA 1) from its own camera.
void time_builtin_frame(benchmark::State& state, const char* name) {
  gl::HeadlessContext context;
  gl::RenderSettings settings;
  settings.msaa = 1;
  time_frames(state, builtin_scene(name), 1280, 720, settings);
}

// The cost of KHR_materials_anisotropy's image-based lighting (three prefiltered lookups
// along the stretched lobe and its tabulated albedo, anisotropy_ibl.glsl): the built-in
// `anisotropy` scene, 16 of its 18 spheres anisotropic. Goal: at most 1.3x the frame with
// one lookup along the bent reflection.
void BM_GlFrameAnisotropy(benchmark::State& state) {
  time_builtin_frame(state, "anisotropy");
}
BENCHMARK(BM_GlFrameAnisotropy)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

// The cost of KHR_materials_sheen's image-based light (the environment's SH averaged over the
// Charlie lobe from its tabulated moments, sheen.glsl): the built-in `sheen` scene. Goal: at
// most 1.3x the frame with the Charlie-prefiltered lookup along the reflection.
void BM_GlFrameSheen(benchmark::State& state) {
  time_builtin_frame(state, "sheen");
}
BENCHMARK(BM_GlFrameSheen)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

// The cost of the transmission pass (docs/benchmarks_archive.md, "glass and liquids"). The 1280x720
// frame (MSAA 1) of `spheres` as is (0: no transmissive material, so no capture and no mip chain),
// with every other sphere thin-walled glass (1: the opaque frame captured, its mip chain built, the
// glass spheres drawn after it reading it), and with those spheres a thick dispersive volume (2:
// three refracted reads per fragment). Goal: 1 and 2 cost at most one extra opaque pass plus the
// mip chain over 0. 3 and 4: the built-in `glass` and `liquid` scenes (their own cameras; `liquid`
// captures the frame twice: its amber behind its glass); 5 and 6: the same without the transmissive
// objects' shadows in the environment light (what they cost); 7 and 8: without thick glass's
// reflections of the frame (what they cost); 9 and 10: with the opaque objects' shadows too
// (RenderSettings::opaque_shadows, off by default); 11 and 12: with neither the transmissive
// objects' shadows nor the reflections, the two-interface refraction alone against the frame before
// it.
void BM_GlFrameTransmission(benchmark::State& state) {
  constexpr int kWidth = 1280, kHeight = 720;
  gl::HeadlessContext context;
  const int variant = int(state.range(0));
  const bool glass = variant == 3 || variant == 5 || variant == 7 || variant == 9 || variant == 11;
  const bool liquid =
      variant == 4 || variant == 6 || variant == 8 || variant == 10 || variant == 12;
  Scene scene = glass    ? builtin_scene("glass")
                : liquid ? builtin_scene("liquid")
                         : spheres_with_two_lights();
  if (variant == 1 || variant == 2) {
    const std::size_t count = scene.materials.size();
    for (std::size_t i = 0; i < count; i += 2) {
      Material& m = scene.materials[i];
      m.transmission = TransmissionExtension{1.0f, {}};
      if (variant == 2) {
        m.volume = VolumeExtension{0.5f, {}, 1.0f, glm::vec3(0.9f, 0.6f, 0.3f)};
        m.dispersion = DispersionExtension{1.0f};
      }
    }
  }
  gl::RenderSettings settings;
  settings.msaa = 1;
  settings.transmissive_shadows = variant != 5 && variant != 6 && variant < 11;
  settings.transmissive_reflections = variant != 7 && variant != 8 && variant < 11;
  settings.opaque_shadows = variant == 9 || variant == 10;
  time_frames(state, scene, kWidth, kHeight, settings);
  static const char* const kNames[] = {"opaque",
                                       "half thin glass",
                                       "half thick dispersive glass",
                                       "builtin glass",
                                       "builtin liquid",
                                       "builtin glass, no glass shadows",
                                       "builtin liquid, no glass shadows",
                                       "builtin glass, no glass reflections",
                                       "builtin liquid, no glass reflections",
                                       "builtin glass, opaque shadows",
                                       "builtin liquid, opaque shadows",
                                       "builtin glass, two-interface refraction alone",
                                       "builtin liquid, two-interface refraction alone"};
  state.SetLabel(kNames[variant]);
}
BENCHMARK(BM_GlFrameTransmission)
    ->DenseRange(0, 12)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

void BM_GlReadBack(benchmark::State& state) {
  gl::HeadlessContext context;
  gl::Renderer renderer;
  renderer.set_scene(Scene{});
  gl::RenderSettings settings;
  settings.background.mode = gl::Background::Mode::kColor;
  const Camera camera = auto_camera(Bounds{}, 16.0f / 9.0f);
  renderer.render(camera, 1280, 720, settings);
  for (auto _ : state) benchmark::DoNotOptimize(renderer.read_back());
}
BENCHMARK(BM_GlReadBack)->Unit(benchmark::kMillisecond)->UseRealTime();

// Everything `pbrkit render --renderer gl` does for its first image, minus the file writes.
void BM_GlTimeToFirstImage(benchmark::State& state) {
  const Scene scene = spheres_with_two_lights();
  for (auto _ : state) {
    const Environment env = load_environment_or_default("", 0.0f, 1.0f);
    const Camera camera = select_camera(scene, std::nullopt, 1280.0f / 720.0f);
    benchmark::DoNotOptimize(
        gl::render_headless(scene, camera, 1280, 720, &env, viewer_bake(), gl::RenderSettings{}));
  }
}
BENCHMARK(BM_GlTimeToFirstImage)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// Many punctual lights (clustered shading, gl/light_clusters.h): a 40 x 40 m floor with a
// 5 x 5 grid of spheres (24 x 12 segments), seen at 35 degrees from above at 640x360, no
// MSAA, with the default environment's IBL, under `n` point lights of range 1.5 m (a
// floor point is reached by 1000 pi 1.5^2 / 1600 = 4.4 of 1,000 on average) or 0.75 m (1.1)
// spread at random over the floor, 0.2 to 1 m above it; clustered (second argument 1) or
// every light in every fragment (0). The binning on the CPU is part of the frame.
Scene floor_with_point_lights(int n, float range) {
  Scene scene;
  scene.source = "bench:many-lights";
  Material floor;
  floor.base_color_factor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
  floor.metallic_factor = 0.0f;
  floor.roughness_factor = 0.7f;
  Material shiny = floor;
  shiny.metallic_factor = 1.0f;
  shiny.roughness_factor = 0.3f;
  scene.materials = {floor, shiny};
  const glm::mat4 id(1.0f);
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-20.0f, 0.0f, 20.0f), glm::vec3(40.0f, 0.0f, 0.0f),
                              glm::vec3(0.0f, 0.0f, -40.0f)),
                    0, id);
  const Mesh sphere = make_uv_sphere(1.0f, 24, 12);
  for (int i = 0; i < 25; ++i)
    add_mesh_instance(scene, sphere, 1,
                      glm::translate(id, glm::vec3(float(i % 5) * 8.0f - 16.0f, 1.0f,
                                                   float(i / 5) * 8.0f - 16.0f)));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < n; ++i) {
    Light l;
    l.position = glm::vec3(40.0f * u(rng) - 20.0f, 0.2f + 0.8f * u(rng), 40.0f * u(rng) - 20.0f);
    l.color = glm::vec3(0.5f + 0.5f * u(rng), 0.5f + 0.5f * u(rng), 0.5f + 0.5f * u(rng));
    l.intensity = 2.0f;
    l.range = range;
    scene.lights.push_back(l);
  }
  Camera camera;
  camera.yfov = 0.9f;
  camera.znear = 0.1f;
  camera.camera_to_world = glm::inverse(glm::lookAt(
      glm::vec3(0.0f, 18.0f, 26.0f), glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  scene.cameras.push_back(camera);
  return scene;
}

void BM_GlFramePunctualLights(benchmark::State& state) {
  gl::HeadlessContext context;
  gl::RenderSettings settings;
  settings.msaa = 1;
  settings.clustered_lights = state.range(1) != 0;
  if (state.range(2) > 0) settings.light_clusters.tile_pixels = int(state.range(2));
  if (state.range(3) > 0) settings.light_clusters.slices = int(state.range(3));
  time_frames(state, floor_with_point_lights(int(state.range(0)), 0.01f * float(state.range(4))),
              640, 360, settings);
  state.SetLabel(settings.clustered_lights ? "clustered" : "every light");
}
// lights, clustered (1) or not (0), the grid's tile size in pixels and slices (0: the
// defaults), the lights' range in cm.
BENCHMARK(BM_GlFramePunctualLights)
    ->ArgNames({"lights", "clustered", "tile", "slices", "range_cm"})
    ->ArgsProduct({{1, 4, 10, 100, 1000}, {1, 0}, {0}, {0}, {150, 75}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);
// The grid's shape at 1,000 lights: smaller clusters hold fewer lights that miss their
// fragments, at more binning work on the CPU.
BENCHMARK(BM_GlFramePunctualLights)
    ->ArgNames({"lights", "clustered", "tile", "slices", "range_cm"})
    ->ArgsProduct({{1000}, {1}, {8, 16, 32}, {16, 32, 64}, {150}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
