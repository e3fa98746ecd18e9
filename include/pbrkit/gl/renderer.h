#pragma once
// The real-time OpenGL 4.5 renderer: one scene (scene/scene.h), the material model of
// shaders/brdf.glsl (the C++ Brdf's twin), KHR_lights_punctual lights and split-sum IBL
// from the baker's maps (ibl/bake.h), rendered into a float framebuffer with MSAA and read
// back as linear RGB. Works in any current GL 4.5 core context: the headless EGL one
// (context.h) or a GLFW window's (apps/viewer/viewer.h). Output conventions (camera,
// environment orientation, exposure and tone mapping after readback) are the path tracer's.
//
// renderer.cpp is the frame: what is drawn in which order with which state. Its parts
// have files of their own: what a frame shows (render_settings.h), the IBL maps
// (ibl_maps.h), and, private to the renderer, the scene on the GPU (gpu_scene.h), its
// deforming meshes posed in the vertex shader (gpu_deformation.h), the
// shader permutations (shader_permutations.h), the framebuffers (render_targets.h), the
// environment light's shadows (occluder_pass.h), the software rasteriser's draw queue
// (draw_queue.h) and the GPU timer (gpu_timer.h).
#include <memory>
#include <optional>

#include "pbrkit/core/color.h"
#include "pbrkit/gl/ibl_maps.h"
#include "pbrkit/gl/render_settings.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

class Renderer {
 public:
  /// Compiles the programs; needs a current GL 4.5 core context.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads meshes, materials and textures (replacing any previous scene). The scene is
  /// drawn as given (a scene posed by pose_scene as posed) until set_pose().
  void set_scene(const Scene& scene);
  /// Poses the scene of the last set_scene() cheaply: uploads only the skins' joint
  /// matrices, the morph weights and the instance transforms at `pose` (and moves the
  /// lights; the first call after set_scene also uploads the deforming meshes' rest data,
  /// scene/pose.h's DeformingMesh: rest vertices, joint influences, morph targets); from
  /// then on the deforming meshes are morphed and skinned in the vertex
  /// shader from their rest data, whatever pose the vertices given to set_scene were in,
  /// with pose_scene's math (scene/pose.cpp), so the image is the one of set_scene with
  /// the scene pose_scene posed at `pose`. The cameras are the caller's (pose_scene poses
  /// them). What stays as set_scene computed it: the meshes' bounds (the transmissive pass's
  /// order and the environment shadows' proxies). Throws pbrkit::Error for an animation out
  /// of range, a time or a pose that is not finite (as pose_scene); a scene without motion
  /// takes only the rest pose.
  void set_pose(const PoseTime& pose);
  /// Replaces the scene's materials (same count and order; textures stay) without
  /// uploading anything: what the viewer's material overrides change per frame.
  void set_materials(const std::vector<Material>& materials);
  /// The sharp background: the equirect map (nullptr: none; background colour black).
  void set_environment(const Environment* env);
  /// The IBL maps (nullptr: no image-based lighting).
  void set_ibl(const IblMaps* maps);
  /// The environment light in one call, what every caller (the command, the Python module,
  /// the viewer, the benchmarks) gives a renderer: `env` as the sharp background and, with
  /// `bake`, its image-based lighting baked now (bake_environment, ibl/bake.h, with those
  /// options; ibl_maps_from_bake) and uploaded, the maps not kept. `env` nullptr: no
  /// environment (a black background, no IBL); `bake` std::nullopt: the background alone.
  /// `progress` is the bake's; false when it stopped the bake, which leaves no IBL.
  /// set_environment() and set_ibl() remain for maps made otherwise (tests, a bake read back).
  bool set_environment_light(const Environment* env,
                             const std::optional<BakeOptions>& bake = realtime_bake_options(),
                             const ProgressCallback& progress = {});

  /// Renders a frame of `width` x `height` into the renderer's float framebuffer.
  void render(const Camera& camera, int width, int height, const RenderSettings& settings);
  /// The last frame, linear RGBA float, row 0 at the top (as Image everywhere).
  Image read_back() const;
  /// Draws the last frame into the bound draw framebuffer (the window's, in the viewer),
  /// through the display transform of the PNG outputs (exposure, tone mapper, exact sRGB
  /// encoding; shaders/display.glsl) on the GPU: no read-back. The target must be 8-bit
  /// and not sRGB-encoding (GL_FRAMEBUFFER_SRGB is turned off), at least the frame's size.
  void display(float exposure_ev, ToneMapper mapper);
  /// GPU time of the last render() in milliseconds (two GL_TIMESTAMP queries); waits for it.
  double gpu_time_ms() const;
  /// The GPU time of the newest finished frame: the last render()'s if it is done, else
  /// the one before. For a per-frame display (the viewer), where waiting for the frame
  /// just submitted would make the CPU wait for the GPU every frame.
  double latest_gpu_time_ms();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// A complete headless render (context, upload, frame, readback) with IBL maps made
/// beforehand (nullptr: none). `env` may be null (no environment light).
Image render_headless(const Scene& scene, const Camera& camera, int width, int height,
                      const Environment* env, const IblMaps* ibl, const RenderSettings& settings);
/// The same with the environment light given as Renderer::set_environment_light gives it:
/// `env`'s maps baked with `bake` (std::nullopt: the background alone, no IBL).
Image render_headless(const Scene& scene, const Camera& camera, int width, int height,
                      const Environment* env, const std::optional<BakeOptions>& bake,
                      const RenderSettings& settings);

}  // namespace pbrkit::gl
