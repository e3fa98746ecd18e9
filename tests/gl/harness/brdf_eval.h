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
  // The base layer's extensions (BaseLayer's defaults: none).
  float ior = 1.5f;
  float specular = 1.0f;
  glm::vec3 specular_color{1.0f};
  float anisotropy = 0.0f;
  float iridescence = 0.0f;
  float iridescence_ior = 1.3f;
  float iridescence_thickness = 0.0f;

  /// The same inputs for the C++ Brdf.
  BaseLayer layer() const {
    return {base_color,      metallic,
            roughness,       ior,
            specular,        specular_color,
            anisotropy,      iridescence,
            iridescence_ior, iridescence_thickness};
  }
};

/// brdf_test.glsl's std430 record of one case (6 vec4), shared with bsdf_eval.cpp.
void append_brdf_case(const BrdfCase& c, std::vector<glm::vec4>& out);

/// brdf_eval(make_brdf(layer), wo, wi) of brdf.glsl for every case, read back as RGB.
std::vector<glm::vec3> eval_brdf_glsl(const std::vector<BrdfCase>& cases,
                                      const BrdfOptions& options,
                                      FresnelMode fresnel = FresnelMode::kSchlick);

}  // namespace pbrkit::gl
