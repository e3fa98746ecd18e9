// The built-in scenes, generated in code so every renderer (and any other glTF tool,
// through write_glb) sees exactly the same geometry, materials and camera.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/mesh_attributes.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// Sphere tessellation: 64 x 32 keeps the silhouette smooth at 512 px.
constexpr int kSegments = 64;
constexpr int kRings = 32;

Camera look_at_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov) {
  Camera camera;
  camera.name = name;
  camera.type = Camera::Type::kPerspective;
  camera.yfov = yfov;
  camera.aspect_ratio = 1.0f;
  camera.znear = 0.05f;
  camera.camera_to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return camera;
}

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

Material diffuse(const std::string& name, glm::vec3 color) {
  Material m;
  m.name = name;
  m.base_color_factor = glm::vec4(color, 1.0f);
  m.metallic_factor = 0.0f;
  m.roughness_factor = 1.0f;
  return m;
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

// The KHR_materials_* comparison scenes, in the spirit of Khronos' Compare* sample models:
// rows of spheres (radius 0.45, spacing 1, the first row on top) in the XY plane centred
// on the origin, each row starting with a control sphere without the extension and then
// sweeping one parameter. Three rows of six keep the spheres large in a square image and
// the geometry light (48 x 24 segments, about 40k triangles in all).
constexpr int kSweepSegments = 48;
constexpr int kSweepRings = 24;
constexpr float kSweepRadius = 0.45f;

struct SphereRow {
  std::string name;  // material names are "<name>_<column>"
  std::vector<Material> spheres;
};

Scene make_sphere_rows(const std::string& name, const std::vector<SphereRow>& rows) {
  Scene scene;
  scene.source = "builtin:" + name;
  const Mesh sphere = make_uv_sphere(kSweepRadius, kSweepSegments, kSweepRings);
  std::size_t columns = 0;
  for (const SphereRow& row : rows) columns = std::max(columns, row.spheres.size());
  const float half_width = 0.5f * float(columns - 1) + kSweepRadius;
  const float half_height = 0.5f * float(rows.size() - 1) + kSweepRadius;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < rows[r].spheres.size(); ++c) {
      Material m = rows[r].spheres[c];
      m.name = rows[r].name + "_" + std::to_string(c);
      scene.materials.push_back(m);
      const glm::vec3 centre(float(c) - 0.5f * float(columns - 1),
                             0.5f * float(rows.size() - 1) - float(r), 0.0f);
      add_mesh_instance(scene, sphere, int(scene.materials.size()) - 1,
                        glm::translate(glm::mat4(1.0f), centre));
    }
  }
  // The nearest sphere surfaces are kSweepRadius in front of the plane; frame the larger
  // half extent with a 5% margin in a square image (yfov 0.6).
  const float yfov = 0.6f;
  const float half = 1.05f * std::max(half_width, half_height);
  const float distance = half / std::tan(0.5f * yfov) + kSweepRadius;
  scene.cameras.push_back(look_at_camera("front", {0, 0, distance}, {0, 0, 0}, yfov));
  return scene;
}

Material base_material(glm::vec3 color, float metallic, float roughness) {
  Material m;
  m.base_color_factor = glm::vec4(color, 1.0f);
  m.metallic_factor = metallic;
  m.roughness_factor = roughness;
  return m;
}

// A row: the control sphere `base`, then `base` with `set(material, t)` applied for each t.
SphereRow sweep(const std::string& name, const Material& base, std::initializer_list<float> ts,
                const std::function<void(Material&, float)>& set) {
  SphereRow row{name, {base}};
  for (const float t : ts) {
    Material m = base;
    set(m, t);
    row.spheres.push_back(m);
  }
  return row;
}

constexpr std::initializer_list<float> kUnitSweep = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};

// KHR_materials_clearcoat over a red rough dielectric: the coat's factor (smooth coat),
// its roughness (full coat), and the factor again over a rough gold metal.
Scene make_clearcoat() {
  const Material red = base_material({0.8f, 0.05f, 0.05f}, 0.0f, 0.6f);
  const Material gold = base_material({1.0f, 0.78f, 0.34f}, 1.0f, 0.5f);
  return make_sphere_rows("clearcoat",
                          {sweep("clearcoat_factor", red, kUnitSweep,
                                 [](Material& m, float t) {
                                   m.clearcoat.emplace();
                                   m.clearcoat->factor = t;
                                 }),
                           sweep("clearcoat_roughness", red, kUnitSweep,
                                 [](Material& m, float t) {
                                   m.clearcoat.emplace();
                                   m.clearcoat->factor = 1.0f;
                                   m.clearcoat->roughness_factor = t;
                                 }),
                           sweep("clearcoat_metal", gold, kUnitSweep, [](Material& m, float t) {
                             m.clearcoat.emplace();
                             m.clearcoat->factor = t;
                           })});
}

// KHR_materials_sheen over a dark rough dielectric: white sheen of rising intensity
// (roughness 0.5), the sheen roughness (white sheen), and sheen colours (roughness 0.5).
Scene make_sheen() {
  const Material dark = base_material({0.05f, 0.05f, 0.08f}, 0.0f, 0.8f);
  const glm::vec3 colors[] = {{1.0f, 0.1f, 0.1f},
                              {1.0f, 0.6f, 0.1f},
                              {0.1f, 1.0f, 0.2f},
                              {0.1f, 0.5f, 1.0f},
                              {0.8f, 0.2f, 1.0f}};
  return make_sphere_rows("sheen", {sweep("sheen_color", dark, kUnitSweep,
                                          [](Material& m, float t) {
                                            m.sheen.emplace();
                                            m.sheen->color_factor = glm::vec3(t);
                                            m.sheen->roughness_factor = 0.5f;
                                          }),
                                    sweep("sheen_roughness", dark, kUnitSweep,
                                          [](Material& m, float t) {
                                            m.sheen.emplace();
                                            m.sheen->color_factor = glm::vec3(1.0f);
                                            m.sheen->roughness_factor = t;
                                          }),
                                    sweep("sheen_tint", dark, {0.0f, 1.0f, 2.0f, 3.0f, 4.0f},
                                          [&colors](Material& m, float t) {
                                            m.sheen.emplace();
                                            m.sheen->color_factor = colors[int(t)];
                                            m.sheen->roughness_factor = 0.5f;
                                          })});
}

// KHR_materials_anisotropy on a rough-ish silver metal (the spheres' tangents follow the
// parallels): strength along the tangent, strength along the bitangent (rotation pi/2),
// and the rotation at full strength.
Scene make_anisotropy() {
  const Material silver = base_material({0.95f, 0.93f, 0.88f}, 1.0f, 0.3f);
  constexpr float kPi = 3.14159265358979f;
  return make_sphere_rows(
      "anisotropy", {sweep("anisotropy_strength", silver, kUnitSweep,
                           [](Material& m, float t) {
                             m.anisotropy.emplace();
                             m.anisotropy->strength = t;
                           }),
                     sweep("anisotropy_strength_rotated", silver, kUnitSweep,
                           [](Material& m, float t) {
                             m.anisotropy.emplace();
                             m.anisotropy->strength = t;
                             m.anisotropy->rotation = 0.5f * kPi;
                           }),
                     sweep("anisotropy_rotation", silver, kUnitSweep, [](Material& m, float t) {
                       m.anisotropy.emplace();
                       m.anisotropy->strength = 1.0f;
                       m.anisotropy->rotation = t * kPi;
                     })});
}

// KHR_materials_iridescence: the factor over a dark glossy dielectric, the film thickness
// (no thickness texture: the maximum is used) at full factor, and the factor over a metal.
Scene make_iridescence() {
  const Material dark = base_material({0.02f, 0.02f, 0.02f}, 0.0f, 0.2f);
  const Material steel = base_material({0.6f, 0.6f, 0.62f}, 1.0f, 0.2f);
  return make_sphere_rows(
      "iridescence", {sweep("iridescence_factor", dark, kUnitSweep,
                            [](Material& m, float t) {
                              m.iridescence.emplace();
                              m.iridescence->factor = t;
                            }),
                      sweep("iridescence_thickness", dark, {200.0f, 300.0f, 400.0f, 600.0f, 800.0f},
                            [](Material& m, float t) {
                              m.iridescence.emplace();
                              m.iridescence->factor = 1.0f;
                              m.iridescence->thickness_max = t;
                            }),
                      sweep("iridescence_metal", steel, kUnitSweep, [](Material& m, float t) {
                        m.iridescence.emplace();
                        m.iridescence->factor = t;
                      })});
}

// KHR_materials_specular over a dark blue glossy dielectric: specularFactor, a white
// specularColorFactor from 0 to 2 (it may exceed 1), and coloured F0 tints.
Scene make_specular() {
  const Material blue = base_material({0.03f, 0.06f, 0.25f}, 0.0f, 0.3f);
  const glm::vec3 tints[] = {{1.0f, 0.2f, 0.2f},
                             {1.0f, 0.8f, 0.2f},
                             {0.2f, 1.0f, 0.2f},
                             {0.2f, 0.8f, 1.0f},
                             {1.0f, 0.2f, 1.0f}};
  return make_sphere_rows("specular", {sweep("specular_factor", blue, kUnitSweep,
                                             [](Material& m, float t) {
                                               m.specular.emplace();
                                               m.specular->factor = t;
                                             }),
                                       sweep("specular_color", blue, {0.0f, 0.5f, 1.0f, 1.5f, 2.0f},
                                             [](Material& m, float t) {
                                               m.specular.emplace();
                                               m.specular->color_factor = glm::vec3(t);
                                             }),
                                       sweep("specular_tint", blue, {0.0f, 1.0f, 2.0f, 3.0f, 4.0f},
                                             [&tints](Material& m, float t) {
                                               m.specular.emplace();
                                               m.specular->color_factor = tints[int(t)];
                                             })});
}

// KHR_materials_ior from 1 (no dielectric reflection) to 2.5 over a dark dielectric at
// three base roughnesses; the control is the default 1.5.
Scene make_ior() {
  std::vector<SphereRow> rows;
  for (const float roughness : {0.05f, 0.3f, 0.6f})
    rows.push_back(sweep("ior_roughness" + std::to_string(int(std::lround(roughness * 100))),
                         base_material({0.05f, 0.08f, 0.12f}, 0.0f, roughness),
                         {1.0f, 1.2f, 1.33f, 2.0f, 2.5f}, [](Material& m, float t) { m.ior = t; }));
  return make_sphere_rows("ior", rows);
}

// KHR_materials_unlit: pairs of a lit (rough dielectric) sphere and an unlit one of the
// same base colour, in three rows of colours.
Scene make_unlit() {
  const glm::vec3 colors[3][3] = {
      {{0.8f, 0.1f, 0.1f}, {0.1f, 0.7f, 0.1f}, {0.1f, 0.2f, 0.8f}},
      {{0.1f, 0.7f, 0.7f}, {0.7f, 0.1f, 0.7f}, {0.8f, 0.7f, 0.1f}},
      {{0.9f, 0.9f, 0.9f}, {0.18f, 0.18f, 0.18f}, {0.02f, 0.02f, 0.02f}}};
  std::vector<SphereRow> rows;
  for (int r = 0; r < 3; ++r) {
    SphereRow row{"unlit_row" + std::to_string(r), {}};
    for (const glm::vec3& color : colors[r]) {
      Material lit = base_material(color, 0.0f, 0.7f);
      row.spheres.push_back(lit);
      lit.unlit = true;
      row.spheres.push_back(lit);
    }
    rows.push_back(row);
  }
  return make_sphere_rows("unlit", rows);
}

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

// A rock: a coarse sphere (12 x 6 segments) pushed in and out by a smooth function of
// the direction, flattened, flat-shaded, resting on y = 0. Made once; every rock of the
// `instances` field draws this one mesh.
Mesh make_rock() {
  Mesh rock = make_uv_sphere(1.0f, 12, 6);
  rock.name = "rock";
  float lowest = 0.0f;
  for (glm::vec3& p : rock.positions) {
    // Equal positions (the seam, the poles) move equally: the rock stays closed.
    const float bump = 0.22f * std::sin(2.7f * p.x + 0.4f) * std::cos(3.1f * p.y + 1.3f) +
                       0.12f * std::sin(5.3f * p.z + 2.1f) * std::sin(4.1f * p.x);
    p *= 0.3f * (1.0f + bump);
    p.y *= 0.65f;
    lowest = std::min(lowest, p.y);
  }
  for (glm::vec3& p : rock.positions) p.y -= lowest;
  rock.normals.clear();
  rock.tangents.clear();
  rock.texcoords0.clear();
  generate_flat_normals(rock);
  return rock;
}

// A hash of an integer to [0, 1) (the low bits of a multiplicative hash), so that the
// field's variation is the same on every platform.
float hash01(std::uint32_t i, std::uint32_t salt) {
  std::uint32_t h = (i + 0x9e3779b9u * salt) * 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return float(h >> 8) / 16777216.0f;
}

// instances: a 100 x 100 field of one rock (spacing 0.6, each turned about +Y, jittered
// and scaled 0.6 to 1.2 at random) on a diffuse ground, seen from above one corner. Every
// 211th rock is mirrored (a negative x scale: its winding flips), every 173rd squashed
// non-uniformly (1.9, 0.45, 1), and the one nearest the centre glows (its own mesh, an
// emissive copy of the rock). 10,000 instances of one 120-triangle mesh: 1.2 M instanced
// triangles, 120 unique.
Scene make_instances() {
  Scene scene;
  scene.source = "builtin:instances";
  scene.materials.push_back(diffuse("ground", {0.35f, 0.33f, 0.3f}));
  Material stone = diffuse("rock", {0.55f, 0.5f, 0.45f});
  stone.roughness_factor = 0.8f;
  scene.materials.push_back(stone);
  Material glow = stone;
  glow.name = "glowing_rock";
  glow.emissive_factor = glm::vec3(1.0f, 0.55f, 0.2f);
  glow.emissive_strength = 6.0f;
  scene.materials.push_back(glow);

  constexpr int kSide = 100;
  constexpr float kSpacing = 0.6f;
  const float half = 0.5f * kSpacing * float(kSide);
  Mesh ground = make_quad({-half - 1.0f, 0.0f, half + 1.0f}, {2.0f * half + 2.0f, 0.0f, 0.0f},
                          {0.0f, 0.0f, -2.0f * half - 2.0f});
  ground.name = "ground";
  add_mesh_instance(scene, std::move(ground), 0);
  Mesh rock = make_rock();
  rock.material = 1;
  scene.meshes.push_back(rock);
  const int rock_mesh = int(scene.meshes.size()) - 1;
  rock.name = "glowing_rock";
  rock.material = 2;
  scene.meshes.push_back(std::move(rock));
  const int glow_mesh = int(scene.meshes.size()) - 1;

  glm::mat4 glowing(1.0f);
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) {
      const auto i = std::uint32_t(row * kSide + col);
      const glm::vec3 jitter(hash01(i, 1) - 0.5f, 0.0f, hash01(i, 2) - 0.5f);
      const glm::vec3 at = glm::vec3(float(col) + 0.5f - 0.5f * float(kSide), 0.0f,
                                     float(row) + 0.5f - 0.5f * float(kSide)) *
                               kSpacing +
                           0.3f * kSpacing * jitter;
      const float size = 0.6f + 0.6f * hash01(i, 3);
      glm::vec3 scale(size);
      if (i % 211 == 7) scale.x = -scale.x;                      // mirrored
      if (i % 173 == 11) scale *= glm::vec3(1.9f, 0.45f, 1.0f);  // squashed
      glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
      m = glm::rotate(m, 6.2831853f * hash01(i, 4), glm::vec3(0, 1, 0));
      m = glm::scale(m, scale);
      if (row == kSide / 2 && col == kSide / 2)
        glowing = m;
      else
        scene.instances.push_back({rock_mesh, m, -1});
    }
  scene.instances.push_back({glow_mesh, glowing, -1});
  // From above the near edge, looking across the field towards its centre.
  scene.cameras.push_back(look_at_camera("front", {0.0f, 7.0f, 24.0f}, {0.0f, 0.0f, 2.0f}, 0.6f));
  return scene;
}

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

}  // namespace

std::vector<std::string> builtin_scene_names() {
  return {"spheres",  "furnace", "cornell", "clearcoat", "sheen",  "anisotropy", "iridescence",
          "specular", "ior",     "unlit",   "glass",     "liquid", "instances",  "lights"};
}

bool is_builtin_scene(const std::string& name) {
  const auto names = builtin_scene_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene builtin_scene(const std::string& name) {
  if (name == "spheres") return make_spheres();
  if (name == "furnace") return make_furnace();
  if (name == "cornell") return make_cornell();
  if (name == "clearcoat") return make_clearcoat();
  if (name == "sheen") return make_sheen();
  if (name == "anisotropy") return make_anisotropy();
  if (name == "iridescence") return make_iridescence();
  if (name == "specular") return make_specular();
  if (name == "ior") return make_ior();
  if (name == "unlit") return make_unlit();
  if (name == "glass") return make_glass();
  if (name == "liquid") return make_liquid();
  if (name == "instances") return make_instances();
  if (name == "lights") return make_lights();
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += (known.empty() ? "" : ", ") + n;
  fail("unknown built-in scene '{}' (known: {})", name, known);
}

}  // namespace pbrkit
