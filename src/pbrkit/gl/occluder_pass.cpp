#include "pbrkit/gl/occluder_pass.h"

#include <algorithm>
#include <utility>

#include "pbrkit/util/log.h"

namespace pbrkit::gl {

void OccluderPass::scene_changed(const GpuScene& scene) {
  occluders_ = ibl_occluders(scene, kinds_);
  changed_ = true;
}

void OccluderPass::begin_frame(const GpuScene& scene, OccluderKinds kinds,
                               ShaderPermutations& programs, SurfaceFeatures& features) {
  if (kinds != kinds_) {
    kinds_ = kinds;
    occluders_ = ibl_occluders(scene, kinds);
    changed_ = true;
  }
  if (occluders_.empty()) return;
  if (changed_) {
    selected_ = select_occluders(occluders_, counts_);
    if (selected_.size() < occluders_.size() && !std::exchange(limit_warned_, true))
      warn(
          "OpenGL renderer: {} objects shadow the environment light, more than a frame takes "
          "({} spheres and {} boxes at most); the {} largest do ({} spheres, {} boxes), the "
          "other {} do not",
          occluders_.size(), kMaxOccluders, kMaxOccluders, selected_.size(), counts_.x, counts_.y,
          occluders_.size() - selected_.size());
    buffer_.upload(selected_);
    programs.set_occluder_geometry(occluder_geometry_define(selected_));
    changed_ = false;
  }
  buffer_.bind();
  features.sphere_occluders = counts_.x;
  features.box_occluders = counts_.y;
  features.occluder_bounce =
      std::any_of(selected_.begin(), selected_.end(), [](const Occluder& o) { return o.opaque; });
}

}  // namespace pbrkit::gl
