// The OpenGL renderer's cost of a new pose of a skinned character (Khronos' BrainStem:
// 61,666 triangles in 59 skinned meshes), two ways, over 48 times of its animation:
//  - GPU: Renderer::set_pose, which uploads the joint matrices, morph weights and instance
//    transforms, the meshes deformed in the vertex shader (gl/gpu_deformation.h);
//  - re-upload: pose_scene on the CPU, then Renderer::set_scene of the posed scene (what the
//    viewer did per frame before set_pose).
// Each update ends with glFinish (the upload done, not queued); then the frame at 640x360
// that draws the pose, timed the same way, since the GPU path moves the deformation into
// every frame's vertex shader. Median and range over the 48 poses.
//
//   LP_NUM_THREADS=2 build/release/bin/gl_pose_bench [BrainStem.glb]
//
// BrainStem is not in the repository: pass its path, or set PBRKIT_SAMPLE_MODELS to a
// glTF-Sample-Models checkout's 2.0 folder.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/log.h"

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

struct Summary {
  double median = 0, lo = 0, hi = 0;
};
Summary summarise(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v.front(), v.back()};
}

void print(const char* what, const std::vector<double>& ms) {
  const Summary s = summarise(ms);
  std::printf("  %-44s median %8.2f ms  (range %.2f to %.2f, %zu poses)\n", what, s.median, s.lo,
              s.hi, ms.size());
}

std::string brainstem(int argc, char** argv) {
  if (argc > 1) return argv[1];
  if (const char* dir = std::getenv("PBRKIT_SAMPLE_MODELS")) {
    const auto path = std::filesystem::path(dir) / "BrainStem" / "glTF-Binary" / "BrainStem.glb";
    if (std::filesystem::exists(path)) return path.string();
  }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pbrkit;
  const std::string path = brainstem(argc, argv);
  if (path.empty()) {
    std::printf("gl_pose_bench: no BrainStem.glb (pass its path or set PBRKIT_SAMPLE_MODELS)\n");
    return 0;
  }
  set_log_sink([](LogLevel, const std::string&) {});
  const Scene rest = load_scene(path);
  if (!rest.motion || rest.motion->animations.empty()) {
    std::fprintf(stderr, "%s has no animation\n", path.c_str());
    return 1;
  }
  const Animation& a = rest.motion->animations[0];
  constexpr int kPoses = 48, kWidth = 640, kHeight = 360;
  std::vector<PoseTime> poses;
  for (int i = 0; i < kPoses; ++i)
    poses.push_back({0, a.start() + (a.end() - a.start()) * float(i) / float(kPoses)});
  const Camera camera = auto_camera(rest.world_bounds(), float(kWidth) / float(kHeight));
  gl::RenderSettings settings;
  settings.ibl = false;

  gl::HeadlessContext context;
  std::printf("gl_pose_bench: %s (%zu triangles, %zu deforming meshes), %s, %dx%d frames\n",
              path.c_str(), rest.triangle_count(), rest.motion->deforming.size(),
              gl::current_renderer().c_str(), kWidth, kHeight);
  std::vector<double> gpu_update, gpu_frame, cpu_pose, cpu_upload, cpu_frame;
  {
    gl::Renderer r;
    r.set_scene(rest);
    r.set_pose(poses[0]);
    r.render(camera, kWidth, kHeight, settings);  // llvmpipe compiles the shaders' code here
    glFinish();
    for (const PoseTime& p : poses) {
      auto t = Clock::now();
      r.set_pose(p);
      glFinish();
      gpu_update.push_back(ms_since(t));
      t = Clock::now();
      r.render(camera, kWidth, kHeight, settings);
      glFinish();
      gpu_frame.push_back(ms_since(t));
    }
  }
  {
    gl::Renderer r;
    r.set_scene(rest);
    r.render(camera, kWidth, kHeight, settings);
    glFinish();
    Scene posed = rest;
    for (const PoseTime& p : poses) {
      auto t = Clock::now();
      pose_scene(posed, p);
      cpu_pose.push_back(ms_since(t));
      t = Clock::now();
      r.set_scene(posed);
      glFinish();
      cpu_upload.push_back(ms_since(t));
      t = Clock::now();
      r.render(camera, kWidth, kHeight, settings);
      glFinish();
      cpu_frame.push_back(ms_since(t));
    }
  }
  std::vector<double> cpu_update(cpu_pose.size());
  for (std::size_t i = 0; i < cpu_pose.size(); ++i) cpu_update[i] = cpu_pose[i] + cpu_upload[i];
  std::printf("a new pose:\n");
  print("GPU: set_pose", gpu_update);
  print("re-upload: pose_scene + set_scene", cpu_update);
  print("  of which pose_scene", cpu_pose);
  print("  of which set_scene", cpu_upload);
  std::printf("the frame that draws it:\n");
  print("GPU: deformed in the vertex shader", gpu_frame);
  print("re-upload: static meshes", cpu_frame);
  return 0;
}
