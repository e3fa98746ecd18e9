// Animation figures:
//  - posing: the time pose_scene takes per frame on a skinned character (Khronos'
//    BrainStem: 61,666 triangles in 59 skinned meshes), over 100 times of its animation;
//  - a sequence: 48 frames of a skinned character (Khronos' CesiumMan) at 256x256, 64 spp,
//    each posed, its BVH rebuilt and rendered, against 48 renders of its rest pose;
//  - motion blur: the built-in `spheres` with every sphere moving rigidly across the
//    shutter, time per sample against the same scene still.
//
//   build/release/bin/animation_bench [BrainStem.glb CesiumMan.glb]
//
// The Khronos models are not in the repository (their licences and sizes): pass their
// paths, or set PBRKIT_SAMPLE_MODELS to a checkout's 2.0 folder (github.com/KhronosGroup/
// glTF-Sample-Models); without them only the motion-blur figure is printed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pbrkit/image/environment.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/log.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Summary {
  double median = 0, lo = 0, hi = 0;
};
Summary summarise(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v.front(), v.back()};
}

std::string sample_model(int argc, char** argv, int index, const char* name) {
  if (argc > index) return argv[index];
  if (const char* dir = std::getenv("PBRKIT_SAMPLE_MODELS")) {
    const auto path =
        std::filesystem::path(dir) / name / "glTF-Binary" / (std::string(name) + ".glb");
    if (std::filesystem::exists(path)) return path.string();
  }
  return {};
}

pbrkit::PathTracerSettings settings(int size, std::uint32_t spp) {
  pbrkit::PathTracerSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.threads = 2;
  return s;
}

void posing(const std::string& file) {
  pbrkit::Scene scene = pbrkit::load_scene(file);
  if (!scene.motion || scene.motion->animations.empty()) return;
  const pbrkit::Animation& a = scene.motion->animations[0];
  std::vector<double> ms;
  for (int i = 0; i < 100; ++i) {
    const float t = a.start() + (a.end() - a.start()) * float(i) / 99.0f;
    const auto start = Clock::now();
    pbrkit::pose_scene(scene, {0, t});
    ms.push_back(1e3 * seconds_since(start));
  }
  const Summary s = summarise(ms);
  std::printf(
      "posing %s (%zu triangles, %zu deforming meshes): %.2f ms per pose (median of 100; "
      "%.2f-%.2f)\n",
      std::filesystem::path(file).filename().c_str(), scene.triangle_count(),
      scene.motion->deforming.size(), s.median, s.lo, s.hi);
}

void sequence(const std::string& file, const pbrkit::Environment& env) {
  pbrkit::Scene scene = pbrkit::load_scene(file);
  if (!scene.motion || scene.motion->animations.empty()) return;
  const pbrkit::Scene rest = scene;
  const pbrkit::Camera camera = pbrkit::select_camera(rest, std::nullopt, 1.0f);
  const pbrkit::PathTracerSettings s = settings(256, 64);
  const int frames = 48;
  // Alternate the two, three times each, so that the machine's drift touches both.
  std::vector<double> posed_s, rest_s;
  for (int run = 0; run < 3; ++run) {
    auto start = Clock::now();
    for (int f = 0; f < frames; ++f) {
      pbrkit::pose_scene(scene, {0, float(f) / 24.0f});
      pbrkit::render_path(scene, &env, camera, s);
    }
    posed_s.push_back(seconds_since(start));
    start = Clock::now();
    for (int f = 0; f < frames; ++f) pbrkit::render_path(rest, &env, camera, s);
    rest_s.push_back(seconds_since(start));
  }
  const Summary p = summarise(posed_s), r = summarise(rest_s);
  std::printf(
      "sequence %s, 48 frames 256x256 64 spp: posed %.2f s (%.2f-%.2f), rest pose %.2f s "
      "(%.2f-%.2f): %.3fx\n",
      std::filesystem::path(file).filename().c_str(), p.median, p.lo, p.hi, r.median, r.lo, r.hi,
      p.median / r.median);
}

// Every instance of `spheres` slides 0.3 units in x over one second of a synthetic
// animation (one channel per instance's own node).
pbrkit::Scene moving_spheres() {
  pbrkit::Scene scene = pbrkit::builtin_scene("spheres");
  auto motion = std::make_shared<pbrkit::SceneMotion>();
  pbrkit::Animation a;
  a.name = "slide";
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    pbrkit::NodeRest node;
    const glm::mat4& m = scene.instances[i].transform;
    node.has_matrix = false;
    node.translation = glm::vec3(m[3]);
    motion->nodes.push_back(node);
    motion->order.push_back(int(i));
    // The node carries the translation; the rest of the transform rides as the offset.
    glm::mat4 offset = m;
    offset[3] = glm::vec4(0, 0, 0, 1);
    motion->placements.push_back({int(i), int(i), offset});
    pbrkit::AnimationSampler sampler;
    sampler.times = {0.0f, 1.0f};
    const glm::vec3 p = node.translation;
    sampler.values = {p.x - 0.15f, p.y, p.z, p.x + 0.15f, p.y, p.z};
    sampler.width = 3;
    a.samplers.push_back(sampler);
    a.channels.push_back({int(i), int(i), pbrkit::AnimatedProperty::kTranslation});
  }
  motion->animations.push_back(a);
  scene.motion = motion;
  pbrkit::pose_scene(scene, {0, 0.5f});
  return scene;
}

void motion_blur(const pbrkit::Environment& env) {
  const pbrkit::Scene scene = moving_spheres();
  const pbrkit::Camera camera = pbrkit::select_camera(scene, std::nullopt, 1.0f);
  pbrkit::PathTracerSettings still = settings(256, 64);
  pbrkit::PathTracerSettings blur = still;
  blur.shutter = {0, 0.0f, 1.0f, 9};
  std::vector<double> still_us, blur_us;
  for (int run = 0; run < 5; ++run) {
    for (auto* s : {&still, &blur}) {
      const pbrkit::PathTracerResult r = pbrkit::render_path(scene, &env, camera, *s);
      const double per_sample = 1e6 * r.stats.render_seconds / double(r.stats.samples);
      (s == &still ? still_us : blur_us).push_back(per_sample);
    }
  }
  const Summary a = summarise(still_us), b = summarise(blur_us);
  std::printf(
      "motion blur, spheres 256x256 64 spp (49 spheres moving rigidly, 9 steps): still "
      "%.3f us/sample (%.3f-%.3f), blurred %.3f us/sample (%.3f-%.3f): %.3fx\n",
      a.median, a.lo, a.hi, b.median, b.lo, b.hi, b.median / a.median);
}

}  // namespace

int main(int argc, char** argv) {
  pbrkit::set_log_sink([](pbrkit::LogLevel level, const std::string& m) {
    if (level >= pbrkit::LogLevel::kWarning) std::fprintf(stderr, "%s\n", m.c_str());
  });
  const pbrkit::Environment env = pbrkit::load_environment_or_default("", 0.0f, 1.0f);
  const std::string brainstem = sample_model(argc, argv, 1, "BrainStem");
  const std::string cesium = sample_model(argc, argv, 2, "CesiumMan");
  if (!brainstem.empty()) posing(brainstem);
  if (!cesium.empty()) sequence(cesium, env);
  if (brainstem.empty() || cesium.empty())
    std::printf(
        "(posing and sequence figures need Khronos' BrainStem.glb and CesiumMan.glb: "
        "pass their paths or set PBRKIT_SAMPLE_MODELS)\n");
  motion_blur(env);
  return 0;
}
