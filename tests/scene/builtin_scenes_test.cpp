// The built-in scenes: layouts and materials as documented, cameras that frame them, and
// the Scene helpers on known geometry.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/coincident_faces.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/mesh_closure.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

glm::vec2 project(const Camera& camera, glm::vec3 p) {
  const glm::vec4 clip = projection_matrix(camera, 1.0f) * view_matrix(camera) * glm::vec4(p, 1);
  return glm::vec2(clip) / clip.w;
}

TEST(BuiltinScenes, SpheresGrid) {
  const Scene s = load_scene("spheres");
  EXPECT_EQ(s.source, "builtin:spheres");
  ASSERT_EQ(s.instances.size(), 49u);
  for (const Instance& inst : s.instances) {
    const glm::vec3 c(inst.transform[3]);
    const Material& m = s.material_of(s.meshes[std::size_t(inst.mesh)]);
    const float row = c.y + 3.0f, col = c.x + 3.0f;
    EXPECT_NEAR(m.metallic_factor, row / 6.0f, 1e-6f);
    EXPECT_NEAR(m.roughness_factor, 0.05f + 0.95f * col / 6.0f, 1e-6f);
    EXPECT_EQ(m.base_color_factor, glm::vec4(0.9f, 0.6f, 0.3f, 1.0f));
    EXPECT_FLOAT_EQ(c.z, 0.0f);
  }
  const Bounds b = s.world_bounds();
  EXPECT_NEAR(b.min.x, -3.4f, 1e-4f);
  EXPECT_NEAR(b.max.y, 3.4f, 1e-4f);
  EXPECT_NEAR(b.max.z, 0.4f, 1e-4f);
  // The camera on +Z sees every sphere completely.
  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& cam = s.cameras[0];
  EXPECT_GT(cam.position().z, 5.0f);
  for (float x : {b.min.x, b.max.x})
    for (float y : {b.min.y, b.max.y}) {
      const glm::vec2 ndc = project(cam, {x, y, 0.0f});
      EXPECT_LT(std::abs(ndc.x), 1.0f);
      EXPECT_LT(std::abs(ndc.y), 1.0f);
    }
  // 64 x 32 sphere: 2 * 64 * (32 - 1) triangles (no degenerate pole triangles).
  EXPECT_EQ(s.triangle_count(), 49u * 2u * 64u * 31u);
}

TEST(BuiltinScenes, Furnace) {
  const Scene s = load_scene("builtin:furnace");
  ASSERT_EQ(s.instances.size(), 1u);
  const Material& m = s.material_of(s.meshes[0]);
  EXPECT_EQ(m.base_color_factor, glm::vec4(1.0f));
  EXPECT_EQ(m.metallic_factor, 0.0f);
  const Bounds b = s.world_bounds();
  EXPECT_NEAR(b.max.x, 1.0f, 1e-5f);
  EXPECT_NEAR(b.min.y, -1.0f, 1e-5f);
  const glm::vec2 edge = project(s.cameras.at(0), {1.0f, 0.0f, 0.0f});
  EXPECT_LT(edge.x, 1.0f);
  EXPECT_GT(edge.x, 0.3f);
}

TEST(BuiltinScenes, CornellBox) {
  const Scene s = load_scene("cornell");
  int emissive = 0;
  for (const Mesh& mesh : s.meshes) {
    const Material& m = s.material_of(mesh);
    if (m.emissive_factor != glm::vec3(0.0f)) {
      ++emissive;
      EXPECT_EQ(m.emissive_factor, glm::vec3(1.0f, 0.85f, 0.6f));
      EXPECT_FLOAT_EQ(m.emissive_strength, 15.0f);
      // The light faces down, just below the ceiling.
      for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(n.y, -1.0f, 1e-6f);
      for (const glm::vec3& p : mesh.positions) EXPECT_NEAR(p.y, 1.98f, 1e-6f);
    }
    if (mesh.name == "left") {
      EXPECT_GT(m.base_color_factor.r, 0.5f);
      EXPECT_LT(m.base_color_factor.g, 0.1f);
      EXPECT_NEAR(mesh.normals[0].x, 1.0f, 1e-6f);  // faces into the room
    }
    if (mesh.name == "right") {
      EXPECT_GT(m.base_color_factor.g, m.base_color_factor.r);
      EXPECT_NEAR(mesh.normals[0].x, -1.0f, 1e-6f);
    }
    if (mesh.name == "floor") {
      EXPECT_NEAR(mesh.normals[0].y, 1.0f, 1e-6f);
    }
  }
  EXPECT_EQ(emissive, 1);
  const Bounds b = s.world_bounds();
  EXPECT_NEAR(b.min.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.max.y, 2.0f, 1e-6f);
  // The camera looks in through the open front (+Z) and sees the back wall's corners.
  const Camera& cam = s.cameras.at(0);
  EXPECT_GT(cam.position().z, 1.0f);
  const glm::vec2 corner = project(cam, {-1.0f, 2.0f, -1.0f});
  EXPECT_LT(std::abs(corner.x), 1.0f);
  EXPECT_LT(std::abs(corner.y), 1.0f);
}

// The KHR_materials comparison scenes: 3 rows of 6 spheres; the first sphere of each row
// has no extension (the control), the others all use the scene's extension.
struct Sphere {
  glm::vec3 centre;
  const Mesh* mesh;
  const Material* material;
};
std::vector<std::vector<Sphere>> sphere_rows(const Scene& s) {
  std::vector<std::vector<Sphere>> rows(3);
  for (const Instance& inst : s.instances) {
    const glm::vec3 c(inst.transform[3]);
    const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
    const int row = int(std::lround(1.0f - c.y));  // the first row on top (y = 1)
    EXPECT_TRUE(row >= 0 && row < 3) << c.y;
    if (row >= 0 && row < 3) rows[std::size_t(row)].push_back({c, &mesh, &s.material_of(mesh)});
  }
  for (auto& row : rows)
    std::sort(row.begin(), row.end(),
              [](const Sphere& a, const Sphere& b) { return a.centre.x < b.centre.x; });
  return rows;
}
std::vector<std::vector<Sphere>> sphere_rows(Scene&&) = delete;  // the rows point into it

bool uses(const Material& m, const std::string& extension) {
  if (extension == "clearcoat") return m.clearcoat.has_value();
  if (extension == "sheen") return m.sheen.has_value();
  if (extension == "anisotropy") return m.anisotropy.has_value();
  if (extension == "iridescence") return m.iridescence.has_value();
  if (extension == "specular") return m.specular.has_value();
  if (extension == "ior") return m.ior != 1.5f;
  return m.unlit;
}

TEST(BuiltinScenes, ExtensionScenesHaveAControlThenASweepAndAreFramed) {
  for (const char* name :
       {"clearcoat", "sheen", "anisotropy", "iridescence", "specular", "ior", "unlit"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(is_builtin_scene(name));
    const Scene s = load_scene(name);
    EXPECT_EQ(s.source, std::string("builtin:") + name);
    ASSERT_EQ(s.instances.size(), 18u);
    const auto rows = sphere_rows(s);
    for (const auto& row : rows) {
      ASSERT_EQ(row.size(), 6u);
      for (std::size_t c = 0; c < row.size(); ++c) {
        EXPECT_NEAR(row[c].centre.x, float(c) - 2.5f, 1e-6f);
        // unlit alternates lit controls and unlit spheres; the others start with the control.
        const bool expected = std::string(name) == "unlit" ? c % 2 == 1 : c > 0;
        EXPECT_EQ(uses(*row[c].material, name), expected) << row[c].material->name;
        // Tangents (anisotropy needs them) along the sphere's parallels.
        ASSERT_EQ(row[c].mesh->tangents.size(), row[c].mesh->positions.size());
      }
      // Within a row the spheres differ (a sweep), except unlit's lit/unlit pairs.
      if (std::string(name) != "unlit") {
        for (std::size_t c = 2; c < row.size(); ++c)
          EXPECT_NE(row[c].material->name, row[c - 1].material->name);
      }
    }
    // Light geometry: 48 x 24 spheres.
    EXPECT_EQ(s.triangle_count(), 18u * 2u * 48u * 23u);
    // The camera sees every sphere completely.
    const Bounds b = s.world_bounds();
    ASSERT_EQ(s.cameras.size(), 1u);
    for (float x : {b.min.x, b.max.x})
      for (float y : {b.min.y, b.max.y}) {
        const glm::vec2 ndc = project(s.cameras[0], {x, y, 0.0f});
        EXPECT_LT(std::abs(ndc.x), 1.0f);
        EXPECT_LT(std::abs(ndc.y), 1.0f);
        EXPECT_GT(std::abs(ndc.x), 0.7f);  // and fills the frame's width
      }
  }
}

TEST(BuiltinScenes, ExtensionSweepsCoverTheirRanges) {
  {
    const Scene s = load_scene("clearcoat");
    const auto rows = sphere_rows(s);
    EXPECT_EQ(rows[0][1].material->clearcoat->factor, 0.0f);
    EXPECT_EQ(rows[0][5].material->clearcoat->factor, 1.0f);
    EXPECT_EQ(rows[1][5].material->clearcoat->roughness_factor, 1.0f);
    EXPECT_EQ(rows[1][5].material->clearcoat->factor, 1.0f);
    EXPECT_EQ(rows[2][0].material->metallic_factor, 1.0f);  // the coat over a metal
  }
  {
    const Scene s = load_scene("sheen");
    const auto rows = sphere_rows(s);
    EXPECT_EQ(rows[0][5].material->sheen->color_factor, glm::vec3(1.0f));
    EXPECT_EQ(rows[1][1].material->sheen->roughness_factor, 0.0f);
    EXPECT_EQ(rows[1][5].material->sheen->roughness_factor, 1.0f);
    EXPECT_LT(rows[0][0].material->base_color_factor.r, 0.1f);  // a dark base
  }
  {
    const Scene s = load_scene("anisotropy");
    const auto rows = sphere_rows(s);
    EXPECT_EQ(rows[0][5].material->anisotropy->strength, 1.0f);
    EXPECT_NEAR(rows[1][3].material->anisotropy->rotation, 1.5707963f, 1e-6f);
    EXPECT_NEAR(rows[2][5].material->anisotropy->rotation, 3.1415927f, 1e-6f);
    EXPECT_EQ(rows[0][0].material->metallic_factor, 1.0f);
  }
  {
    const Scene s = load_scene("iridescence");
    const auto rows = sphere_rows(s);
    EXPECT_EQ(rows[0][5].material->iridescence->factor, 1.0f);
    EXPECT_EQ(rows[1][1].material->iridescence->thickness_max, 200.0f);
    EXPECT_EQ(rows[1][5].material->iridescence->thickness_max, 800.0f);
  }
  {
    const Scene s = load_scene("specular");
    const auto rows = sphere_rows(s);
    EXPECT_EQ(rows[0][1].material->specular->factor, 0.0f);
    EXPECT_EQ(rows[1][5].material->specular->color_factor, glm::vec3(2.0f));  // above 1
  }
  {
    const Scene s = load_scene("ior");
    const auto rows = sphere_rows(s);
    for (const auto& row : rows) {
      EXPECT_EQ(row[0].material->ior, 1.5f);  // the control: no extension
      EXPECT_EQ(row[1].material->ior, 1.0f);  // exactly 1: no dielectric reflection
      EXPECT_EQ(row[5].material->ior, 2.5f);
    }
  }
  {
    const Scene s = load_scene("unlit");
    const auto rows = sphere_rows(s);
    for (const auto& row : rows)
      for (std::size_t c = 0; c < 6; c += 2)
        EXPECT_EQ(row[c].material->base_color_factor, row[c + 1].material->base_color_factor);
  }
}

const Material& named(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

// Every mesh whose material is a volume boundary closes its volume (recounted here: the
// Mesh::closed default is true too), and the camera sees every non-backdrop mesh whole,
// in front of the wall (the backdrop's material is "backdrop").
void expect_closed_volumes_framed_before_the_backdrop(const Scene& s) {
  const Camera& cam = s.cameras.at(0);
  float wall_z = 1e9f;
  for (const Mesh& mesh : s.meshes)
    if (mesh.name == "wall") wall_z = mesh.positions[0].z;
  ASSERT_LT(wall_z, 0.0f);
  for (const Instance& inst : s.instances) {
    const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
    const Material& m = s.material_of(mesh);
    SCOPED_TRACE(mesh.name);
    if (m.volume && m.volume->thickness_factor > 0.0f) {
      EXPECT_TRUE(mesh.closed);
      EXPECT_TRUE(count_edges(mesh).closed());
      EXPECT_FALSE(m.double_sided);  // glTF-Validator: KHR_MATERIALS_VOLUME_DOUBLE_SIDED
    }
    if (m.name == "backdrop") continue;
    EXPECT_TRUE(m.transmission.has_value());
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec3 w(inst.transform * glm::vec4(p, 1.0f));
      EXPECT_GT(w.z, wall_z);
      EXPECT_GE(w.y, -1e-6f);  // on or above the floor
      const glm::vec2 ndc = project(cam, w);
      ASSERT_LT(std::abs(ndc.x), 1.0f) << w.x << " " << w.y << " " << w.z;
      ASSERT_LT(std::abs(ndc.y), 1.0f) << w.x << " " << w.y << " " << w.z;
    }
  }
  // The backdrop is a checker (refraction shows as bent edges).
  const TextureRef& checker = named(s, "backdrop").base_color_texture;
  ASSERT_TRUE(checker.valid());
  const Texture& texels = s.textures[std::size_t(checker.texture)];
  EXPECT_GT(texels.texel(0, 0, 0).r, 10.0f * texels.texel(0, texels.width() - 1, 0).r);
}

TEST(BuiltinScenes, GlassHasEachKindOfGlassBeforeACheckerBackdrop) {
  const Scene s = load_scene("glass");
  EXPECT_EQ(s.source, "builtin:glass");
  EXPECT_TRUE(s.warnings.empty());
  expect_closed_volumes_framed_before_the_backdrop(s);
  const Material& smooth = named(s, "glass_smooth");
  EXPECT_EQ(smooth.roughness_factor, 0.0f);
  EXPECT_EQ(smooth.transmission->factor, 1.0f);
  EXPECT_EQ(smooth.metallic_factor, 0.0f);
  EXPECT_EQ(smooth.volume->attenuation_distance, std::numeric_limits<float>::infinity());
  EXPECT_GT(named(s, "glass_rough").roughness_factor, 0.2f);
  const Material& tinted = named(s, "glass_tinted");
  EXPECT_TRUE(std::isfinite(tinted.volume->attenuation_distance));
  EXPECT_LT(tinted.volume->attenuation_color.r, 0.5f);  // a visible tint
  const Material& sheet = named(s, "glass_sheet");
  EXPECT_FALSE(sheet.volume.has_value());  // thin-walled
  EXPECT_TRUE(sheet.double_sided);
  const Material& flint = named(s, "glass_dispersive");
  EXPECT_GE(flint.dispersion->dispersion, 0.5f);
  EXPECT_GT(flint.volume->thickness_factor, 0.0f);  // dispersion needs a volume
  EXPECT_GT(flint.ior, 1.5f);
  // The volumes' thicknessFactor is their size (what a rasteriser uses for the path length).
  for (const Mesh& mesh : s.meshes) {
    if (mesh.name.rfind("sphere", 0) == 0) {
      EXPECT_NEAR(s.material_of(mesh).volume->thickness_factor,
                  2.0f * glm::length(mesh.positions[0]), 1e-5f);
    }
  }
}

TEST(BuiltinScenes, LiquidReachesSlightlyIntoItsGlass) {
  const Scene s = load_scene("liquid");
  EXPECT_EQ(s.source, "builtin:liquid");
  EXPECT_TRUE(s.warnings.empty());
  expect_closed_volumes_framed_before_the_backdrop(s);
  const Mesh *glass = nullptr, *liquid = nullptr;
  for (const Mesh& mesh : s.meshes) {
    if (mesh.name == "tumbler_filled") glass = &mesh;
    if (mesh.name == "liquid") liquid = &mesh;
  }
  ASSERT_TRUE(glass && liquid);
  EXPECT_EQ(s.material_of(*liquid).ior, 1.33f);
  EXPECT_LT(s.material_of(*liquid).volume->attenuation_distance, 1.0f);
  // The glass's inner wall is the smaller radius at the rim; its inner floor the higher
  // vertex on the axis.
  float rim = 0.0f, liquid_radius = 0.0f, liquid_bottom = 1e9f, liquid_top = 0.0f;
  for (const glm::vec3& p : glass->positions) rim = std::max(rim, p.y);
  float outer = 0.0f, inner = 1e9f, base = 0.0f;
  for (const glm::vec3& p : glass->positions) {
    const float r = std::hypot(p.x, p.z);
    outer = std::max(outer, r);
    if (p.y == rim) inner = std::min(inner, r);
    if (r == 0.0f) base = std::max(base, p.y);  // the inner floor's centre
  }
  for (const glm::vec3& p : liquid->positions) {
    liquid_radius = std::max(liquid_radius, std::hypot(p.x, p.z));
    liquid_bottom = std::min(liquid_bottom, p.y);
    liquid_top = std::max(liquid_top, p.y);
  }
  // The documented overlap: 0.002 into the wall and into the floor, less than the wall.
  EXPECT_NEAR(liquid_radius - inner, 0.002f, 1e-5f);
  EXPECT_LT(liquid_radius, outer);
  EXPECT_NEAR(base - liquid_bottom, 0.002f, 1e-5f);
  EXPECT_LT(liquid_top, rim - 0.1f);
  // The same placement (both in the left tumbler).
  int left = 0;
  for (const Instance& inst : s.instances) {
    const std::string& name = s.meshes[std::size_t(inst.mesh)].name;
    if ((name == "liquid" || name == "tumbler_filled") && inst.transform[3].x < 0.0f) ++left;
  }
  EXPECT_EQ(left, 2);
}

TEST(BuiltinScenes, NoTransmissiveSurfaceLiesOnAnother) {
  // Where a glass's face and another object's face share a plane and an area, which of the
  // two a ray meets first is decided by rounding (it differed between Embree's AVX2 and
  // AVX-512 kernels), so the path tracer's image would be too: a ground truth must not
  // contain such a pair (scene/coincident_faces.h, tested on known cases in
  // coincident_faces_test.cpp).
  for (const std::string& name : builtin_scene_names()) {
    SCOPED_TRACE(name);
    const Scene s = load_scene(name);
    const CoincidentFacesResult r = find_coincident_faces(s);
    EXPECT_FALSE(r.incomplete);
    for (const CoincidentFaces& c : r.pairs)
      ADD_FAILURE() << s.meshes[std::size_t(s.instances[c.transmissive].mesh)].name << " lies on "
                    << s.meshes[std::size_t(s.instances[c.other].mesh)].name << " (" << c.triangles
                    << " triangles)";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  }
}

TEST(BuiltinScenes, TransmissionScenesRoundTripThroughGlb) {
  // `pbrkit scene write` (the validator runs in GltfWriter.BuiltinScenesFollowTheCameraSchema).
  for (const char* name : {"glass", "liquid"}) {
    SCOPED_TRACE(name);
    const Scene a = load_scene(name);
    const auto path = test::scratch_dir() / (std::string(name) + ".glb");
    write_glb(a, path);
    const Scene b = load_scene(path.string());
    EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
      const Material &x = a.materials[i], &y = b.materials[i];
      SCOPED_TRACE(x.name);
      EXPECT_EQ(x.ior, y.ior);
      EXPECT_EQ(x.transmission.has_value(), y.transmission.has_value());
      ASSERT_EQ(x.volume.has_value(), y.volume.has_value());
      if (x.volume) {
        EXPECT_EQ(x.volume->thickness_factor, y.volume->thickness_factor);
        EXPECT_EQ(x.volume->attenuation_distance, y.volume->attenuation_distance);
        EXPECT_EQ(x.volume->attenuation_color, y.volume->attenuation_color);
      }
      EXPECT_EQ(x.dispersion.has_value(), y.dispersion.has_value());
    }
    for (const Mesh& mesh : b.meshes) EXPECT_TRUE(mesh.closed) << mesh.name;
  }
  // The same through the CLI: `pbrkit scene write`, then `pbrkit info` finds every
  // extension supported and nothing to warn about.
  const auto path = test::scratch_dir() / "glass_cli.glb";
  std::string out;
  ASSERT_EQ(test::run_command(
                test::cli_path().string() + " scene write glass '" + path.string() + "'", &out),
            0)
      << out;
  ASSERT_EQ(
      test::run_command(test::cli_path().string() + " info --json '" + path.string() + "'", &out),
      0)
      << out;
  const nlohmann::json j = nlohmann::json::parse(out.substr(out.find('{')));
  EXPECT_EQ(j["extensions_unsupported"], nlohmann::json::array());
  EXPECT_EQ(j["warnings"], nlohmann::json::array());
  std::vector<std::string> used = j["extensions_used"];
  std::sort(used.begin(), used.end());
  EXPECT_EQ(used, (std::vector<std::string>{"KHR_materials_dispersion", "KHR_materials_ior",
                                            "KHR_materials_transmission", "KHR_materials_volume"}));
}

TEST(BuiltinScenes, InstancesIsAFieldOfOneRockMadeOnce) {
  const Scene s = load_scene("instances");
  EXPECT_EQ(s.source, "builtin:instances");
  ASSERT_EQ(s.meshes.size(), 3u);  // the ground, the rock, the glowing rock
  ASSERT_EQ(s.instances.size(), 1u + 100u * 100u);
  int rocks = 0, glowing = 0, mirrored = 0, squashed = 0;
  for (const Instance& inst : s.instances) {
    const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
    const Material& m = s.material_of(mesh);
    if (mesh.name == "ground") continue;
    (m.emissive_factor != glm::vec3(0.0f) ? glowing : rocks)++;
    const glm::mat3 a(inst.transform);
    mirrored += glm::determinant(a) < 0.0f;
    const float sx = glm::length(a[0]), sy = glm::length(a[1]);
    squashed += std::fabs(sx / sy - 1.0f) > 0.5f;
    // Every rock rests on the ground: its lowest vertex at y = 0.
    float lowest = std::numeric_limits<float>::max();
    for (const glm::vec3& p : mesh.positions)
      lowest = std::min(lowest, (inst.transform * glm::vec4(p, 1.0f)).y);
    EXPECT_NEAR(lowest, 0.0f, 1e-5f);
  }
  EXPECT_EQ(rocks, 9999);
  EXPECT_EQ(glowing, 1);
  EXPECT_GE(mirrored, 40);  // every 211th
  EXPECT_GE(squashed, 50);  // every 173rd
  // One rock mesh: 120 unique triangles for 1.2 M instanced ones; closed (the seam and
  // poles of its sphere move together).
  const Mesh& rock = s.meshes[1];
  EXPECT_EQ(rock.triangle_count(), 120u);
  EXPECT_TRUE(count_edges(rock).closed());
  EXPECT_EQ(s.triangle_count(), 2u + 10000u * 120u);
  // The camera sees the field's centre.
  const glm::vec2 c = project(s.cameras.at(0), glm::vec3(0.0f));
  EXPECT_LT(std::fabs(c.x), 0.5f);
  EXPECT_LT(std::fabs(c.y), 0.9f);

  // Written, the rock is one node with EXT_mesh_gpu_instancing.
  const auto path = test::scratch_dir() / "instances.glb";
  write_glb(s, path);
  const Scene loaded = load_scene(path.string());
  EXPECT_EQ(loaded.node_count, 4u);  // the ground, the rocks, the glowing rock, the camera
  EXPECT_EQ(loaded.extensions_required, std::vector<std::string>{"EXT_mesh_gpu_instancing"});
  EXPECT_EQ(loaded.instances.size(), s.instances.size());
}

// Power of an emitter in luminance-weighted watts-like units (the scene's radiometric
// units): a point light 4 pi I, a spot 2 pi (1 - cos(outer)) I at most, a one-sided
// emissive quad pi L A.
float luminance(glm::vec3 c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

TEST(BuiltinScenes, LightsIsAClosedRoomWithManyVariedEmitters) {
  const Scene s = load_scene("lights");
  EXPECT_EQ(s.source, "builtin:lights");
  // Everything lies in the room x in [-4, 4], y in [0, 3], z in [-7, 7], whose six walls
  // are its bounds.
  const Bounds b = s.world_bounds();
  EXPECT_NEAR(b.min.x, -4.0f, 1e-5f);
  EXPECT_NEAR(b.max.x, 4.0f, 1e-5f);
  EXPECT_NEAR(b.min.y, 0.0f, 1e-5f);
  EXPECT_NEAR(b.max.y, 3.0f, 1e-5f);
  EXPECT_NEAR(b.min.z, -7.0f, 1e-5f);
  EXPECT_NEAR(b.max.z, 7.0f, 1e-5f);
  auto strictly_inside = [](glm::vec3 p) {
    return std::fabs(p.x) < 4.0f && p.y > 0.0f && p.y < 3.0f && std::fabs(p.z) < 7.0f;
  };

  std::vector<float> powers;
  int spots = 0, points = 0;
  for (const Light& l : s.lights) {
    ASSERT_NE(l.type, Light::Type::kDirectional) << l.name;
    ASSERT_TRUE(l.range.has_value()) << l.name;
    EXPECT_GT(*l.range, 0.5f) << l.name;
    EXPECT_TRUE(strictly_inside(l.position)) << l.name;
    if (l.type == Light::Type::kSpot) {
      ++spots;
      EXPECT_LT(l.inner_cone_angle, l.outer_cone_angle) << l.name;
      // Pointing down, reaching the floor within its range: a pool of light.
      const glm::vec3 d = glm::normalize(l.direction);
      ASSERT_LT(d.y, -0.5f) << l.name;
      EXPECT_LT(l.position.y / -d.y, *l.range) << l.name;
      powers.push_back(2.0f * 3.14159265f * (1.0f - std::cos(l.outer_cone_angle)) * l.intensity *
                       luminance(l.color));
    } else {
      ++points;
      powers.push_back(4.0f * 3.14159265f * l.intensity * luminance(l.color));
    }
  }
  EXPECT_EQ(spots, 6);
  EXPECT_EQ(points, 76);
  // The first lights are the spots (a renderer that shades only a few shows the pools).
  for (int k = 0; k < spots; ++k) EXPECT_EQ(s.lights[std::size_t(k)].type, Light::Type::kSpot);

  int emitters = 0, most_uses = 0;
  std::vector<int> uses(s.meshes.size(), 0);
  for (const Instance& inst : s.instances) {
    const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
    const Material& m = s.material_of(mesh);
    if (m.emissive_factor == glm::vec3(0.0f)) continue;
    ++emitters;
    most_uses = std::max(most_uses, ++uses[std::size_t(inst.mesh)]);
    ASSERT_EQ(mesh.triangle_count(), 2u) << mesh.name;
    float area = 0.0f;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = glm::vec3(inst.transform * glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f));
      area += 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
      EXPECT_TRUE(strictly_inside((p[0] + p[1] + p[2]) / 3.0f)) << mesh.name;
    }
    powers.push_back(3.14159265f * m.emissive_strength * luminance(m.emissive_factor) * area);
  }
  EXPECT_EQ(emitters, 23);
  EXPECT_EQ(most_uses, 12);  // the warm ceiling panels: one mesh, twelve instances
  EXPECT_EQ(powers.size(), 105u);
  // Different powers: over more than a decade.
  const auto [lo, hi] = std::minmax_element(powers.begin(), powers.end());
  EXPECT_GT(*lo, 0.0f);
  EXPECT_GT(*hi / *lo, 20.0f);

  // The camera stands in the room and sees the plinth with the gold sphere.
  const Camera& camera = s.cameras.at(0);
  EXPECT_TRUE(strictly_inside(camera.position()));
  const glm::vec2 c = project(camera, {0.0f, 1.0f, -3.0f});
  EXPECT_LT(std::fabs(c.x), 0.5f);
  EXPECT_LT(std::fabs(c.y), 0.9f);

  // Written and read back: the same lights (with their ranges) and instances.
  const auto path = test::scratch_dir() / "lights.glb";
  write_glb(s, path);
  const Scene loaded = load_scene(path.string());
  ASSERT_EQ(loaded.lights.size(), s.lights.size());
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    ASSERT_TRUE(loaded.lights[i].range.has_value());
    EXPECT_FLOAT_EQ(*loaded.lights[i].range, *s.lights[i].range);
    EXPECT_NEAR(glm::distance(loaded.lights[i].position, s.lights[i].position), 0.0f, 1e-5f);
  }
  EXPECT_EQ(loaded.instances.size(), s.instances.size());
  EXPECT_EQ(loaded.triangle_count(), s.triangle_count());
}

// The nearest hit of the ray o + s d (s > 0) on the instances whose mesh `counts`, or
// infinity; Moller-Trumbore with the triangle's edges included, so that a ray through an
// edge or a corner that two meshes share hits.
template <class Counts>
float nearest_hit(const Scene& s, glm::vec3 o, glm::vec3 d, Counts counts) {
  float nearest = std::numeric_limits<float>::infinity();
  for (const Instance& inst : s.instances) {
    const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
    if (!counts(mesh)) continue;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = glm::vec3(inst.transform * glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f));
      const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0], q = glm::cross(d, e2);
      const float det = glm::dot(e1, q);
      if (std::fabs(det) < 1e-12f) continue;
      const glm::vec3 r = o - p[0];
      const float u = glm::dot(r, q) / det;
      const glm::vec3 m = glm::cross(r, e1);
      const float v = glm::dot(d, m) / det, dist = glm::dot(e2, m) / det;
      constexpr float kEdge = 1e-5f;
      if (u >= -kEdge && v >= -kEdge && u + v <= 1.0f + kEdge && dist > 1e-6f)
        nearest = std::min(nearest, dist);
    }
  }
  return nearest;
}

TEST(BuiltinScenes, InteriorIsAClosedRoomLitThroughItsWindow) {
  const Scene s = load_scene("interior");
  EXPECT_EQ(s.source, "builtin:interior");
  EXPECT_TRUE(s.warnings.empty());
  // The room inside: x in [-2, 2], y in [0, 3], z in [-2.5, 2.5]; the window in the +Z
  // wall, x in [-0.2, 1], y in [0.9, 2.3].
  auto inside = [](glm::vec3 p) {
    return std::fabs(p.x) < 2.0f && p.y > 0.0f && p.y < 3.0f && std::fabs(p.z) < 2.5f;
  };
  auto in_window = [](glm::vec3 p) {
    return p.x > -0.2f && p.x < 1.0f && p.y > 0.9f && p.y < 2.3f;
  };
  auto is_shell = [](const Mesh& mesh) {
    for (const char* name : {"floor", "ceiling", "wall", "window"})
      if (mesh.name.find(name) != std::string::npos) return true;
    return false;
  };
  auto all = [](const Mesh&) { return true; };

  // Watertight: from points all over the room, rays in every direction, and rays to each
  // inside corner and the middle of each inside edge (where walls meet), leave only
  // through the window.
  std::vector<glm::vec3> origins;
  for (const float x : {-1.9f, -0.5f, 0.7f, 1.9f})
    for (const float y : {0.05f, 1.5f, 2.95f})
      for (const float z : {-2.4f, 0.0f, 2.4f}) origins.push_back({x, y, z});
  std::vector<glm::vec3> directions;
  constexpr int kDirections = 400;
  for (int k = 0; k < kDirections; ++k) {  // a Fibonacci sphere
    const float z = 1.0f - 2.0f * (float(k) + 0.5f) / float(kDirections);
    const float phi = 2.39996323f * float(k), r = std::sqrt(1.0f - z * z);
    directions.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  int escaped = 0;
  for (const glm::vec3& o : origins) {
    std::vector<glm::vec3> dirs = directions;
    for (const float x : {-2.0f, 0.0f, 2.0f})
      for (const float y : {0.0f, 1.5f, 3.0f})
        for (const float z : {-2.5f, 0.0f, 2.5f})
          if ((std::fabs(x) == 2.0f) + (y != 1.5f) + (std::fabs(z) == 2.5f) >= 2)
            dirs.push_back(glm::normalize(glm::vec3(x, y, z) - o));
    for (const glm::vec3& d : dirs) {
      if (std::isfinite(nearest_hit(s, o, d, is_shell))) continue;
      ++escaped;
      // Out through the opening in the plane z = 2.5.
      ASSERT_GT(d.z, 0.0f) << o.x << " " << o.y << " " << o.z;
      const glm::vec3 at = o + (2.5f - o.z) / d.z * d;
      EXPECT_TRUE(in_window(at)) << at.x << " " << at.y << " from " << o.x << " " << o.y << " "
                                 << o.z;
    }
  }
  EXPECT_GT(escaped, 0);

  // The sun: one directional light, steep, through the window onto the floor, where
  // nothing stands between the patch and the window.
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& sun = s.lights[0];
  EXPECT_EQ(sun.type, Light::Type::kDirectional);
  const glm::vec3 d = glm::normalize(sun.direction);
  EXPECT_LT(d.y, -std::sin(glm::radians(45.0f)));
  const glm::vec3 window_centre(0.4f, 1.6f, 2.6f);
  const float to_floor = nearest_hit(s, window_centre, d, all);
  ASSERT_TRUE(std::isfinite(to_floor));
  const glm::vec3 patch = window_centre + to_floor * d;
  EXPECT_NEAR(patch.y, 0.0f, 1e-5f);
  EXPECT_TRUE(inside(patch + glm::vec3(0.0f, 0.01f, 0.0f)));
  EXPECT_FALSE(std::isfinite(nearest_hit(s, patch + glm::vec3(0.0f, 1e-3f, 0.0f), -d, all)));

  // The camera stands in the room, faces away from the window, and sees the room but not
  // the sunlit patch: what it sees is lit by bounced light.
  const Camera& camera = s.cameras.at(0);
  EXPECT_TRUE(inside(camera.position()));
  EXPECT_LT(camera.forward().z, -0.8f);
  const glm::vec4 patch_view = view_matrix(camera) * glm::vec4(patch, 1.0f);
  const glm::vec2 patch_ndc = project(camera, patch);
  EXPECT_TRUE(patch_view.z > 0.0f || std::fabs(patch_ndc.x) > 1.0f || std::fabs(patch_ndc.y) > 1.0f)
      << patch_ndc.x << " " << patch_ndc.y;

  // The materials the scene is for, each on an object the camera sees.
  auto seen = [&](const std::string& name) {
    for (const Instance& inst : s.instances) {
      const Mesh& mesh = s.meshes[std::size_t(inst.mesh)];
      if (mesh.name != name) continue;
      Bounds b;
      for (const glm::vec3& p : mesh.positions) b.extend(p);
      const glm::vec2 ndc = project(camera, glm::vec3(inst.transform * glm::vec4(b.center(), 1)));
      return std::fabs(ndc.x) < 1.0f && std::fabs(ndc.y) < 1.0f;
    }
    return false;
  };
  const Material& floor = named(s, "floor");
  EXPECT_EQ(floor.metallic_factor, 0.0f);
  EXPECT_NEAR(floor.roughness_factor, 0.15f, 1e-6f);
  const Material& metal = named(s, "copper");
  EXPECT_EQ(metal.metallic_factor, 1.0f);
  EXPECT_NEAR(metal.roughness_factor, 0.35f, 1e-6f);
  EXPECT_TRUE(seen("metal_sphere"));
  const Material& glass = named(s, "glass");
  ASSERT_TRUE(glass.transmission && glass.volume);
  EXPECT_EQ(glass.transmission->factor, 1.0f);
  EXPECT_FALSE(glass.double_sided);  // glTF-Validator: KHR_MATERIALS_VOLUME_DOUBLE_SIDED
  for (const Mesh& mesh : s.meshes)
    if (&s.material_of(mesh) == &glass) {
      EXPECT_TRUE(count_edges(mesh).closed()) << mesh.name;
      EXPECT_TRUE(seen(mesh.name));
    }
  EXPECT_TRUE(seen("table_top"));
  EXPECT_TRUE(seen("cabinet"));
}

TEST(BuiltinScenes, UnknownNameListsTheKnownOnes) {
  try {
    builtin_scene("teapot");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spheres"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("iridescence"), std::string::npos);
  }
  EXPECT_TRUE(is_builtin_scene("cornell"));
  EXPECT_FALSE(is_builtin_scene("cornell.glb"));
}

TEST(SceneHelpers, DefaultMaterialIsTheSpecDefault) {
  const Material& m = Scene::default_material();
  EXPECT_EQ(m.base_color_factor, glm::vec4(1.0f));
  EXPECT_EQ(m.metallic_factor, 1.0f);
  EXPECT_EQ(m.roughness_factor, 1.0f);
  EXPECT_EQ(m.emissive_factor, glm::vec3(0.0f));
  EXPECT_EQ(m.alpha_mode, AlphaMode::kOpaque);
  EXPECT_EQ(m.alpha_cutoff, 0.5f);
  EXPECT_FALSE(m.double_sided);
  Scene s;
  Mesh mesh;
  mesh.material = 7;  // out of range falls back to the default
  EXPECT_EQ(&s.material_of(mesh), &m);
}

}  // namespace
}  // namespace pbrkit
