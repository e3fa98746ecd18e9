#pragma once
// Evaluates the GLSL BRDF (shaders/brdf.glsl) on the GPU for a batch of inputs, through a
// compute shader: the shader unit test that shows the OpenGL renderer and the C++ Brdf
// (and so the path tracer) are one model. Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/gl/render_settings.h"

namespace pbrkit::gl {

struct BrdfCase {
  glm::vec3 wo{0.0f, 0.0f, 1.0f};  ///< local frame, towards the viewer
  glm::vec3 wi{0.0f, 0.0f, 1.0f};  ///< local frame, towards the light
  glm::vec3 base_color{1.0f};
  float metallic = 0.0f;
  float roughness = 0.5f;
};

/// brdf_eval(make_brdf(...), wo, wi) of brdf.glsl for every case, read back as RGB.
std::vector<glm::vec3> eval_brdf_glsl(const std::vector<BrdfCase>& cases,
                                      const BrdfOptions& options,
                                      FresnelMode fresnel = FresnelMode::kSchlick);

}  // namespace pbrkit::gl
