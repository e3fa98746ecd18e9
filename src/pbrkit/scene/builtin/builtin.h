#pragma once
// The built-in scenes by family, private to the scene module: each family's scenes
// (scene/builtin/<family>.cpp) and what they share. builtin_scene() (scene/load.h) names
// them.
#include <string>

#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit::builtin {

// Sphere tessellation: 64 x 32 keeps the silhouette smooth at 512 px.
constexpr int kSegments = 64;
constexpr int kRings = 32;

/// A perspective camera at `eye` looking at `target` (+Y up), square aspect.
Camera look_at_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov);

/// A rough (roughness 1) diffuse dielectric of base colour `color`.
Material diffuse(const std::string& name, glm::vec3 color);

/// An unnamed material of base colour `color`, `metallic` and `roughness`.
Material base_material(glm::vec3 color, float metallic, float roughness);

// The classic test scenes (builtin/classic.cpp).
Scene make_spheres();
Scene make_furnace();
Scene make_cornell();

// The KHR_materials_* comparison rows (builtin/extension_rows.cpp).
Scene make_clearcoat();
Scene make_sheen();
Scene make_anisotropy();
Scene make_iridescence();
Scene make_specular();
Scene make_ior();
Scene make_unlit();

// The transmission scenes (builtin/transmission.cpp).
Scene make_glass();
Scene make_liquid();

// The instanced rock field (builtin/instances.cpp).
Scene make_instances();

// The room of many lights (builtin/lights.cpp).
Scene make_lights();

// The sunlit room seen from inside (builtin/interior.cpp).
Scene make_interior();

}  // namespace pbrkit::builtin
