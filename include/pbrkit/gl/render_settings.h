#pragma once
// What a frame of the OpenGL renderer (renderer.h) shows and how: the BRDF model and
// Fresnel form, image-based and punctual lighting on or off, the irradiance form, MSAA,
// the background, and the live overrides of the viewer's panel. Typed values only; the
// command line's spellings are parsed in apps/pbrkit/gl_options.cpp.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/gl/debug_channels.h"

namespace pbrkit::gl {

/// What is behind the geometry.
struct Background {
  enum class Mode { kEnvironment, kBlurred, kColor };
  Mode mode = Mode::kEnvironment;
  float blur_lod = 3.0f;  ///< kBlurred: mip of the prefiltered specular cube
  glm::vec3 color{0.0f};  ///< kColor: linear RGB
};

enum class IrradianceMode { kSH, kCube };

/// The specular Fresnel term: Schlick's approximation, or UE4's spherical-Gaussian form.
enum class FresnelMode { kSchlick, kSphericalGaussian };

/// The grid of clustered shading (gl/light_clusters.h): square tiles of `tile_pixels` over
/// the viewport, `slices` depth slices exponential in view depth. Smaller clusters hold
/// fewer lights that miss their fragments, at more binning work per frame on the CPU
/// (docs/benchmarks_archive.md, "Many punctual lights", measures both on llvmpipe).
struct LightClusterGrid {
  int tile_pixels = 16;
  int slices = 32;
};

struct RenderSettings {
  BrdfOptions brdf;  ///< model (reference | classic) and multiscatter
  FresnelMode fresnel = FresnelMode::kSchlick;
  bool ibl = true;  ///< image-based lighting on (when maps are set)
  IrradianceMode irradiance = IrradianceMode::kSH;
  /// The environment's light on a surface is shadowed by the transmissive objects around it
  /// (each a proxy that hides part of the surface's hemisphere and lets its transmittance
  /// through; MODEL.md "Shadows of transmissive objects"), so that a floor seen through
  /// glass is lit only through it, as in the path tracer. Off: every surface sees the whole
  /// environment, as the Khronos Sample Viewer's do.
  bool transmissive_shadows = true;
  /// The environment's light on a surface is also shadowed by the opaque objects around it,
  /// each a proxy like a transmissive object's that hides part of the surface's hemisphere
  /// and sends back its own diffusely reflected environment light (MODEL.md "Shadows of
  /// opaque objects"): a floor beside a wall is lit by less of the sky and by the wall, as
  /// in the path tracer. Off by default: the Khronos Sample Viewer has no such shadows, and
  /// every opaque fragment pays a form factor per proxy.
  bool opaque_shadows = false;
  /// A thick transmissive surface (KHR_materials_volume) reflects the opaque frame where its
  /// mirror direction meets it on the screen (a screen-space reflection: the wall or floor
  /// the path tracer's reflected rays meet), and the environment elsewhere. Off: it
  /// reflects the environment alone, as the Khronos Sample Viewer's glass does.
  bool transmissive_reflections = true;
  bool lights = true;               ///< punctual lights on
  std::vector<bool> light_enabled;  ///< per light; missing entries are on
  /// Clustered shading of the punctual lights (gl/light_clusters.h): each fragment shades
  /// the lights whose range reaches its cluster, and every light without a range. Off:
  /// every fragment loops over every light (the same image up to the order of the sum).
  bool clustered_lights = true;
  LightClusterGrid light_clusters;
  int msaa = 4;  ///< samples per pixel (1 = off)
  /// On a software rasteriser (Mesa's llvmpipe), which queues the triangles it has binned for
  /// its rasteriser threads, the frame waits for that queue to drain after each this many
  /// triangles and draws a run of instances in chunks of at most that many (at least one
  /// instance each; a mesh of more in index ranges of that many): it bounds the memory the
  /// queue holds (a frame of 57 million instanced triangles: 1.5 GB at its peak without,
  /// 0.44 GB with 2 million; docs/benchmarks_archive.md, "The OpenGL frame's memory at production
  /// scale"). The same image either way. 0: never wait.
  /// A GPU's driver needs no such wait, and there it is not made.
  std::size_t software_queue_triangles = 2'000'000;
  Background background;
  float env_rotation_deg = 0.0f;
  float env_intensity = 1.0f;
  float metallic_override = -1.0f;   ///< >= 0 replaces every material's metallic
  float roughness_override = -1.0f;  ///< >= 0 replaces every material's roughness
  /// What the surfaces write: the shaded colour, or a material input or one lobe's share
  /// of it, raw (debug_channels.h).
  DebugChannel debug_channel = DebugChannel::kNone;
};

}  // namespace pbrkit::gl
