// Shadows of transmissive objects in the environment light (occluders.h, occluders.glsl):
// the GLSL form factors against the exact factor, integrated here in double over the
// hemisphere by casting cosine-distributed rays at the sphere or the parallelepiped; the
// transmittance against the closed form of the dielectric's hemispherical reflectance; and a
// floor under a tinted glass sphere, rendered with the shadows on and off, whose ratio must
// be 1 - F (1 - T) at every floor pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/harness/occluder_eval.h"
#include "gl_test_context.h"
#include "pbrkit/core/equirect.h"
#include "pbrkit/gl/occluders.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::gl {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The exact form factor from (x, n) to a body, by the midpoint rule over Malley's mapping
// of the unit square to cosine-distributed directions (each cell an equal share of the
// cosine-weighted hemisphere): the share of cells whose ray meets the body.
template <class Hits>
double integrated_form_factor(glm::dvec3 x, glm::dvec3 n, Hits hits, int cells = 600) {
  const glm::dvec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                                          : glm::cross(n, glm::dvec3(0, 1, 0)));
  const glm::dvec3 b = glm::cross(n, t);
  long hit = 0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const double r = std::sqrt((i + 0.5) / cells), phi = 2.0 * kPi * (j + 0.5) / cells;
      const double u = r * std::cos(phi), v = r * std::sin(phi);
      const glm::dvec3 d = u * t + v * b + std::sqrt(std::max(0.0, 1.0 - u * u - v * v)) * n;
      hit += hits(x, d) ? 1 : 0;
    }
  return double(hit) / (double(cells) * cells);
}

bool ray_meets_sphere(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, double r) {
  const glm::dvec3 oc = o - c;
  const double b = glm::dot(oc, d), q = glm::dot(oc, oc) - r * r;
  const double disc = b * b - q;
  return disc >= 0.0 && (-b + std::sqrt(disc)) > 0.0;
}

// A ray against the parallelepiped c + sum_k s_k a_k, |s_k| <= 1: slabs in its own
// coordinates (the inverse of the matrix of half-axes).
bool ray_meets_parallelepiped(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, const glm::dmat3& A) {
  const glm::dmat3 inv = glm::inverse(A);
  const glm::dvec3 lo = inv * (o - c), ld = inv * d;
  double t0 = 0.0, t1 = 1e30;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ld[k]) < 1e-15) {
      if (std::abs(lo[k]) > 1.0) return false;
      continue;
    }
    double a = (-1.0 - lo[k]) / ld[k], b = (1.0 - lo[k]) / ld[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

// The exact form factor from (x, n) to a parallelepiped wholly above x's horizon, by
// Lambert's formula for polygons (Arvo 1995, eq. 3) over the faces that face x: per face,
// 1 / (2 pi) |sum_i theta_i n.g_i|, theta_i the angle between the directions to consecutive
// corners and g_i the unit normal of the plane through them and x.
double lambert_parallelepiped(glm::dvec3 x, glm::dvec3 n, glm::dvec3 c, const glm::dmat3& A) {
  double total = 0.0;
  for (int k = 0; k < 3; ++k)
    for (int side = -1; side <= 1; side += 2) {
      const glm::dvec3 normal = double(side) * A[k];
      const glm::dvec3 face = c + normal;
      if (glm::dot(x - face, glm::cross(A[(k + 1) % 3], A[(k + 2) % 3])) * side *
              glm::sign(glm::dot(glm::cross(A[(k + 1) % 3], A[(k + 2) % 3]), A[k])) <=
          0.0)
        continue;  // faces away from x (or x lies in its plane)
      const glm::dvec3 u = A[(k + 1) % 3], v = A[(k + 2) % 3];
      const glm::dvec3 corners[4] = {face + u + v, face - u + v, face - u - v, face + u - v};
      double sum = 0.0;
      for (int i = 0; i < 4; ++i) {
        const glm::dvec3 a = glm::normalize(corners[i] - x),
                         b = glm::normalize(corners[(i + 1) % 4] - x);
        const glm::dvec3 g = glm::cross(a, b);
        const double len = glm::length(g);
        if (len > 0.0)
          sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, g) / len;
      }
      total += std::abs(sum) / (2.0 * kPi);
    }
  return total;
}

TEST(OccluderFormFactors, ASphereAboveTheHorizonIsTheDifferentialToSphereFactor) {
  testing::context();
  std::vector<FormFactorCase> cases;
  std::vector<double> exact;
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  // Spheres of radius 0.5 whose lowest point is above the floor's plane y = 0, seen from
  // floor points at several distances and angles.
  for (float height : {0.6f, 1.0f, 2.5f})
    for (float across : {0.0f, 0.4f, 1.5f, 4.0f}) {
      FormFactorCase c;
      c.x = glm::vec3(across, 0.0f, 0.3f * across);
      c.n = n;
      c.center = glm::vec3(0.0f, height, 0.0f);
      c.radius = 0.5f;
      // Wholly above x's horizon: the sphere's angular radius below the centre's elevation.
      const double d = glm::length(glm::dvec3(c.center - c.x));
      if (std::asin(0.5 / d) > std::asin(double(height) / d)) continue;
      cases.push_back(c);
      exact.push_back(
          integrated_form_factor(glm::dvec3(c.x), glm::dvec3(n), [&](glm::dvec3 o, glm::dvec3 dir) {
            return ray_meets_sphere(o, dir, glm::dvec3(c.center), 0.5);
          }));
    }
  // Well inside: the sphere's contents, not shadowed by it (kContentsMargin).
  FormFactorCase inside;
  inside.center = glm::vec3(0.2f, 0.1f, 0.0f);
  inside.radius = 0.5f;
  cases.push_back(inside);
  exact.push_back(0.0);
  ASSERT_GE(cases.size(), 10u);
  const std::vector<float> got = form_factors_glsl(cases);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    // The midpoint rule over 600^2 cells: within 2e-3 of the integral here.
    EXPECT_NEAR(got[i], exact[i], 2e-3 + 1e-2 * exact[i]) << "case " << i;
  }
}

// A parallelepiped's factor is taken as a disc of its projected area towards the point
// (occluder_form_factors.glsl): exact in the limit of distance, and an approximation near
// it whose error this test bounds where it was measured, against Lambert's exact formula, on
// a cube, a slab, a tilted box, a flat sheet (a degenerate axis) and a column, from 1 mm off
// their nearest face to 20 of their half-diagonals.
TEST(OccluderFormFactors, AParallelepipedIsItsProjectedAreaFromAfarAndCloseNearby) {
  testing::context();
  struct Body {
    glm::vec3 axes[3];
  };
  const glm::mat3 tilt = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1, 1, 0)));
  const Body bodies[] = {
      {{glm::vec3(0.35f, 0, 0), glm::vec3(0, 0.35f, 0), glm::vec3(0, 0, 0.35f)}},
      {{glm::vec3(0.8f, 0, 0), glm::vec3(0, 0.1f, 0), glm::vec3(0, 0, 0.5f)}},
      {{tilt * glm::vec3(0.5f, 0, 0), tilt * glm::vec3(0, 0.3f, 0), tilt * glm::vec3(0, 0, 0.2f)}},
      {{glm::vec3(0.3f, 0, 0), glm::vec3(0, 0.25f, 0), glm::vec3(0, 0, 0.0f)}},
      {{glm::vec3(0.05f, 0, 0), glm::vec3(0, 0.05f, 0), glm::vec3(0, 0, 1.0f)}},  // a column
  };
  std::vector<FormFactorCase> cases;
  std::vector<double> exact, distance;
  for (const Body& body : bodies) {
    // The exact integral's body: a flat sheet (a zero axis) given a hair's thickness.
    glm::dmat3 A(glm::dvec3(body.axes[0]), glm::dvec3(body.axes[1]), glm::dvec3(body.axes[2]));
    if (glm::length(A[2]) == 0.0) A[2] = glm::dvec3(0.0, 0.0, 1e-6);
    const double half_diagonal =
        glm::length(glm::dvec3(body.axes[0] + body.axes[1] + body.axes[2]));
    // Points on a wall z = 0 facing +z, the body's centre in front of it (its nearest face
    // 1 mm off the wall, or further), looked at from straight below it and sideways.
    const float touching =
        std::abs(body.axes[0].z) + std::abs(body.axes[1].z) + std::abs(body.axes[2].z) + 0.001f;
    for (float z : {touching, 1.2f, 2.5f, 6.0f, 20.0f})
      for (float side : {0.0f, 0.5f, 1.5f}) {
        FormFactorCase c;
        c.sphere = false;
        c.x = glm::vec3(side * std::max(z, 0.6f), 0.3f * side, 0.0f);
        c.n = glm::vec3(0.0f, 0.0f, 1.0f);
        c.center = glm::vec3(0.0f, 0.0f, z);
        for (int k = 0; k < 3; ++k) c.axes[k] = body.axes[k];
        cases.push_back(c);
        distance.push_back(glm::length(glm::dvec3(c.center - c.x)) / half_diagonal);
        exact.push_back(
            lambert_parallelepiped(glm::dvec3(c.x), glm::dvec3(c.n), glm::dvec3(c.center), A));
        // Lambert's formula against the ray-cast integral, where the body is large enough
        // on the hemisphere for the integral's cells (a check of the check).
        if (z < 2.0f && side == 0.0f) {
          const double cast = integrated_form_factor(
              glm::dvec3(c.x), glm::dvec3(c.n), [&](glm::dvec3 o, glm::dvec3 d) {
                return ray_meets_parallelepiped(o, d, glm::dvec3(c.center), A);
              });
          EXPECT_NEAR(cast, exact.back(), 5e-3) << "z " << z;
        }
      }
    // Well inside: the body's contents, not shadowed by it (kContentsMargin).
    FormFactorCase inside;
    inside.sphere = false;
    inside.x =
        glm::vec3(0.1f, 0.0f, 0.0f) * glm::length(body.axes[0]) + glm::vec3(0.0f, 0.0f, 3.0f);
    inside.center = glm::vec3(0.0f, 0.0f, 3.0f);
    for (int k = 0; k < 3; ++k) inside.axes[k] = body.axes[k];
    if (glm::length(body.axes[2]) > 0.0f) {
      cases.push_back(inside);
      exact.push_back(0.0);
      distance.push_back(0.0);
    }
  }
  // Floor points (n = +y) beside a box standing 1 mm above the floor (0.7 wide, 1 tall): the
  // common case of an object on a floor, at 1 cm to 1 m from its side and off its corner.
  {
    const glm::vec3 axes[3] = {glm::vec3(0.35f, 0, 0), glm::vec3(0, 0.5f, 0),
                               glm::vec3(0, 0, 0.35f)};
    const glm::dmat3 A{glm::dvec3(axes[0]), glm::dvec3(axes[1]), glm::dvec3(axes[2])};
    const glm::vec3 centre(0.0f, 0.501f, 0.0f);
    for (float gap : {0.01f, 0.1f, 0.3f, 1.0f})
      for (float along : {0.0f, 0.3f, 0.6f}) {
        FormFactorCase c;
        c.sphere = false;
        c.x = glm::vec3(0.35f + gap, 0.0f, along);
        c.n = glm::vec3(0.0f, 1.0f, 0.0f);
        c.center = centre;
        for (int k = 0; k < 3; ++k) c.axes[k] = axes[k];
        cases.push_back(c);
        distance.push_back(glm::length(glm::dvec3(c.center - c.x)) /
                           glm::length(glm::dvec3(0.35, 0.5, 0.35)));
        exact.push_back(
            lambert_parallelepiped(glm::dvec3(c.x), glm::dvec3(c.n), glm::dvec3(centre), A));
      }
  }
  const std::vector<float> got = form_factors_glsl(cases);
  double worst_far = 0.0, worst_near = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const double err = double(got[i]) - exact[i];
    // Each case's figures, for re-measuring the bounds below.
    if (std::getenv("PBRKIT_PRINT_CASES"))
      std::printf("case %2zu dist %6.2f exact %.4f got %.4f err %+.4f\n", i, distance[i], exact[i],
                  double(got[i]), err);
    if (distance[i] == 0.0) {
      EXPECT_EQ(got[i], 0.0f) << "case " << i << ": inside";
    } else {
      worst_near = std::max(worst_near, std::abs(err));
      // Near: measured within 0.15 (0.13 above exact 0.29 on a floor point 10 cm beside a
      // standing box's corner, 0.14 below exact 0.57 under a tilted box's edge).
      EXPECT_NEAR(got[i], exact[i], 0.2)
          << "case " << i << " at " << distance[i] << " half-diagonals";
      if (distance[i] >= 8.0) {
        // Far: the disc of the projected area is the body's solid angle to first order in
        // size / distance (the nearer faces are nearer than the centre).
        if (exact[i] >= 1e-3) worst_far = std::max(worst_far, std::abs(err) / exact[i]);
        EXPECT_NEAR(got[i], exact[i], 0.1 * exact[i] + 2e-4) << "case " << i;
      }
    }
  }
  std::printf(
      "parallelepiped form factor: worst absolute error %.3f; at 8 half-diagonals or more "
      "(F >= 1e-3) worst relative error %.3f\n",
      worst_near, worst_far);
}

// The closed form of a dielectric's diffuse (cosine-weighted hemispherical) reflectance from
// outside, for relative index n > 1 (Judd 1942; as written in Walsh 1926 and in Egan and
// Hilgeman, "Optical Properties of Inhomogeneous Materials", 1979, eq. 3.10).
double diffuse_reflectance(double n) {
  const double n2 = n * n, n4 = n2 * n2;
  return 0.5 + (n - 1.0) * (3.0 * n + 1.0) / (6.0 * (n + 1.0) * (n + 1.0)) +
         n2 * (n2 - 1.0) * (n2 - 1.0) / std::pow(n2 + 1.0, 3.0) * std::log((n - 1.0) / (n + 1.0)) -
         2.0 * n * n2 * (n2 + 2.0 * n - 1.0) / ((n2 + 1.0) * (n4 - 1.0)) +
         8.0 * n4 * (n4 + 1.0) / ((n2 + 1.0) * (n4 - 1.0) * (n4 - 1.0)) * std::log(n);
}

TEST(OccluderTransmittance, GlassLetsThroughWhatItsInterfacesDoNotReflect) {
  // The closed form's own check: 0.0918 at n = 1.5 (the figure quoted for glass).
  EXPECT_NEAR(diffuse_reflectance(1.5), 0.0918, 5e-4);
  for (double ior : {1.2, 1.5, 2.0}) {
    Material m;
    m.metallic_factor = 0.0f;
    m.ior = float(ior);
    m.transmission = TransmissionExtension{1.0f, {}};
    const double leave = 1.0 - diffuse_reflectance(ior);
    // Thin-walled: one interface; a volume: in and out, and Beer-Lambert over the chord.
    EXPECT_NEAR(occluder_transmittance(m, false, 1.0f).x, leave, 1e-3) << ior;
    m.volume = VolumeExtension{1.0f, {}, 2.0f, glm::vec3(0.5f, 0.25f, 1.0f)};
    const glm::vec3 t = occluder_transmittance(m, true, 3.0f);
    EXPECT_NEAR(t.x, leave * leave * std::pow(0.5, 1.5), 1e-3) << ior;
    EXPECT_NEAR(t.y, leave * leave * std::pow(0.25, 1.5), 1e-3) << ior;
    EXPECT_NEAR(t.z, leave * leave, 1e-3) << ior;
  }
  Material clear;  // ior 1: no interface, nothing reflected
  clear.metallic_factor = 0.0f;
  clear.ior = 1.0f;
  clear.transmission = TransmissionExtension{1.0f, {}};
  EXPECT_FLOAT_EQ(occluder_transmittance(clear, false, 1.0f).y, 1.0f);
  clear.metallic_factor = 1.0f;  // a metal lets nothing through
  EXPECT_FLOAT_EQ(occluder_transmittance(clear, false, 1.0f).y, 0.0f);
}

// A white rough floor (12 x 12 at y = 0) with `object` (its mesh and transform; material
// `material`, `textures` the scene's) in environment `env`, seen from `eye` towards the
// origin, rendered with the settings `on` and `off`. For each floor pixel whose ray does not
// pass near the object (`near(eye, direction)`: the object and its silhouette's pixels, and
// the floor seen through it, are left out), check(pixel, floor point, ratio) with `ratio`
// the on / off ratio per channel. Returns the pixels checked.
template <class Near, class Check>
int floor_ratios(Mesh object, const glm::mat4& transform, const Material& material,
                 std::vector<Texture> textures, const Environment& env, glm::vec3 eye,
                 const RenderSettings& on_settings, const RenderSettings& off_settings, Near near,
                 Check check) {
  testing::context();
  constexpr int kW = 96, kH = 64;
  Scene scene;
  Material floor;
  floor.metallic_factor = 0.0f;
  floor.roughness_factor = 1.0f;
  scene.materials = {floor, material};
  scene.textures = std::move(textures);
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-6, 0, 6), glm::vec3(12, 0, 0), glm::vec3(0, 0, -12)), 0);
  add_mesh_instance(scene, std::move(object), 1, transform);
  Camera camera;
  camera.yfov = 0.9f;
  camera.camera_to_world =
      glm::inverse(glm::lookAt(eye, glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  const IblMaps maps = testing::small_ibl_maps(env);
  const Image on = render_headless(scene, camera, kW, kH, &env, &maps, on_settings);
  const Image off = render_headless(scene, camera, kW, kH, &env, &maps, off_settings);
  const glm::mat4 inv_vp =
      glm::inverse(projection_matrix(camera, float(kW) / kH) * view_matrix(camera));
  int counted = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      // The pixel's ray (image row 0 is the top).
      const glm::vec2 ndc((x + 0.5f) / kW * 2.0f - 1.0f, 1.0f - (y + 0.5f) / kH * 2.0f);
      // A point on the pixel's ray (the projection's far plane is at infinity).
      const glm::vec4 far = inv_vp * glm::vec4(ndc, 0.5f, 1.0f);
      const glm::dvec3 d = glm::normalize(glm::dvec3(far) / double(far.w) - glm::dvec3(eye));
      if (d.y >= 0.0 || near(glm::dvec3(eye), d)) continue;
      const glm::dvec3 p = glm::dvec3(eye) - double(eye.y) / d.y * d;
      if (std::abs(p.x) > 5.5 || std::abs(p.z) > 5.5) continue;
      check(glm::ivec2(x, y), p, glm::dvec3(on.rgb(x, y)) / glm::dvec3(off.rgb(x, y)));
      ++counted;
    }
  return counted;
}

// floor_ratios for a sphere of `material` (radius 0.5, centre 1.2 above the floor: wholly
// above every floor point's horizon) in a uniform environment (radiance `env_radiance`,
// white by default), seen from low at the side:
// each floor pixel's ratio held to want(F) in every channel within 4e-3, F the closed-form
// sphere factor at the floor point; at least 1000 pixels, 100 of them with F > 0.05.
template <class Want>
void expect_floor_under_sphere(const char* what, const Material& material,
                               std::vector<Texture> textures, const RenderSettings& on_settings,
                               const RenderSettings& off_settings, Want want,
                               float env_radiance = 1.0f) {
  const float radius = 0.5f;
  const glm::dvec3 centre(0.0, 1.2, 0.0);
  int shadowed = 0;
  double worst = 0.0;
  const int counted = floor_ratios(
      make_uv_sphere(radius), glm::translate(glm::mat4(1.0f), glm::vec3(centre)), material,
      std::move(textures), Environment::constant(glm::vec3(env_radiance)),
      glm::vec3(0.0f, 0.5f, 3.5f), on_settings, off_settings,
      [&](glm::dvec3 eye, glm::dvec3 d) { return ray_meets_sphere(eye, d, centre, radius * 1.15); },
      [&](glm::ivec2 px, glm::dvec3 p, glm::dvec3 ratio) {
        const glm::dvec3 w = centre - p;
        const double dist = glm::length(w);
        const double F = double(radius) * radius / (dist * dist) * (w.y / dist);
        const glm::dvec3 expected = want(F);
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, std::abs(ratio[k] - expected[k]));
          EXPECT_NEAR(ratio[k], expected[k], 4e-3)
              << what << ": pixel " << px.x << "," << px.y << " channel " << k;
        }
        shadowed += F > 0.05 ? 1 : 0;
      });
  std::printf("%s: %d pixels (%d with F > 0.05), worst |ratio - expected| %.2e\n", what, counted,
              shadowed, worst);
  EXPECT_GE(counted, 1000);
  EXPECT_GE(shadowed, 100);
}

// Under a tinted glass sphere the image-based light is linear in the visibility, so with
// the shadows on and off the ratio at a floor pixel is 1 - F (1 - T), T the sphere's
// transmittance.
TEST(TransmissiveShadows, AFloorUnderAGlassSphereKeepsOneMinusFTimesOneMinusT) {
  const float radius = 0.5f;
  Material glass;
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission = TransmissionExtension{1.0f, {}};
  glass.volume = VolumeExtension{1.0f, {}, 0.5f, glm::vec3(0.3f, 0.6f, 0.9f)};
  // The sphere's transmittance: two interfaces of ior 1.5 and Beer-Lambert over its mean
  // chord 4 r / 3.
  const double leave = 1.0 - diffuse_reflectance(1.5);
  const glm::dvec3 T =
      leave * leave * glm::pow(glm::dvec3(0.3, 0.6, 0.9), glm::dvec3(4.0 * radius / 3.0 / 0.5));
  RenderSettings on;
  on.msaa = 1;
  RenderSettings off = on;
  off.transmissive_shadows = false;
  expect_floor_under_sphere("floor under a glass sphere", glass, {}, on, off,
                            [&](double F) { return 1.0 - F * (1.0 - T); });
}

// Under an opaque sphere (opaque shadows), the floor keeps 1 - F of the white environment
// and gets F times the sphere's own light back: its albedo (the base colour factor times its
// texture's mean) times the irradiance pi of every one of its sides, over pi. So the ratio
// is 1 - F + F albedo; in the red channel, whose albedo is 1, a white furnace: the floor
// keeps all its light.
TEST(OpaqueShadows, AFloorUnderAnOpaqueSphereKeepsOneMinusFPlusFTimesItsAlbedo) {
  Material rock;
  rock.metallic_factor = 0.0f;
  rock.roughness_factor = 1.0f;
  rock.base_color_factor = glm::vec4(1.0f, 0.5f, 0.5f, 1.0f);
  rock.base_color_texture.texture = 0;
  // Two texels, linear (1, 0.4, 0.2) and (1, 0.8, 0.6): mean (1, 0.6, 0.4).
  Image texels(2, 1, 3);
  texels.data = {1.0f, 0.4f, 0.2f, 1.0f, 0.8f, 0.6f};
  const glm::dvec3 albedo(1.0, 0.5 * 0.6, 0.5 * 0.4);
  RenderSettings on;
  on.msaa = 1;
  on.opaque_shadows = true;
  RenderSettings off = on;
  off.opaque_shadows = false;
  expect_floor_under_sphere("floor under an opaque sphere", rock,
                            {Texture::from_linear(texels, false)}, on, off,
                            [&](double F) { return 1.0 - F + F * albedo; });
}

// An opaque proxy sends its emission besides what it reflects, and an unlit one (KHR_materials_
// unlit) its base colour alone, as the path tracer's unlit surface does: in a uniform
// environment of radiance 2 the floor under the sphere keeps (2 (1 - F) + F L) / 2 of its
// light, L = 2 albedo + emission (emissive factor times strength times the emissive
// texture's mean), and L = the base colour for the unlit sphere, which a lit sphere of that
// albedo would send twice over.
TEST(OpaqueShadows, AnEmissiveOrUnlitSphereSendsItsOwnLightToTheFloor) {
  RenderSettings on;
  on.msaa = 1;
  on.opaque_shadows = true;
  RenderSettings off = on;
  off.opaque_shadows = false;
  Material lamp;
  lamp.metallic_factor = 0.0f;
  lamp.roughness_factor = 1.0f;
  lamp.base_color_factor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  lamp.emissive_factor = glm::vec3(0.2f, 0.6f, 1.0f);
  lamp.emissive_strength = 1.5f;
  lamp.emissive_texture.texture = 0;
  // Two texels, linear (1, 0.5, 0.2) and (1, 0.7, 0.4): mean (1, 0.6, 0.3).
  Image texels(2, 1, 3);
  texels.data = {1.0f, 0.5f, 0.2f, 1.0f, 0.7f, 0.4f};
  const glm::dvec3 emission = 1.5 * glm::dvec3(0.2, 0.6 * 0.6, 1.0 * 0.3);
  expect_floor_under_sphere(
      "floor under an emissive sphere", lamp, {Texture::from_linear(texels, false)}, on, off,
      [&](double F) { return 1.0 - F + F * (2.0 * glm::dvec3(0.5) + emission) / 2.0; }, 2.0f);
  Material unlit;
  unlit.unlit = true;
  unlit.base_color_factor = glm::vec4(0.8f, 0.4f, 0.2f, 1.0f);
  const glm::dvec3 colour(0.8, 0.4, 0.2);
  expect_floor_under_sphere(
      "floor under an unlit sphere", unlit, {}, on, off,
      [&](double F) { return 1.0 - F + F * colour / 2.0; }, 2.0f);
}

// Each side of an opaque proxy sends back albedo E(N) / pi, E the environment's irradiance
// at the side's outward normal N. A floor beside a wall (a box resting on it, turned about
// +Y) under a sky (radiance 1 over the upper half of the environment, 0 below): the floor's
// irradiance is pi, and the wall's vertical sides that it sees have pi / 2 (a uniform
// hemisphere's, in closed form), its base none, its top pi. So a wall of albedo a and one
// of albedo 0, which hide the same light, differ on the floor by F a / 2 of its light, F
// the box's form factor (occluder_form_factors.glsl's, measured against the exact one
// above).
TEST(OpaqueShadows, AFloorBesideAWallSeesItsLitSides) {
  Environment sky = Environment::constant(glm::vec3(1.0f), 128);
  for (int y = sky.map.height / 2; y < sky.map.height; ++y)
    for (int x = 0; x < sky.map.width; ++x) {
      float* p = sky.map.pixel(x, y);  // row 0 is the zenith
      p[0] = p[1] = p[2] = 0.0f;
    }
  Material wall;
  wall.metallic_factor = 0.0f;
  wall.roughness_factor = 1.0f;
  wall.base_color_factor = glm::vec4(0.9f, 0.5f, 0.1f, 1.0f);
  const glm::vec3 centre(0.3f, 1.0f, -1.2f), half(2.0f, 1.0f, 0.15f);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
  const glm::mat4 transform = glm::translate(glm::mat4(1.0f), centre) * turn;
  FormFactorCase wall_case;
  wall_case.sphere = false;
  wall_case.center = centre;
  for (int k = 0; k < 3; ++k) wall_case.axes[k] = glm::vec3(turn[k]) * half[k];
  Material black = wall;
  black.base_color_factor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  RenderSettings on;
  on.msaa = 1;
  on.opaque_shadows = true;
  RenderSettings off = on;
  off.opaque_shadows = false;
  const glm::mat4 to_wall = glm::inverse(transform);
  const auto near_wall = [&](glm::dvec3 eye, glm::dvec3 d) {
    // The ray in the wall's frame against the box grown by 10%: the slab test.
    const glm::dvec3 o = glm::dvec3(to_wall * glm::vec4(eye, 1.0f));
    const glm::dvec3 v = glm::dvec3(glm::mat3(to_wall) * glm::vec3(d));
    double t0 = 0.0, t1 = 1e30;
    for (int k = 0; k < 3; ++k) {
      const double h = 1.1 * half[k] + 0.05;
      const double a = (-h - o[k]) / v[k], b = (h - o[k]) / v[k];
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
    }
    return t0 <= t1;
  };
  std::vector<FormFactorCase> cases;
  std::vector<glm::dvec3> lit, dark;  // on / off with the wall's albedo and with 0
  floor_ratios(make_box(-half, half), transform, wall, {}, sky, glm::vec3(0.0f, 1.6f, 4.0f), on,
               off, near_wall, [&](glm::ivec2, glm::dvec3 p, glm::dvec3 ratio) {
                 FormFactorCase c = wall_case;
                 c.x = glm::vec3(p);
                 c.n = glm::vec3(0, 1, 0);
                 cases.push_back(c);
                 lit.push_back(ratio);
               });
  floor_ratios(make_box(-half, half), transform, black, {}, sky, glm::vec3(0.0f, 1.6f, 4.0f), on,
               off, near_wall,
               [&](glm::ivec2, glm::dvec3, glm::dvec3 ratio) { dark.push_back(ratio); });
  ASSERT_EQ(dark.size(), lit.size());
  testing::context();
  const std::vector<float> F = form_factors_glsl(cases);
  int shadowed = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double want = F[i] * wall.base_color_factor[k] / 2.0;
      worst = std::max(worst, std::abs(lit[i][k] - dark[i][k] - want));
      EXPECT_NEAR(lit[i][k] - dark[i][k], want, 4e-3)
          << "floor point " << cases[i].x.x << "," << cases[i].x.z << " channel " << k;
    }
    shadowed += F[i] > 0.05f ? 1 : 0;
  }
  std::printf(
      "floor beside a wall under a sky: %zu pixels (%d with F > 0.05), worst |ratio - ratio "
      "with a black wall - F albedo / 2| %.2e\n",
      cases.size(), shadowed, worst);
  EXPECT_GE(cases.size(), std::size_t(1000));
  EXPECT_GE(shadowed, 100);
}

// The occluders' geometry is compiled into the surface programs and their transmittances
// are uniforms: a renderer given a new scene (the sphere moved) or new materials (another
// tint) must draw what a fresh renderer draws, not the shadow of the previous ones.
TEST(TransmissiveShadows, ANewSceneOrNewMaterialsMoveTheShadow) {
  testing::context();
  auto scene_with_sphere_at = [](glm::vec3 centre, glm::vec3 tint) {
    Scene scene;
    Material floor;
    floor.metallic_factor = 0.0f;
    Material glass;
    glass.metallic_factor = 0.0f;
    glass.transmission = TransmissionExtension{1.0f, {}};
    glass.volume = VolumeExtension{1.0f, {}, 0.5f, tint};
    scene.materials = {floor, glass};
    add_mesh_instance(scene,
                      make_quad(glm::vec3(-6, 0, 6), glm::vec3(12, 0, 0), glm::vec3(0, 0, -12)), 0);
    add_mesh_instance(scene, make_uv_sphere(0.5f, 24, 12), 1,
                      glm::translate(glm::mat4(1.0f), centre));
    return scene;
  };
  const Scene a = scene_with_sphere_at(glm::vec3(-1.0f, 0.8f, 0.0f), glm::vec3(0.3f, 0.6f, 0.9f));
  const Scene b = scene_with_sphere_at(glm::vec3(1.0f, 0.8f, 0.0f), glm::vec3(0.3f, 0.6f, 0.9f));
  const Scene b_tinted =
      scene_with_sphere_at(glm::vec3(1.0f, 0.8f, 0.0f), glm::vec3(0.9f, 0.2f, 0.2f));
  Camera camera;
  camera.camera_to_world = glm::inverse(
      glm::lookAt(glm::vec3(0, 2.5f, 4), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  const Environment env = Environment::constant(glm::vec3(1.0f));
  const IblMaps maps = testing::small_ibl_maps(env);
  RenderSettings settings;
  settings.msaa = 1;
  constexpr int kW = 64, kH = 48;
  Renderer renderer;
  renderer.set_environment(&env);
  renderer.set_ibl(&maps);
  renderer.set_scene(a);
  renderer.render(camera, kW, kH, settings);
  const Image first = renderer.read_back();
  renderer.set_scene(b);
  renderer.render(camera, kW, kH, settings);
  const Image moved = renderer.read_back();
  renderer.set_materials(b_tinted.materials);
  renderer.render(camera, kW, kH, settings);
  const Image tinted = renderer.read_back();
  EXPECT_NE(first.data, moved.data);
  EXPECT_EQ(moved.data, render_headless(b, camera, kW, kH, &env, &maps, settings).data);
  EXPECT_NE(moved.data, tinted.data);
  EXPECT_EQ(tinted.data, render_headless(b_tinted, camera, kW, kH, &env, &maps, settings).data);
}

// An opaque mesh stands in as its bounding box only where it could be convex: a convex body
// inside a box has at most the box's surface area. A floor (a quad: half its flat box's
// area) and a box (all of it) stand in; a comb of eleven unit fins across a unit cube
// (11 against the cube's 6), as an engine's cooling fins, does not.
TEST(OpaqueShadows, OnlyMeshesThatCouldBeConvexStandInAsBoxes) {
  testing::context();
  Scene scene;
  scene.materials = {Material{}};
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-6, 0, 6), glm::vec3(12, 0, 0), glm::vec3(0, 0, -12)), 0);
  add_mesh_instance(scene, make_box(glm::vec3(-1.0f), glm::vec3(1.0f)), 0,
                    glm::translate(glm::mat4(1.0f), glm::vec3(3, 1, 0)));
  Mesh comb;
  for (int k = 0; k <= 10; ++k) {
    Mesh fin = make_quad(glm::vec3(0.1f * float(k), 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1));
    const auto base = std::uint32_t(comb.positions.size());
    comb.positions.insert(comb.positions.end(), fin.positions.begin(), fin.positions.end());
    comb.normals.insert(comb.normals.end(), fin.normals.begin(), fin.normals.end());
    for (std::uint32_t i : fin.indices) comb.indices.push_back(base + i);
  }
  add_mesh_instance(scene, std::move(comb), 0,
                    glm::translate(glm::mat4(1.0f), glm::vec3(-3, 0, 0)));
  GpuScene gpu;
  gpu.upload(scene);
  EXPECT_NEAR(gpu.meshes[2].surface_area, 11.0f, 1e-4f);
  const std::vector<Occluder> proxies = ibl_occluders(gpu, {false, true});
  ASSERT_EQ(proxies.size(), 2u);
  for (const Occluder& o : proxies) {
    EXPECT_TRUE(o.opaque);
    EXPECT_NE(o.slot, int(gpu.slot_of[2]));  // not the comb
  }
}

// The surface program writes each selected proxy's term out from four lists of indices, by
// kind and role (occluders.glsl's OCCLUDER_TERM lists): every proxy in the one of its kind
// and role, in the selection's order, and a list without proxies empty.
TEST(TransmissiveShadows, EachProxyIsWrittenOutOnceInTheListOfItsKindAndRole) {
  const auto proxy = [](bool sphere, bool opaque) {
    Occluder o;
    o.sphere = sphere;
    o.opaque = opaque;
    return o;
  };
  // select_occluders' order: spheres, then boxes; of each, the transmissive ones first.
  const std::vector<Occluder> mixed = {proxy(true, false),  proxy(true, false), proxy(true, true),
                                       proxy(false, false), proxy(false, true), proxy(false, true)};
  const std::string d = occluder_geometry_define(mixed);
  EXPECT_NE(d.find("#define OCCLUDER_TRANSMISSIVE_SPHERES OCCLUDER_TERM(0) OCCLUDER_TERM(1)\n"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("#define OCCLUDER_OPAQUE_SPHERES OCCLUDER_TERM(2)\n"), std::string::npos) << d;
  EXPECT_NE(d.find("#define OCCLUDER_TRANSMISSIVE_BOXES OCCLUDER_TERM(3)\n"), std::string::npos)
      << d;
  EXPECT_NE(d.find("#define OCCLUDER_OPAQUE_BOXES OCCLUDER_TERM(4) OCCLUDER_TERM(5)\n"),
            std::string::npos)
      << d;
  const std::string boxes = occluder_geometry_define(std::vector<Occluder>{proxy(false, false)});
  EXPECT_NE(boxes.find("#define OCCLUDER_TRANSMISSIVE_SPHERES\n"), std::string::npos) << boxes;
  EXPECT_NE(boxes.find("#define OCCLUDER_OPAQUE_BOXES\n"), std::string::npos) << boxes;
  EXPECT_NE(boxes.find("#define OCCLUDER_TRANSMISSIVE_BOXES OCCLUDER_TERM(0)\n"), std::string::npos)
      << boxes;
}

// More transmissive objects than a frame compiles in: the largest 16 of each kind are kept
// (and said once on stderr), and a frame with the most of both renders finite.
TEST(TransmissiveShadows, AFrameKeepsTheLargestSixteenOfEachKind) {
  testing::context();
  std::vector<Occluder> many;
  for (int i = 0; i < 20; ++i) {
    Occluder sphere;
    sphere.sphere = true;
    sphere.radius = 0.1f + 0.01f * float(i);
    many.push_back(sphere);
    Occluder box;
    const float half = 0.1f + 0.01f * float(i);
    const glm::vec3 axes[3] = {glm::vec3(half, 0, 0), glm::vec3(0, half, 0), glm::vec3(0, 0, half)};
    box.faces = parallelepiped_faces(axes);
    box.slot = i;
    many.push_back(box);
  }
  glm::ivec2 counts;
  const std::vector<Occluder> kept = select_occluders(many, counts);
  EXPECT_EQ(counts, glm::ivec2(kMaxOccluders, kMaxOccluders));
  ASSERT_EQ(kept.size(), std::size_t(2 * kMaxOccluders));
  // Spheres first, radius 0.29 down to 0.14; then the boxes, half-size 0.29 down to 0.14.
  EXPECT_TRUE(kept[0].sphere);
  EXPECT_FLOAT_EQ(kept[0].radius, 0.29f);
  EXPECT_FLOAT_EQ(kept[15].radius, 0.14f);
  EXPECT_FALSE(kept[16].sphere);
  EXPECT_EQ(kept[16].slot, 19);
  EXPECT_EQ(kept[31].slot, 4);

  Scene scene;
  Material glass;
  glass.metallic_factor = 0.0f;
  glass.transmission = TransmissionExtension{1.0f, {}};
  Material floor;
  scene.materials = {floor, glass};
  add_mesh_instance(scene,
                    make_quad(glm::vec3(-6, 0, 6), glm::vec3(12, 0, 0), glm::vec3(0, 0, -12)), 0);
  for (int i = 0; i < 17; ++i) {
    const glm::mat4 at =
        glm::translate(glm::mat4(1.0f), glm::vec3(float(i % 6) - 2.5f, 0.5f, float(i / 6) - 1.0f));
    add_mesh_instance(scene, make_uv_sphere(0.2f, 16, 8), 1, at);
    add_mesh_instance(scene, make_box(glm::vec3(-0.1f), glm::vec3(0.1f)), 1,
                      glm::translate(at, glm::vec3(0.0f, 0.5f, 0.0f)));
  }
  Camera camera;
  camera.camera_to_world =
      glm::inverse(glm::lookAt(glm::vec3(0, 3, 6), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  const Environment env = Environment::constant(glm::vec3(1.0f));
  const IblMaps maps = testing::small_ibl_maps(env);
  RenderSettings settings;
  settings.msaa = 1;
  const Image image = render_headless(scene, camera, 64, 48, &env, &maps, settings);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(image.rgb(x, y)[k]));
}

}  // namespace
}  // namespace pbrkit::gl
