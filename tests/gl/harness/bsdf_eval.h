#pragma once
// Evaluates the GLSL layered material (shaders/bsdf.glsl: clearcoat over sheen over the
// base layer) on the GPU for a batch of inputs, as brdf_eval.h does for the base layer:
// the shader unit test that shows the OpenGL renderer's punctual-light shading and the C++
// Bsdf (and so the path tracer) are one model. Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

#include "gl/harness/brdf_eval.h"
#include "pbrkit/core/bsdf.h"

namespace pbrkit::gl {

struct BsdfCase {
  BrdfCase base;  ///< directions and the base layer
  float coat_weight = 0.0f;
  float coat_roughness = 0.0f;
  glm::vec3 coat_normal{0.0f, 0.0f, 1.0f};  ///< in the base's local frame
  glm::vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;

  /// The same inputs for the C++ Bsdf.
  SurfaceParams params() const {
    SurfaceParams p;
    p.base = base.layer();
    p.coat = {coat_weight, coat_roughness, coat_normal};
    p.sheen = {sheen_color, sheen_roughness};
    return p;
  }
};

/// bsdf_eval(make_bsdf(...), wo, wi) of bsdf.glsl for every case, read back as RGB.
std::vector<glm::vec3> eval_bsdf_glsl(const std::vector<BsdfCase>& cases,
                                      const BrdfOptions& options);

}  // namespace pbrkit::gl
