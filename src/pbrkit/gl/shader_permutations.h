#pragma once
// Private to the OpenGL renderer (renderer.cpp): its shader permutations. Each program is
// one pair of shader files compiled with a set of #defines; every set in use is its own
// program, compiled on first use and kept, as real-time engines do.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "pbrkit/core/color.h"
#include "pbrkit/gl/program.h"
#include "pbrkit/gl/surface_bindings.h"

namespace pbrkit::gl {

// The most lights LIGHTS 1 compiles in as a constant (llvmpipe runs the unrolled loop
// over constant buffer offsets faster than one over a uniform count).
inline constexpr int kCompiledLightCount = 16;

/// One #define of the surface program (pbr_fragment.glsl and the files it includes).
struct SurfaceDefine {
  std::string name;          ///< e.g. "MATERIAL_SHEEN", "HAS_BASE_COLOR_TEXTURE"
  int value = 0;             ///< its value in this permutation
  const char* meaning = "";  ///< what it selects in the shaders, and its values
};

// Compile-time features of the surface program. They are #defines rather than uniforms
// because llvmpipe, the software rasteriser of CI and headless servers, runs both sides of a
// branch on a uniform with masked lanes: an unused texture or IBL term would still cost its
// fetches. define_list() names each one and says what it selects.
struct SurfaceFeatures {
  unsigned textures = 0;  ///< bit t: texture slot t bound (scene.h's TextureSlot: HAS_<slot>)
  bool colors = false;    ///< the mesh has COLOR_0
  int alpha_mode = 0;     ///< 0 opaque, 1 mask, 2 blend
  bool ibl = false;
  bool irradiance_sh = true;
  bool multiscatter = false;
  int geometry = 0;  ///< GeometryModel for punctual lights
  int fresnel = 0;   ///< 0 Schlick, 1 spherical Gaussian
  /// punctual lights (LIGHTS): 0 none, 1 every light, 2 clustered, 3 clustered with spot
  /// lights among them
  int lights = 0;
  /// LIGHTS 1: the number of lights when it is compiled in (up to kCompiledLightCount; the
  /// loop unrolls over constant indices), -1 when the shader reads it (uLightCount).
  int light_count = -1;
  // The KHR_materials_* extensions the material uses (pbr_fragment.glsl's MATERIAL_*).
  bool specular = false;  ///< KHR_materials_ior / _specular (ior != 1.5 or the extension)
  bool anisotropy = false;
  bool iridescence = false;
  bool clearcoat = false;
  bool sheen = false;
  bool unlit = false;
  // The transmission features (transmission.glsl): KHR_materials_transmission (the screen-space
  // refraction of the opaque frame), _volume (thickness > 0: refraction through a thick medium and
  // Beer-Lambert attenuation), _dispersion (three iors), _diffuse_transmission.
  bool transmission = false;
  bool volume = false;
  bool dispersion = false;
  bool diffuse_transmission = false;
  /// What the surfaces write (debug_channels.glsl's DEBUG_CHANNEL: DebugChannel's value).
  int debug_channel = 0;
  /// The environment light is shadowed by the scene's transmissive objects
  /// (occluders.glsl's IBL_OCCLUDERS): their proxies, spheres and parallelepipeds, up to
  /// kMaxOccluders of each.
  int sphere_occluders = 0;
  int box_occluders = 0;
  /// Some of the occluders are opaque objects' proxies, which send back their own light
  /// (occluders.glsl's OCCLUDER_BOUNCE; RenderSettings::opaque_shadows).
  bool occluder_bounce = false;
  /// A thick transmissive surface's specular reflection reads the opaque frame where the
  /// mirror direction meets it on the screen (pbr_fragment.glsl's GLASS_REFLECTIONS).
  bool glass_reflections = false;
  /// The mesh deforms in the vertex shader (deformation.glsl's DEFORM): 0 no, 1 morphed and
  /// skinned from its rest data (gpu_deformation.h), 2 the same with flat normals made from
  /// each deformed triangle's corners.
  int deform = 0;

  /// Where key() holds the occluder counts (kOccluderKeyBits): occluder_bits() is not 0
  /// for a program that compiles occluders in.
  static constexpr int kOccluderKeyShift = 53;
  static constexpr int kOccluderKeyBits = 10;
  static std::uint64_t occluder_bits(std::uint64_t key) {
    return (key >> kOccluderKeyShift) & ((std::uint64_t(1) << kOccluderKeyBits) - 1);
  }
  std::uint64_t key() const {
    // The texture bits take the key's low 19 bits; more slots need the fields below moved.
    static_assert(kTextureSlotCount <= 19, "SurfaceFeatures::key: widen the texture bits");
    return std::uint64_t(textures) | std::uint64_t(alpha_mode) << 19 | std::uint64_t(ibl) << 21 |
           std::uint64_t(irradiance_sh) << 22 | std::uint64_t(multiscatter) << 23 |
           std::uint64_t(geometry) << 24 | std::uint64_t(fresnel) << 26 |
           std::uint64_t(lights) << 27 | std::uint64_t(occluder_bounce) << 29 |
           std::uint64_t(deform) << 30 | std::uint64_t(colors) << 32 |
           std::uint64_t(specular) << 33 | std::uint64_t(anisotropy) << 34 |
           std::uint64_t(iridescence) << 35 | std::uint64_t(clearcoat) << 36 |
           std::uint64_t(sheen) << 37 | std::uint64_t(unlit) << 38 |
           std::uint64_t(transmission) << 39 | std::uint64_t(volume) << 40 |
           std::uint64_t(dispersion) << 41 | std::uint64_t(diffuse_transmission) << 42 |
           std::uint64_t(light_count + 1) << 43 | std::uint64_t(debug_channel) << 48 |
           std::uint64_t(sphere_occluders) << kOccluderKeyShift |
           std::uint64_t(box_occluders) << (kOccluderKeyShift + 5) |
           std::uint64_t(glass_reflections) << (kOccluderKeyShift + kOccluderKeyBits);
  }
  /// The #defines of this permutation, each with what it selects (shader_permutations.cpp
  /// documents every one; no GLSL file lists them), in the order defines() writes them.
  std::vector<SurfaceDefine> define_list() const;
  /// surface_prelude() (slots, units and binding points) and then define_list() as
  /// `#define NAME value` lines: the text every surface program starts with.
  std::string defines() const;
};

/// Sets `f`'s transmission features (transmission, volume, dispersion, diffuse
/// transmission) for material `m` on a mesh that is closed or not.
void set_transmission_features(const Material& m, bool closed, SurfaceFeatures& f);

/// The renderer's programs: the surface program per SurfaceFeatures, the background's per
/// MODE (0 environment, 1 blurred, 2 colour; background_fragment.glsl) and the display
/// transform's per ToneMapper. Needs the current GL context for its whole life.
class ShaderPermutations {
 public:
  /// Compiles the default surface program and the three background programs.
  ShaderPermutations();

  const Program& surface(const SurfaceFeatures& f);
  /// The occluders' geometry the surface programs with occluders compile in
  /// (occluders.h's occluder_geometry_define); a change drops the programs compiled with
  /// the previous one.
  void set_occluder_geometry(std::string define);
  const Program& background(int mode) const { return background_[std::size_t(mode)]; }
  const Program& display(ToneMapper mapper);

 private:
  std::unordered_map<std::uint64_t, Program> surface_;  // by SurfaceFeatures::key
  std::string occluder_geometry_;
  std::array<Program, 3> background_;  // by background MODE
  std::array<Program, 4> display_;     // by ToneMapper, compiled on first use
};

}  // namespace pbrkit::gl
