#pragma once
// Evaluates the GLSL transmission functions (shaders/transmission.glsl) on the GPU for a
// batch of inputs, through a compute shader: the shader unit test of the OpenGL renderer's
// screen-space refraction, Beer-Lambert attenuation and dispersion, and of the thick
// objects' two-interface refraction (shaders/thick_refraction.glsl). Needs a current GL 4.5
// context.
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::gl {

/// The inputs of the functions of transmission.glsl (each function reads its own).
struct TransmissionCase {
  glm::vec3 n{0.0f, 0.0f, 1.0f};  ///< shading normal (or the point to project, kProject)
  float ior = 1.5f;
  glm::vec3 v{0.0f, 0.0f, 1.0f};  ///< towards the viewer
  float thickness = 0.0f;
  glm::vec3 model_scale{1.0f};
  float dispersion = 0.0f;
  glm::vec3 attenuation_color{1.0f};
  float attenuation_distance = 0.0f;  ///< <= 0: none
  float roughness = 0.5f;
  float width = 256.0f;        ///< the frame's width (transmission_lod)
  float distance = 0.0f;       ///< through the medium (volume_attenuation)
  glm::vec3 base_color{1.0f};  ///< punctual_transmission's Brdf (n is wo, v the mirrored wi)
  float metallic = 0.0f;
  glm::vec3 back_point{0.0f};               ///< a point of the back face (back_plane_distance)
  glm::vec3 back_normal{0.0f, 0.0f, 1.0f};  ///< the back face's outward normal
};

enum class TransmissionFunction {
  kVolumeRay = 0,    ///< volume_transmission_ray -> xyz
  kDispersion = 1,   ///< dispersion_iors -> xyz
  kAttenuation = 2,  ///< volume_attenuation -> xyz
  kRoughness = 3,    ///< (transmission_roughness, transmission_lod)
  kProject = 4,      ///< project_to_screen(view_projection, n) -> (uv, on screen)
  kPunctual = 5,     ///< punctual_transmission(Brdf(base, metallic, roughness, ior), n, v)
  /// refract_twice(v, n, back_normal, ior) -> (direction, 1 under total internal reflection)
  kRefractTwice = 6,
  /// (wyman_distance(distance, thickness, dot(n, v), ior), 0, 0, 0)
  kWymanDistance = 7,
  /// (back_plane_distance(p = n, t1 = v, distance, back_point, back_normal), 0, 0, 0)
  kBackPlaneDistance = 8,
  /// frame_hit(origin = n, direction = v, eval_frame_hit_glsl's depth) -> (uv, d, 1 where
  /// it meets the frame)
  kFrameHit = 9,
  /// reflected_frame(origin = n, direction = v, eval_reflected_frame_glsl's depth and
  /// colours, level 0) -> (the colour read, 1 where it reads the frame)
  kReflectedFrame = 10,
  /// frame_march(origin = n, direction = v, eval_frame_hit_glsl's depth) -> (uv, d, 1 where
  /// it passes behind the frame's surface)
  kFrameMarch = 11,
};

/// `function` of transmission.glsl for every case, read back as one vec4 each.
std::vector<glm::vec4> eval_transmission_glsl(const std::vector<TransmissionCase>& cases,
                                              TransmissionFunction function,
                                              const glm::mat4& view_projection = glm::mat4(1.0f));

/// A depth buffer for frame_hit: `width` x `height` window-space depths in [0, 1] (1: the
/// background), row 0 at the bottom as GL stores it.
struct FrameDepth {
  int width = 0, height = 0;
  std::vector<float> depth;
};

/// thick_refraction.glsl's frame_hit for every case (origin `n`, unit direction `v`) against
/// `depth`, seen through `view_projection`: (uv, d, 1 where the ray meets the frame).
std::vector<glm::vec4> eval_frame_hit_glsl(const std::vector<TransmissionCase>& cases,
                                           const FrameDepth& depth,
                                           const glm::mat4& view_projection);

/// thick_refraction.glsl's frame_march for every case (origin `n`, unit direction `v`)
/// against `depth`, seen through `view_projection`: (uv, d, 1 where it found a crossing).
std::vector<glm::vec4> eval_frame_march_glsl(const std::vector<TransmissionCase>& cases,
                                             const FrameDepth& depth,
                                             const glm::mat4& view_projection);

/// thick_refraction.glsl's reflected_frame for every case (origin `n`, unit direction `v`)
/// in the frame of depths `depth` and RGBA colours `colors` (the same size and row order),
/// seen through `view_projection`: (the colour read at level 0, 1 where it reads the frame).
std::vector<glm::vec4> eval_reflected_frame_glsl(const std::vector<TransmissionCase>& cases,
                                                 const FrameDepth& depth,
                                                 const std::vector<glm::vec4>& colors,
                                                 const glm::mat4& view_projection);

}  // namespace pbrkit::gl
