#pragma once
// Private to the OpenGL renderer (renderer.cpp): the frame's shadows of the environment
// light, as a part of its own. It keeps the proxies (occluders.h) of the kinds of objects
// the settings ask for, remade when the scene, its materials or those kinds change, and on
// a change selects the ones a frame compiles in, uploads their transmittances and hands
// their geometry to the surface programs.
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/gl/occluders.h"
#include "pbrkit/gl/shader_permutations.h"

namespace pbrkit::gl {

class OccluderPass {
 public:
  /// The scene or its materials changed (Renderer::set_scene, set_materials): the proxies
  /// are remade for the current kinds and selected again at the next frame.
  void scene_changed(const GpuScene& scene);
  /// At the start of a frame: remakes the proxies when `kinds` differ from the last
  /// frame's, selects and uploads them after any change (warning once per renderer when a
  /// frame cannot take them all), binds their buffer and sets the occluder features every
  /// surface permutation of the frame shares (`features`).
  void begin_frame(const GpuScene& scene, OccluderKinds kinds, ShaderPermutations& programs,
                   SurfaceFeatures& features);

 private:
  std::vector<Occluder> occluders_;  // ibl_occluders' for kinds_
  OccluderKinds kinds_;
  std::vector<Occluder> selected_;  // select_occluders' of them
  bool changed_ = true;             // since they were last selected and uploaded
  bool limit_warned_ = false;       // more than kMaxOccluders of a kind (warned once)
  glm::ivec2 counts_{0};            // the selection's spheres and parallelepipeds
  GpuOccluderBuffer buffer_;
};

}  // namespace pbrkit::gl
