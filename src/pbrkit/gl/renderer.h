#pragma once
// The real-time OpenGL 4.5 renderer: one scene (scene/scene.h), the material model of
// shaders/brdf.glsl (the C++ Brdf's twin), KHR_lights_punctual lights and split-sum IBL
// from the baker's maps (ibl/bake.h), rendered into a float framebuffer with MSAA and read
// back as linear RGB. Works in any current GL 4.5 core context: the headless EGL one
// (context.h) or a GLFW window's (viewer.h). Output conventions (camera, environment
// orientation, exposure and tone mapping after readback) are the path tracer's.
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/gl/brdf_eval.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image.h"
#include "pbrkit/scene/scene.h"

namespace pbrkit::gl {

/// What is behind the geometry.
struct Background {
  enum class Mode { kEnvironment, kBlurred, kColor };
  Mode mode = Mode::kEnvironment;
  float blur_lod = 3.0f;  ///< kBlurred: mip of the prefiltered specular cube
  glm::vec3 color{0.0f};  ///< kColor: linear RGB
};

enum class IrradianceMode { kSH, kCube };

/// Image-based lighting maps as the baker makes them (ibl/bake.h). The cubes hold the
/// environment as it was baked, i.e. with `rotation_deg` and `intensity` already applied;
/// the renderer applies only the difference to the current settings.
struct IblMaps {
  Cubemap specular;
  Cubemap irradiance;
  SH9 sh{};
  float rotation_deg = 0.0f;
  float intensity = 1.0f;
};
/// IblMaps from a bake of `env` (its rotation and intensity are baked in).
IblMaps ibl_maps_from_bake(BakeResult bake, const Environment& env);
/// The bake the real-time renderer makes on the fly from an environment (`pbrkit render
/// --renderer gl`, `pbrkit view`): `face_size` px specular faces down to 8 px, `samples`
/// GGX samples, a 16 px irradiance cube and a 32 px LUT, and a quadrature budget of 2^30
/// (the rough levels exact, the roughness-0.25 one sampled) so that it takes well under a
/// second on two cores.
BakeOptions realtime_bake_options(int face_size = 128, int samples = 256);

struct RenderSettings {
  BrdfOptions brdf;  ///< model (reference | classic) and multiscatter
  FresnelMode fresnel = FresnelMode::kSchlick;
  bool ibl = true;  ///< image-based lighting on (when maps are set)
  IrradianceMode irradiance = IrradianceMode::kSH;
  bool lights = true;               ///< punctual lights on
  std::vector<bool> light_enabled;  ///< per light; missing entries are on
  int msaa = 4;                     ///< samples per pixel (1 = off)
  Background background;
  float env_rotation_deg = 0.0f;
  float env_intensity = 1.0f;
  float metallic_override = -1.0f;   ///< >= 0 replaces every material's metallic
  float roughness_override = -1.0f;  ///< >= 0 replaces every material's roughness
};

class Renderer {
 public:
  /// Compiles the programs; needs a current GL 4.5 core context.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads meshes, materials and textures (replacing any previous scene).
  void set_scene(const Scene& scene);
  /// The sharp background: the equirect map (nullptr: none; background colour black).
  void set_environment(const Environment* env);
  /// The IBL maps (nullptr: no image-based lighting).
  void set_ibl(const IblMaps* maps);

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

/// A complete headless render (context, upload, optional bake, frame, readback): what
/// `pbrkit render --renderer gl` runs. `env` may be null (no environment light).
Image render_headless(const Scene& scene, const Camera& camera, int width, int height,
                      const Environment* env, const IblMaps* ibl, const RenderSettings& settings);

}  // namespace pbrkit::gl
