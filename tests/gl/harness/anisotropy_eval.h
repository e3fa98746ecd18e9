#pragma once
// Evaluates the GLSL anisotropic image-based lighting (shaders/anisotropy_ibl.glsl) on the
// GPU for a batch of inputs, through a compute shader: the shader unit test that shows the
// OpenGL renderer's taps and ibl/anisotropic_taps.h are one scheme. Needs a current GL 4.5
// context.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl {

/// The inputs of the functions of anisotropy_ibl.glsl (each function reads its own).
struct AnisotropyCase {
  glm::vec3 wo{0.0f, 0.0f, 1.0f};  ///< towards the viewer, local frame
  int tap = 0;
  float alpha_x = 0.5f, alpha_y = 0.1f;
  glm::mat3 frame{1.0f};  ///< world axes of the local frame (kRadiance)
};

enum class AnisotropyFunction {
  kTapPoint = 0,   ///< anisotropic_tap_point(tap) -> xy
  kTapWi = 1,      ///< anisotropic_tap(...)'s wi -> xyz
  kTapWeight = 2,  ///< anisotropic_tap(...)'s (weight, roughness) -> xy
  kRadiance =
      3,  ///< anisotropic_ibl_radiance(cube, 1 level, albedo, frame, rotation, wo, ax, ay) -> rgb
  kAlbedo = 4,  ///< (anisotropic_albedo(albedo texture, wo, ax, ay), 0, 0, 0)
};

/// `function` of anisotropy_ibl.glsl for every case, read back as one vec4 each. kRadiance
/// reads a one-level cube of 1x1 faces coloured `face_colors` (+X, -X, +Y, -Y, +Z, -Z) with
/// the environment rotation `rotation` (world_to_env's (cos, sin)); kRadiance and kAlbedo
/// read the renderer's albedo texture (create_anisotropic_albedo_texture).
std::vector<glm::vec4> eval_anisotropy_glsl(const std::vector<AnisotropyCase>& cases,
                                            AnisotropyFunction function,
                                            const std::array<glm::vec3, 6>& face_colors = {},
                                            glm::vec2 rotation = {1.0f, 0.0f});

}  // namespace pbrkit::gl
