// The KHR_materials_* comparison scenes: rows of spheres sweeping one parameter of an
// extension each.
#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

namespace {

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

}  // namespace

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

}  // namespace pbrkit::builtin
