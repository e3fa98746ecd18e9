// The transmission scenes: glass objects and a filled tumbler before a checker backdrop.
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

namespace {

// The transmission scenes (KHR_materials_transmission, volume, dispersion): objects on a
// checker floor in front of a checker wall, so that what refraction bends, blurs, tints or
// splits is visible through them. Lit like the other extension scenes, by the environment
// only (the wall hides the part behind it).

// A diffuse floor (y = 0, z from `back` towards the camera) and wall (z = `back`), each
// `size` square, with a `checks` x `checks` checker of 0.8 / 0.05 grey (linear).
void add_backdrop(Scene& scene, float back, float size, int checks) {
  scene.textures.push_back(
      make_checker_texture(32 * checks, checks, glm::vec3(0.8f), glm::vec3(0.05f)));
  Material m = diffuse("backdrop", glm::vec3(1.0f));
  m.base_color_texture.texture = int(scene.textures.size()) - 1;
  scene.materials.push_back(m);
  const int material = int(scene.materials.size()) - 1;
  const float h = 0.5f * size;
  Mesh floor = make_quad({-h, 0.0f, back + size}, {size, 0, 0}, {0, 0, -size});
  floor.name = "floor";
  add_mesh_instance(scene, std::move(floor), material);
  Mesh wall = make_quad({-h, 0.0f, back}, {size, 0, 0}, {0, size, 0});
  wall.name = "wall";
  add_mesh_instance(scene, std::move(wall), material);
}

// Clear glass (KHR_materials_transmission 1, ior 1.5, no absorption); `thickness` > 0
// makes it a volume boundary (KHR_materials_volume), 0 a thin wall.
Material glass(const std::string& name, float roughness, float thickness) {
  Material m;
  m.name = name;
  m.metallic_factor = 0.0f;
  m.roughness_factor = roughness;
  m.transmission = TransmissionExtension{1.0f, {}};
  if (thickness > 0.0f) {
    m.volume.emplace();
    m.volume->thickness_factor = thickness;
  }
  return m;
}

// How far the glass and liquid scenes' objects float above the floor (an air gap, as under
// a real glass on a table, where optical contact is rare). A flat base lying in the floor's
// plane would make the floor and the base coincident surfaces: which of the two a ray
// meets first would then depend on rounding (Embree's AVX2 and AVX-512 triangle tests
// choose differently, and the liquid scene's path-traced image moved by up to 5% per tile
// between them), and a path leaving the glass through its base could be shaded as if it
// had hit the floor from inside the glass. The gap is about 60 times the ray offsets
// (pt/ray_offset.h) and a fraction of a pixel at the built-in cameras.
constexpr float kRestingGap = 0.001f;

}  // namespace

// glass: five objects on the floor. At the back, left to right: a smooth glass sphere, a
// rough one (roughness 0.35) and a prism of dense flint-like glass (ior 1.65, dispersion
// 1: Abbe number 20) with an edge towards the camera; in front, between them: a
// green-tinted block (absorption: attenuationColor (0.25, 0.7, 0.4) at 0.3, so its colour
// deepens with the path length) and a thin-walled pale-blue sheet (no volume: no
// refraction, only the base-colour tint).
Scene make_glass() {
  Scene scene;
  scene.source = "builtin:glass";
  add_backdrop(scene, -1.5f, 8.0f, 16);
  constexpr float kRadius = 0.42f;
  const Mesh sphere = make_uv_sphere(kRadius, kSegments, kRings);
  constexpr float kBack = -0.5f, kFront = 0.9f;
  auto at = [](float x, float z, float degrees = 0.0f) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), {x, kRestingGap, z}), glm::radians(degrees),
                       glm::vec3(0, 1, 0));
  };

  scene.materials.push_back(glass("glass_smooth", 0.0f, 2.0f * kRadius));
  Mesh smooth = sphere;
  smooth.name = "sphere_smooth";
  add_mesh_instance(scene, std::move(smooth), int(scene.materials.size()) - 1,
                    glm::translate(at(-1.6f, kBack), {0.0f, kRadius, 0.0f}));

  scene.materials.push_back(glass("glass_rough", 0.35f, 2.0f * kRadius));
  Mesh rough = sphere;
  rough.name = "sphere_rough";
  add_mesh_instance(scene, std::move(rough), int(scene.materials.size()) - 1,
                    glm::translate(at(0.0f, kBack), {0.0f, kRadius, 0.0f}));

  Material tinted = glass("glass_tinted", 0.0f, 0.7f);
  tinted.volume->attenuation_color = {0.25f, 0.7f, 0.4f};
  tinted.volume->attenuation_distance = 0.3f;
  scene.materials.push_back(tinted);
  Mesh block = make_box({-0.35f, 0.0f, -0.35f}, {0.35f, 0.7f, 0.35f});
  block.name = "block_tinted";
  add_mesh_instance(scene, std::move(block), int(scene.materials.size()) - 1,
                    at(-0.8f, kFront, 30.0f));

  Material sheet = glass("glass_sheet", 0.05f, 0.0f);
  sheet.base_color_factor = {0.75f, 0.88f, 1.0f, 1.0f};
  sheet.double_sided = true;  // a thin wall is seen from both sides
  scene.materials.push_back(sheet);
  Mesh quad = make_quad({-0.4f, 0.0f, 0.0f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.9f, 0.0f});
  quad.name = "sheet_thin";
  add_mesh_instance(scene, std::move(quad), int(scene.materials.size()) - 1,
                    at(0.8f, kFront, -25.0f));

  Material flint = glass("glass_dispersive", 0.0f, 0.7f);
  flint.ior = 1.65f;
  flint.dispersion = DispersionExtension{1.0f};
  scene.materials.push_back(flint);
  // An equilateral triangle of side 0.8 around the origin, one corner towards +Z.
  std::vector<glm::vec2> triangle;
  for (int k = 0; k < 3; ++k) {
    const float a = glm::radians(120.0f * float(k));
    triangle.push_back(0.8f / std::sqrt(3.0f) * glm::vec2(std::sin(a), std::cos(a)));
  }
  Mesh prism = make_prism(triangle, 0.9f);
  prism.name = "prism_dispersive";
  add_mesh_instance(scene, std::move(prism), int(scene.materials.size()) - 1, at(1.6f, kBack));

  // From above, so the front row sits below the back one: tan(0.4) * 5.5 = 2.3 > 2.02, the
  // back row's half width at its distance.
  scene.cameras.push_back(look_at_camera("front", {0.0f, 2.1f, 4.9f}, {0.0f, 0.35f, 0.0f}, 0.8f));
  return scene;
}

// liquid: two tumblers on the floor, the left one filled with an amber liquid (ior 1.33,
// attenuationColor (0.95, 0.55, 0.15) at 0.25), the right one empty. The glass is a closed
// shell (outer radius 0.32, wall 0.025, base 0.08, height 0.95) and the liquid a closed
// cylinder up to y = 0.62. Where they meet, the liquid reaches 0.002 (8% of the wall) into
// the glass instead of touching it: coincident surfaces make the order of the two hits
// depend on rounding, and a gap would put an air layer (two extra interfaces, total
// internal reflection) between them. With the overlap a ray leaving the glass is already
// inside the liquid, so a renderer that tracks the media it is in (nested dielectrics,
// Schmidt and Budge 2002) sees one glass/liquid interface, 0.002 away from the true one.
Scene make_liquid() {
  Scene scene;
  scene.source = "builtin:liquid";
  add_backdrop(scene, -1.0f, 5.0f, 16);
  constexpr float kOuter = 0.32f, kWall = 0.025f, kBase = 0.08f, kHeight = 0.95f;
  constexpr float kOverlap = 0.002f, kLevel = 0.62f;
  const float inner = kOuter - kWall;
  // Out along the bottom, up the outside, across the rim, down the inside, in along the
  // inner bottom (make_lathe: outward faces).
  const Mesh tumbler = make_lathe({{0.0f, 0.0f},
                                   {kOuter, 0.0f},
                                   {kOuter, kHeight},
                                   {inner, kHeight},
                                   {inner, kBase},
                                   {0.0f, kBase}},
                                  kSegments);
  scene.materials.push_back(glass("tumbler_glass", 0.0f, kWall));
  const int glass_material = int(scene.materials.size()) - 1;
  Material amber = glass("liquid", 0.0f, 2.0f * inner);
  amber.ior = 1.33f;
  amber.volume->attenuation_color = {0.95f, 0.55f, 0.15f};
  amber.volume->attenuation_distance = 0.25f;
  scene.materials.push_back(amber);
  const int liquid_material = int(scene.materials.size()) - 1;

  const glm::mat4 left = glm::translate(glm::mat4(1.0f), {-0.42f, kRestingGap, 0.0f});
  const glm::mat4 right = glm::translate(glm::mat4(1.0f), {0.42f, kRestingGap, 0.0f});
  Mesh filled = tumbler;
  filled.name = "tumbler_filled";
  add_mesh_instance(scene, std::move(filled), glass_material, left);
  Mesh liquid = make_lathe({{0.0f, kBase - kOverlap},
                            {inner + kOverlap, kBase - kOverlap},
                            {inner + kOverlap, kLevel},
                            {0.0f, kLevel}},
                           kSegments);
  liquid.name = "liquid";
  add_mesh_instance(scene, std::move(liquid), liquid_material, left);
  Mesh empty = tumbler;
  empty.name = "tumbler_empty";
  add_mesh_instance(scene, std::move(empty), glass_material, right);

  // From above the rims (to see the liquid's surface): tan(0.3) * 3.1 = 0.96 > 0.74, the
  // pair's half width.
  scene.cameras.push_back(look_at_camera("front", {0.0f, 1.5f, 2.85f}, {0.0f, 0.42f, 0.0f}, 0.6f));
  return scene;
}

}  // namespace pbrkit::builtin
