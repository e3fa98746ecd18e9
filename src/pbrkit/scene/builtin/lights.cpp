// The many-lights scene: a closed room of emissive panels and punctual lights.
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

// lights: a closed room (x in [-4, 4], y in [0, 3], z in [-7, 7], the camera inside near
// the +Z wall) lit by many emitters of different power, colour and size, and no
// environment (render it with --no-env: the walls hide the environment from the path
// tracer, but the OpenGL renderer's image-based lighting has no occlusion):
// - 18 emissive ceiling panels (KHR_materials_emissive_strength) in three rows: warm
//   0.6 m squares at the sides (one panel mesh placed 12 times: instances), cool
//   0.25 x 1.5 m strips down the middle (another, placed 6 times);
// - 5 coloured emissive panels on the back wall, each its own mesh and colour;
// - KHR_lights_punctual lights, every one with a range (where its window
//   clamp(1 - (d / range)^4, 0, 1) ends, so a renderer may cull it beyond): 6 spot lights
//   from the ceiling making pools on the floor and the objects, 12 warm wall sconces, and
//   64 dim coloured LEDs along the foot of the side walls.
// 23 emissive instances (46 triangles) and 82 punctual lights: 105 emitters whose powers
// span more than a decade. The spots and sconces come first in the light list, so a
// renderer that shades only the first lights still shows the pools of light.
Scene make_lights() {
  Scene scene;
  scene.source = "builtin:lights";
  auto add_material = [&](Material m) {
    scene.materials.push_back(std::move(m));
    return int(scene.materials.size()) - 1;
  };
  auto add = [&](Mesh mesh, const std::string& name, int material,
                 const glm::mat4& transform = glm::mat4(1.0f)) {
    mesh.name = name;
    return add_mesh_instance(scene, std::move(mesh), material, transform);
  };
  constexpr float kHalfWidth = 4.0f, kHeight = 3.0f, kHalfLength = 7.0f;

  // The room: quads facing inwards (make_quad's normal is cross(edge_u, edge_v)).
  Material floor = diffuse("floor", {0.45f, 0.36f, 0.28f});
  floor.roughness_factor = 0.35f;  // a satin floor: the panels and pools glint in it
  const int floor_m = add_material(floor);
  const int ceiling_m = add_material(diffuse("ceiling", {0.8f, 0.8f, 0.78f}));
  const int wall_m = add_material(diffuse("wall", {0.7f, 0.68f, 0.62f}));
  const int back_m = add_material(diffuse("back_wall", {0.25f, 0.3f, 0.4f}));
  const float w = kHalfWidth, h = kHeight, l = kHalfLength;
  add(make_quad({-w, 0, l}, {2 * w, 0, 0}, {0, 0, -2 * l}), "floor", floor_m);
  add(make_quad({-w, h, -l}, {2 * w, 0, 0}, {0, 0, 2 * l}), "ceiling", ceiling_m);
  add(make_quad({-w, 0, -l}, {2 * w, 0, 0}, {0, h, 0}), "back_wall", back_m);
  add(make_quad({w, 0, l}, {-2 * w, 0, 0}, {0, h, 0}), "front_wall", wall_m);
  add(make_quad({-w, 0, l}, {0, 0, -2 * l}, {0, h, 0}), "left_wall", wall_m);
  add(make_quad({w, 0, -l}, {0, 0, 2 * l}, {0, h, 0}), "right_wall", wall_m);

  // Objects of varied materials.
  const glm::vec3 up(0, 1, 0);
  const int plinth_m = add_material(diffuse("plinth", {0.75f, 0.75f, 0.75f}));
  add(make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 0.8f, 0.5f}), "plinth", plinth_m,
      glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -3.0f}));
  const int gold_m = add_material(base_material({1.0f, 0.78f, 0.34f}, 1.0f, 0.25f));
  scene.materials.back().name = "gold";
  add(make_uv_sphere(0.35f, kSegments, kRings), "gold_sphere", gold_m,
      glm::translate(glm::mat4(1.0f), {0.0f, 1.15f, -3.0f}));
  const int red_m = add_material(base_material({0.7f, 0.06f, 0.04f}, 0.0f, 0.6f));
  scene.materials.back().name = "red_plastic";
  add(make_box({-0.45f, 0.0f, -0.45f}, {0.45f, 0.9f, 0.45f}), "red_box", red_m,
      glm::rotate(glm::translate(glm::mat4(1.0f), {-2.0f, 0.0f, -0.5f}), glm::radians(25.0f), up));
  const int green_m = add_material(base_material({0.08f, 0.35f, 0.2f}, 0.0f, 0.15f));
  scene.materials.back().name = "green_glaze";
  add(make_lathe({{0.0f, 0.0f},
                  {0.25f, 0.0f},
                  {0.4f, 0.35f},
                  {0.3f, 0.9f},
                  {0.18f, 1.1f},
                  {0.2f, 1.3f},
                  {0.0f, 1.3f}},
                 kSegments),
      "vase", green_m, glm::translate(glm::mat4(1.0f), {2.2f, 0.0f, -1.5f}));
  const int chrome_m = add_material(base_material({0.95f, 0.95f, 0.95f}, 1.0f, 0.05f));
  scene.materials.back().name = "chrome";
  add(make_uv_sphere(0.5f, kSegments, kRings), "chrome_sphere", chrome_m,
      glm::translate(glm::mat4(1.0f), {1.5f, 0.5f, 2.0f}));

  // Ceiling panels, 1 cm below the ceiling, facing down: one unit quad per row, scaled
  // into place at each of its instances.
  auto emissive = [](const std::string& name, glm::vec3 color, float strength) {
    Material m = diffuse(name, {0.8f, 0.8f, 0.8f});
    m.emissive_factor = color;
    m.emissive_strength = strength;
    return m;
  };
  const int warm_m = add_material(emissive("panel_warm", {1.0f, 0.8f, 0.55f}, 3.0f));
  const int cool_m = add_material(emissive("panel_cool", {0.75f, 0.85f, 1.0f}, 5.0f));
  Mesh panel = make_quad({-0.5f, 0.0f, -0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  panel.name = "panel_warm";
  panel.material = warm_m;
  scene.meshes.push_back(panel);
  const int warm_mesh = int(scene.meshes.size()) - 1;
  panel.name = "panel_cool";
  panel.material = cool_m;
  scene.meshes.push_back(panel);
  const int cool_mesh = int(scene.meshes.size()) - 1;
  // Each mesh's instances together (a glTF file holds them so: one node per repeated mesh).
  for (int k = 0; k < 6; ++k)
    for (const float x : {-2.6f, 2.6f}) {
      const glm::mat4 at = glm::translate(glm::mat4(1.0f), {x, h - 0.01f, -5.5f + 2.2f * float(k)});
      scene.instances.push_back({warm_mesh, glm::scale(at, {0.6f, 1.0f, 0.6f}), -1});
    }
  for (int k = 0; k < 6; ++k) {
    const glm::mat4 at =
        glm::translate(glm::mat4(1.0f), {0.0f, h - 0.01f, -5.5f + 2.2f * float(k)});
    scene.instances.push_back({cool_mesh, glm::scale(at, {0.25f, 1.0f, 1.5f}), -1});
  }
  // Coloured panels on the back wall, 1 cm in front of it.
  const glm::vec3 accents[] = {{1.0f, 0.2f, 0.1f},
                               {1.0f, 0.7f, 0.1f},
                               {0.2f, 1.0f, 0.3f},
                               {0.1f, 0.5f, 1.0f},
                               {0.7f, 0.2f, 1.0f}};
  for (int k = 0; k < 5; ++k) {
    const int m = add_material(emissive("accent_" + std::to_string(k), accents[k], 2.0f));
    const float x = -3.0f + 1.5f * float(k);
    add(make_quad({x - 0.25f, 1.0f, -l + 0.01f}, {0.5f, 0.0f, 0.0f}, {0.0f, 1.2f, 0.0f}),
        "accent_" + std::to_string(k), m);
  }

  // Punctual lights (KHR_lights_punctual: point and spot intensity in candela).
  auto light = [&](Light::Type type, const std::string& name, glm::vec3 position, glm::vec3 color,
                   float intensity, float range) {
    Light added;
    added.type = type;
    added.name = name;
    added.position = position;
    added.color = color;
    added.intensity = intensity;
    added.range = range;
    scene.lights.push_back(added);
    return &scene.lights.back();
  };
  struct Spot {
    glm::vec3 target;
    glm::vec3 color;
    float intensity;
  };
  const Spot spots[] = {{{0.0f, 1.0f, -3.0f}, {1.0f, 0.95f, 0.85f}, 45.0f},
                        {{-2.0f, 0.5f, -0.5f}, {1.0f, 0.85f, 0.6f}, 40.0f},
                        {{2.2f, 0.6f, -1.5f}, {0.9f, 0.95f, 1.0f}, 40.0f},
                        {{1.5f, 0.5f, 2.0f}, {1.0f, 1.0f, 1.0f}, 30.0f},
                        {{-1.8f, 0.0f, 3.5f}, {0.4f, 0.6f, 1.0f}, 60.0f},
                        {{0.5f, 0.0f, -5.5f}, {1.0f, 0.35f, 0.6f}, 60.0f}};
  for (int k = 0; k < 6; ++k) {
    const glm::vec3 from(0.6f * spots[k].target.x, h - 0.1f, spots[k].target.z + 0.3f);
    Light* s = light(Light::Type::kSpot, "spot_" + std::to_string(k), from, spots[k].color,
                     spots[k].intensity, 6.0f);
    s->direction = glm::normalize(spots[k].target - from);
    s->inner_cone_angle = 0.2f;
    s->outer_cone_angle = 0.4f;
  }
  for (int k = 0; k < 6; ++k)
    for (const float x : {-w + 0.3f, w - 0.3f})
      light(Light::Type::kPoint, "sconce_" + std::to_string(scene.lights.size()),
            {x, 2.1f, -5.5f + 2.2f * float(k)}, {1.0f, 0.7f, 0.4f}, 2.5f, 3.5f);
  // LEDs cycling through six hues, every 0.43 m along each side wall. The point lights
  // keep 0.2 m or more from the surfaces: the inverse-square hot spot of a light nearer
  // still would light the room indirectly through a few pixels (fireflies).
  const glm::vec3 hues[] = {{1.0f, 0.1f, 0.1f}, {1.0f, 0.6f, 0.0f}, {0.2f, 1.0f, 0.2f},
                            {0.0f, 0.8f, 1.0f}, {0.2f, 0.2f, 1.0f}, {1.0f, 0.1f, 0.9f}};
  for (int k = 0; k < 32; ++k)
    for (const float x : {-w + 0.2f, w - 0.2f})
      light(Light::Type::kPoint, "led_" + std::to_string(scene.lights.size()),
            {x, 0.25f, -l + 0.3f + 0.43f * float(k)}, hues[k % 6], 0.25f, 1.2f);

  Camera camera = look_at_camera("front", {0.0f, 1.7f, l - 0.5f}, {0.0f, 1.0f, -3.0f}, 0.9f);
  camera.aspect_ratio = 1.5f;
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace pbrkit::builtin
