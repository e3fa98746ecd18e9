// The sunlit interior: a closed room lit through one window, seen from inside.
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

// interior: a room x in [-2, 2], y in [0, 3], z in [-2.5, 2.5] (4 x 3 x 5 m inside) with a
// 1.2 x 1.4 m window in the +Z wall, a sun (KHR_lights_punctual directional) shining
// steeply through it onto the floor, and the camera by the window looking away from it, so
// that almost all it sees is lit by light that has bounced at least once: a test of
// indirect light (a renderer without global illumination shows a dark room).
//
// The shell is boxes 0.2 m thick that overlap at every edge and corner, so a ray can leave
// the room only through the window: where single-sided quads meet at an edge, whether a
// ray through the edge hits either is a matter of rounding, and the sun would leak in.
//
// The environment (a built-in scene cannot name one: the render command's default, or
// --env) is seen and lets light in only through the window. The sun's 100 lux are about
// ten times the default environment's (data/env/city.exr) illuminance on a horizontal
// plane (about 9.3), the ratio on a clear day of the direct sun (100,000 lux at normal
// incidence) to the sky's light (10,000 lux on the ground). The albedos are a light room's,
// so that what the camera sees averages about 0.16 in linear radiance, near middle grey:
// --exposure 0 shows the room as it is (there is no per-scene exposure).
Scene make_interior() {
  Scene scene;
  scene.source = "builtin:interior";
  auto add_material = [&](Material m) {
    scene.materials.push_back(std::move(m));
    return int(scene.materials.size()) - 1;
  };
  auto add = [&](Mesh mesh, const std::string& name, int material,
                 const glm::mat4& transform = glm::mat4(1.0f)) {
    mesh.name = name;
    return add_mesh_instance(scene, std::move(mesh), material, transform);
  };
  constexpr float kHalfWidth = 2.0f, kHeight = 3.0f, kHalfDepth = 2.5f, kWall = 0.2f;
  // The window in the +Z wall: x in [kWindowX0, kWindowX1], y in [kSill, kLintel].
  constexpr float kWindowX0 = -0.2f, kWindowX1 = 1.0f, kSill = 0.9f, kLintel = 2.3f;
  const float w = kHalfWidth, h = kHeight, d = kHalfDepth, t = kWall;

  // The shell. Each box reaches through the others' thickness (the floor and ceiling
  // under and over the walls, the side walls past the end walls), so every inside edge is
  // a fold of one box's face into another's and nothing is open but the window.
  Material floor = base_material({0.5f, 0.36f, 0.22f}, 0.0f, 0.15f);  // varnished oak
  floor.name = "floor";
  const int floor_m = add_material(floor);
  const int ceiling_m = add_material(diffuse("ceiling", {0.85f, 0.85f, 0.83f}));
  const int wall_m = add_material(diffuse("wall", {0.8f, 0.77f, 0.7f}));
  const int accent_m = add_material(diffuse("back_wall", {0.42f, 0.58f, 0.66f}));
  add(make_box({-w - t, -t, -d - t}, {w + t, 0.0f, d + t}), "floor", floor_m);
  add(make_box({-w - t, h, -d - t}, {w + t, h + t, d + t}), "ceiling", ceiling_m);
  add(make_box({-w - t, -t, -d - t}, {-w, h + t, d + t}), "left_wall", wall_m);
  add(make_box({w, -t, -d - t}, {w + t, h + t, d + t}), "right_wall", wall_m);
  add(make_box({-w - t, -t, -d - t}, {w + t, h + t, -d}), "back_wall", accent_m);
  // The window wall in four pieces around the opening; the pieces below and above it
  // reach 1 cm into the ones beside it.
  add(make_box({-w - t, -t, d}, {kWindowX0, h + t, d + t}), "window_wall_left", wall_m);
  add(make_box({kWindowX1, -t, d}, {w + t, h + t, d + t}), "window_wall_right", wall_m);
  add(make_box({kWindowX0 - 0.01f, -t, d}, {kWindowX1 + 0.01f, kSill, d + t}), "window_sill",
      wall_m);
  add(make_box({kWindowX0 - 0.01f, kLintel, d}, {kWindowX1 + 0.01f, h + t, d + t}), "window_lintel",
      wall_m);

  // Furniture: a table in the middle of the room, a tall cabinet against the left wall.
  const glm::vec3 up(0, 1, 0);
  const int wood_m = add_material(base_material({0.55f, 0.35f, 0.2f}, 0.0f, 0.5f));
  scene.materials.back().name = "table_wood";
  constexpr float kTableTop = 0.75f;
  const glm::mat4 table =
      glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, 0.0f, -0.6f}), glm::radians(8.0f), up);
  add(make_box({-0.7f, kTableTop - 0.05f, -0.45f}, {0.7f, kTableTop, 0.45f}), "table_top", wood_m,
      table);
  int leg = 0;
  for (const float x : {-0.62f, 0.57f})
    for (const float z : {-0.37f, 0.32f})
      add(make_box({x, 0.0f, z}, {x + 0.05f, kTableTop - 0.05f, z + 0.05f}),
          "table_leg_" + std::to_string(leg++), wood_m, table);
  const int cabinet_m = add_material(base_material({0.85f, 0.85f, 0.82f}, 0.0f, 0.4f));
  scene.materials.back().name = "cabinet";
  add(make_box({-w, 0.0f, -1.9f}, {-w + 0.45f, 1.8f, -0.9f}), "cabinet", cabinet_m);

  // A rough metal sphere on the floor before the table and a glass bottle on the table.
  const int metal_m = add_material(base_material({0.95f, 0.64f, 0.54f}, 1.0f, 0.35f));
  scene.materials.back().name = "copper";
  add(make_uv_sphere(0.3f, kSegments, kRings), "metal_sphere", metal_m,
      glm::translate(glm::mat4(1.0f), {-0.75f, 0.3f, -0.1f}));
  // Clear glass with a volume (KHR_materials_transmission + volume) on a closed solid of
  // revolution; it floats 1 mm above the table top, as the glass scenes' objects do: a
  // base lying in the table's plane would make which face a ray meets first a matter of
  // rounding.
  Material glass;
  glass.name = "glass";
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission = TransmissionExtension{1.0f, {}};
  glass.volume.emplace();
  glass.volume->thickness_factor = 0.2f;  // about the bottle's diameter
  glass.volume->attenuation_color = {0.75f, 0.92f, 0.85f};
  glass.volume->attenuation_distance = 0.5f;
  const int glass_m = add_material(glass);
  add(make_lathe(
          {{0.0f, 0.0f}, {0.1f, 0.0f}, {0.1f, 0.22f}, {0.04f, 0.3f}, {0.035f, 0.4f}, {0.0f, 0.4f}},
          kSegments),
      "glass_bottle", glass_m,
      table * glm::translate(glm::mat4(1.0f), {0.25f, kTableTop + 0.001f, 0.1f}));

  // The sun: steep (55 degrees above the horizon) and from a little to the +X side, so
  // that the window's light falls on the floor between the window and the table.
  const float elevation = glm::radians(55.0f), azimuth = glm::radians(15.0f);
  Light sun;
  sun.type = Light::Type::kDirectional;
  sun.name = "sun";
  sun.color = {1.0f, 0.95f, 0.88f};
  sun.intensity = 100.0f;
  sun.direction =
      glm::normalize(glm::vec3(-std::cos(elevation) * std::sin(azimuth), -std::sin(elevation),
                               -std::cos(elevation) * std::cos(azimuth)));
  scene.lights.push_back(sun);

  // By the window, looking away from it and a little down: the sunlit patch lies behind
  // and below the camera's view.
  scene.cameras.push_back(look_at_camera("inside", {-0.9f, 1.5f, 2.1f}, {0.2f, 0.8f, -2.5f}, 1.1f));
  return scene;
}

}  // namespace pbrkit::builtin
