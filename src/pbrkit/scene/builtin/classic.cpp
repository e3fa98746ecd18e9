// The classic test scenes: the seeds' metallic x roughness sphere grid, the white furnace
// and the Cornell box.
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

// 7 x 7 spheres (radius 0.4, spacing 1) in the XY plane centred on the origin; metallic
// rises 0 -> 1 along +Y (bottom row 0), roughness 0.05 -> 1 along +X.
Scene make_spheres() {
  Scene scene;
  scene.source = "builtin:spheres";
  const Mesh sphere = make_uv_sphere(0.4f, kSegments, kRings);
  for (int row = 0; row < 7; ++row) {
    for (int col = 0; col < 7; ++col) {
      Material m;
      m.name = "sphere_m" + std::to_string(row) + "_r" + std::to_string(col);
      m.base_color_factor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
      m.metallic_factor = float(row) / 6.0f;
      m.roughness_factor = 0.05f + 0.95f * float(col) / 6.0f;
      scene.materials.push_back(m);
      const glm::vec3 centre(float(col - 3), float(row - 3), 0.0f);
      add_mesh_instance(scene, sphere, int(scene.materials.size()) - 1,
                        glm::translate(glm::mat4(1.0f), centre));
    }
  }
  // tan(0.3) * 12 = 3.7 > 3.4, the grid's half extent.
  scene.cameras.push_back(look_at_camera("front", {0, 0, 12}, {0, 0, 0}, 0.6f));
  return scene;
}

// One white diffuse sphere (radius 1, baseColor 1, metallic 0, roughness 1): under a
// uniform white environment an energy-conserving renderer must return the environment.
Scene make_furnace() {
  Scene scene;
  scene.source = "builtin:furnace";
  Material m;
  m.name = "white";
  m.base_color_factor = glm::vec4(1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 1.0f;
  scene.materials.push_back(m);
  add_mesh_instance(scene, make_uv_sphere(1.0f, kSegments, kRings), 0);
  scene.cameras.push_back(look_at_camera("front", {0, 0, 4}, {0, 0, 0}, 0.6f));
  return scene;
}

// The Cornell box: a room x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +Z,
// white floor/ceiling/back, red left (-X) and green right (+X) walls, a short and a tall
// box, and an emissive quad just below the ceiling (KHR_materials_emissive_strength).
Scene make_cornell() {
  Scene scene;
  scene.source = "builtin:cornell";
  // Reflectances close to the measured Cornell box data (white 0.73, red 0.63/0.065/0.05,
  // green 0.14/0.45/0.09).
  scene.materials.push_back(diffuse("white", {0.73f, 0.73f, 0.73f}));
  scene.materials.push_back(diffuse("red", {0.63f, 0.065f, 0.05f}));
  scene.materials.push_back(diffuse("green", {0.14f, 0.45f, 0.091f}));
  Material light = diffuse("light", {0.78f, 0.78f, 0.78f});
  light.emissive_factor = glm::vec3(1.0f, 0.85f, 0.6f);
  light.emissive_strength = 15.0f;
  scene.materials.push_back(light);

  auto add = [&](Mesh mesh, const std::string& name, int material,
                 const glm::mat4& transform = glm::mat4(1.0f)) {
    mesh.name = name;
    add_mesh_instance(scene, std::move(mesh), material, transform);
  };
  add(make_quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}), "floor", 0);
  add(make_quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}), "ceiling", 0);
  add(make_quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}), "back", 0);
  add(make_quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}), "left", 1);
  add(make_quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}), "right", 2);
  add(make_quad({-0.25f, 1.98f, -0.2f}, {0.5f, 0, 0}, {0, 0, 0.4f}), "light", 3);

  const glm::vec3 up(0, 1, 0);
  glm::mat4 short_box = glm::translate(glm::mat4(1.0f), {0.35f, 0.0f, 0.3f});
  short_box = glm::rotate(short_box, glm::radians(-17.0f), up);
  add(make_box({-0.3f, 0.0f, -0.3f}, {0.3f, 0.6f, 0.3f}), "short_box", 0, short_box);
  glm::mat4 tall_box = glm::translate(glm::mat4(1.0f), {-0.35f, 0.0f, -0.35f});
  tall_box = glm::rotate(tall_box, glm::radians(17.0f), up);
  add(make_box({-0.3f, 0.0f, -0.3f}, {0.3f, 1.2f, 0.3f}), "tall_box", 0, tall_box);

  // From z = 3.8 the opening (half size 1 at distance 2.8) fits in tan(0.35) * 2.8 = 1.02.
  scene.cameras.push_back(look_at_camera("front", {0, 1, 3.8f}, {0, 1, 0}, 0.7f));
  return scene;
}

}  // namespace pbrkit::builtin
