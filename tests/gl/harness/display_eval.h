#pragma once
// Evaluates the GLSL display transform (shaders/display.glsl) on the GPU for a batch of
// linear colours, through a compute shader: the shader unit test that shows the viewer's
// GPU display pass shows what the PNG outputs hold. Needs a current GL 4.5 context.
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/core/color.h"

namespace pbrkit::gl {

/// display_transform(linear, exposure_ev, mapper) of display.glsl for every colour.
std::vector<glm::vec3> display_transform_glsl(const std::vector<glm::vec3>& linear,
                                              float exposure_ev, ToneMapper mapper);

}  // namespace pbrkit::gl
