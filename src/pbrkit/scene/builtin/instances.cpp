// The instanced scene: a field of copies of one procedural rock.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/scene/builtin/builtin.h"
#include "pbrkit/scene/mesh_attributes.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::builtin {

namespace {

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

}  // namespace

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

}  // namespace pbrkit::builtin
