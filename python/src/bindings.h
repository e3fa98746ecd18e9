#pragma once
// The pbrkit Python module's parts: one registration function per concept, each in its
// own file, all called from module.cpp.
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/scene/pose.h"

namespace pbrkit::python {

void bind_scene(pybind11::module_& m);   ///< load(), Scene, Camera, look_at()
void bind_render(pybind11::module_& m);  ///< render()
void bind_images(pybind11::module_& m);  ///< read/write_image, compare, tonemap, denoise
void bind_bake(pybind11::module_& m);    ///< bake()
void bind_brdf(pybind11::module_& m);    ///< D, G, F, albedo

/// The `denoiser=` argument of render() and denoise(): None (kDefaultDenoiser),
/// "learned" or "classic"; anything else a ValueError.
DenoiserChoice denoiser_choice(const std::optional<std::string>& name);

/// The `animation=` and `animation_time=` arguments of render() and Scene.pose() as a pose
/// of `scene`: the animation by name or index (None: the rest pose, which takes no time);
/// a TypeError or ValueError naming the argument, the ValueError listing the animations.
PoseTime pose_argument(const Scene& scene, const pybind11::object& animation, double time,
                       const char* animation_arg, const char* time_arg);

}  // namespace pbrkit::python
