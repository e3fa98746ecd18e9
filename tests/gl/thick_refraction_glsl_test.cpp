// thick_refraction.glsl evaluated on the GPU (llvmpipe in CI) against closed forms of a ray
// through a sphere and a plane, written here in double: a ray entering a sphere at impact
// parameter b = sin(theta_i) leaves it deviated by 2 (theta_i - theta_t) towards the axis
// (Snell at both interfaces; the chord inside subtends pi - 2 theta_t at the centre and is
// 2 R cos(theta_t) long), and a ray inside glass meeting a face beyond the critical angle
// asin(1 / ior) is reflected at the angle it came in.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/harness/transmission_eval.h"
#include "gl_test_context.h"

namespace pbrkit::gl {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit sphere at the origin seen along -z (v = +z): the entry point at impact parameter b
// in azimuth phi, with the plane of incidence's unit vectors e (outwards, in the xy plane)
// and z, and the angles of Snell's law.
struct SphereRay {
  glm::dvec3 e, entry;
  double theta_i, theta_t;
};

SphereRay sphere_ray(double b, double phi, double ior) {
  SphereRay r;
  r.e = glm::dvec3(std::cos(phi), std::sin(phi), 0.0);
  r.theta_i = std::asin(b);
  r.theta_t = std::asin(b / ior);
  r.entry = b * r.e + std::sqrt(1.0 - b * b) * glm::dvec3(0, 0, 1);
  return r;
}

// The point of the unit sphere at polar angle beta from +z towards +e.
glm::dvec3 on_sphere(const SphereRay& r, double beta) {
  return std::sin(beta) * r.e + std::cos(beta) * glm::dvec3(0, 0, 1);
}

TEST(ThickRefractionGlsl, TwoRefractionsThroughASphereDeviateByTwiceThetaIMinusThetaT) {
  testing::context();
  std::vector<TransmissionCase> cases;
  std::vector<glm::dvec3> expected;
  for (double ior : {1.1, 1.33, 1.5, 1.8, 2.4})
    for (double b : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99})
      for (double phi : {0.0, 1.0, 2.5, 4.0}) {
        const SphereRay r = sphere_ray(b, phi, ior);
        TransmissionCase c;
        c.n = glm::vec3(r.entry);
        c.v = glm::vec3(0, 0, 1);
        c.ior = float(ior);
        // The exit point: the chord turns pi - 2 theta_t about the centre, onwards from the
        // entry's polar angle theta_i (at ior 1, pi - theta_i: straight down).
        c.back_normal = glm::vec3(on_sphere(r, kPi + r.theta_i - 2.0 * r.theta_t));
        cases.push_back(c);
        const double delta = 2.0 * (r.theta_i - r.theta_t);
        expected.push_back(-std::sin(delta) * r.e - std::cos(delta) * glm::dvec3(0, 0, 1));
      }
  const auto got = eval_transmission_glsl(cases, TransmissionFunction::kRefractTwice);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    // A sphere never traps light: the exit angle equals the entry's, below the critical one.
    EXPECT_EQ(got[i].w, 0.0f) << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[i][k], expected[i][k], 2e-5) << i << " " << k;
  }
}

// Inside glass, a ray meeting the face at angle theta from its normal: below the critical
// angle it leaves with sin(theta_out) = ior sin(theta); past it, it is reflected inside at
// theta. The face is z = 0 with outward normal +z; the ray is set up by refract_twice's
// entry at a face parallel to the view (normal v: no bending), so t1 = -v.
TEST(ThickRefractionGlsl, TheBackFaceRefractsOrReflectsPastTheCriticalAngle) {
  testing::context();
  std::vector<TransmissionCase> cases;
  std::vector<double> angles;
  const double ior = 1.5, critical = std::asin(1.0 / ior);
  for (double theta = 0.0; theta < 1.5; theta += 0.05) {
    TransmissionCase c;
    // t1 = -v points up and sideways, at theta from +z.
    c.v = -glm::vec3(float(std::sin(theta)), 0.0f, float(std::cos(theta)));
    c.n = c.v;  // entry at normal incidence: t1 = -v exactly
    c.ior = float(ior);
    c.back_normal = glm::vec3(0, 0, 1);
    cases.push_back(c);
    angles.push_back(theta);
  }
  const auto got = eval_transmission_glsl(cases, TransmissionFunction::kRefractTwice);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const double theta = angles[i];
    const glm::dvec3 d(got[i]);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-5) << theta;
    EXPECT_NEAR(d.y, 0.0, 1e-6) << theta;  // in the plane of incidence
    if (std::abs(theta - critical) < 1e-3) continue;
    if (theta < critical) {
      EXPECT_EQ(got[i].w, 0.0f) << theta;
      EXPECT_GT(d.z, 0.0) << theta;  // out through the face
      EXPECT_NEAR(d.x, ior * std::sin(theta), 2e-5) << theta;
    } else {
      EXPECT_EQ(got[i].w, 1.0f) << theta;
      EXPECT_NEAR(d.z, -std::cos(theta), 2e-5) << theta;  // back inside, at theta
      EXPECT_NEAR(d.x, std::sin(theta), 2e-5) << theta;
    }
  }
}

// Wyman's distance estimate and its refinement against the chord through a unit sphere seen
// along -z (an orthographic view: the back face "at the same pixel" as a point is the back
// hemisphere's point with the same x and y). The estimate blends d_v = 2 cos(theta_i) and
// d_n = 2 (the diameter, the material's thickness) and is short of the chord 2 cos(theta_t)
// by up to 16% at b = 0.9 (Wyman 2005's approximation, computed in double); each
// back_plane_distance step meets the plane of the back face seen at the estimate, which for
// a sphere converges quadratically (Newton's method on the sphere): in double the relative
// error after one step is below 6e-3 and after two below 1e-5 for b <= 0.9, so two steps
// reach the chord within float rounding (1e-4 here).
TEST(ThickRefractionGlsl, WymanEstimateRefinedByTheBackFacePlaneReachesTheSphereChord) {
  testing::context();
  const double ior = 1.5;
  std::vector<double> bs = {0.05, 0.2, 0.4, 0.6, 0.75, 0.9};
  std::vector<SphereRay> rays;
  std::vector<glm::dvec3> t1s;
  std::vector<TransmissionCase> cases;
  for (double b : bs) {
    const SphereRay r = sphere_ray(b, 0.7, ior);
    rays.push_back(r);
    // The refracted direction in the plane of incidence: theta_t from -n.
    const double beta = r.theta_i + kPi - 2.0 * r.theta_t;  // exit polar angle
    t1s.push_back(glm::normalize(on_sphere(r, beta) - r.entry));
    TransmissionCase c;
    c.n = glm::vec3(r.entry);
    c.v = glm::vec3(0, 0, 1);
    c.ior = float(ior);
    c.distance = float(2.0 * std::cos(r.theta_i));  // d_v
    c.thickness = 2.0f;                             // d_n
    cases.push_back(c);
  }
  const auto wyman = eval_transmission_glsl(cases, TransmissionFunction::kWymanDistance);
  std::vector<double> d(bs.size());
  for (std::size_t i = 0; i < bs.size(); ++i) {
    const double chord = 2.0 * std::cos(rays[i].theta_t);
    d[i] = wyman[i].x;
    EXPECT_LE(d[i], chord * (1.0 + 1e-5)) << bs[i];
    EXPECT_GE(d[i], chord * 0.84) << bs[i];
  }
  const double bounds[] = {6e-3, 1e-4};
  for (double bound : bounds) {
    std::vector<TransmissionCase> step;
    for (std::size_t i = 0; i < bs.size(); ++i) {
      const glm::dvec3 x = rays[i].entry + d[i] * t1s[i];
      const glm::dvec3 back(x.x, x.y, -std::sqrt(std::max(0.0, 1.0 - x.x * x.x - x.y * x.y)));
      TransmissionCase c;
      c.n = glm::vec3(rays[i].entry);  // the ray's origin
      c.v = glm::vec3(t1s[i]);         // its direction
      c.distance = float(d[i]);
      c.back_point = glm::vec3(back);
      c.back_normal = glm::vec3(back);
      step.push_back(c);
    }
    const auto got = eval_transmission_glsl(step, TransmissionFunction::kBackPlaneDistance);
    for (std::size_t i = 0; i < bs.size(); ++i) {
      const double chord = 2.0 * std::cos(rays[i].theta_t);
      d[i] = got[i].x;
      EXPECT_NEAR(d[i] / chord, 1.0, bound) << bs[i];
    }
  }
}

// The frame of the search tests: a floor (y = 0, 20 x 20) seen from above by a 60-degree
// camera into a 256 x 256 depth buffer written here, with each floor texel's colour its
// world position (w = 1; the background 0).
constexpr int kSize = 256;
constexpr double kFov = 60.0 * kPi / 180.0;
struct FloorFrame {
  glm::vec3 eye{0.0f, 1.5f, 3.0f};
  glm::mat4 vp;
  FrameDepth depth{kSize, kSize, std::vector<float>(std::size_t(kSize) * kSize, 1.0f)};
  std::vector<glm::vec4> position = std::vector<glm::vec4>(std::size_t(kSize) * kSize);
  static bool on_floor(glm::dvec3 p) { return std::abs(p.x) <= 10.0 && std::abs(p.z) <= 10.0; }
  FloorFrame() {
    vp = glm::perspective(float(kFov), 1.0f, 0.1f, 100.0f) *
         glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 inverse_vp = glm::inverse(vp);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const glm::vec2 ndc((x + 0.5f) / kSize * 2.0f - 1.0f, (y + 0.5f) / kSize * 2.0f - 1.0f);
        glm::vec4 far = inverse_vp * glm::vec4(ndc, 1.0f, 1.0f);
        const glm::dvec3 dir = glm::normalize(glm::dvec3(far) / double(far.w) - glm::dvec3(eye));
        if (dir.y >= 0.0) continue;
        const glm::dvec3 p = glm::dvec3(eye) - double(eye.y) / dir.y * dir;
        if (!on_floor(p)) continue;
        const glm::vec4 clip = vp * glm::vec4(glm::vec3(p), 1.0f);
        const std::size_t i = std::size_t(y) * kSize + std::size_t(x);
        depth.depth[i] = clip.z / clip.w * 0.5f + 0.5f;
        position[i] = glm::vec4(glm::vec3(p), 1.0f);
      }
  }
  /// Where `p` projects, in texture coordinates.
  glm::dvec2 uv(glm::dvec3 p) const {
    const glm::vec4 clip = vp * glm::vec4(glm::vec3(p), 1.0f);
    return glm::dvec2(clip.x, clip.y) / double(clip.w) * 0.5 + 0.5;
  }
  /// One texel's width on the floor at `hit`: its angle times the distance, over the cosine
  /// of the view ray with the floor's normal.
  double footprint(glm::dvec3 hit) const {
    const glm::dvec3 w = glm::normalize(hit - glm::dvec3(eye));
    return 2.0 * std::tan(kFov / 2.0) / kSize * glm::length(hit - glm::dvec3(eye)) / std::abs(w.y);
  }
};

// The rays of the march and reflection tests, in every direction from points above the
// floor: origins at x, z in {-1, 0, 1} and heights 0.1 and 0.5, elevations -85 to 30
// degrees in steps of 5, azimuths every 30 degrees; f(origin, unit direction) for each.
template <class F>
void for_each_ray_above_floor(F&& f) {
  for (double x : {-1.0, 0.0, 1.0})
    for (double z : {-1.0, 0.0, 1.0})
      for (double height : {0.1, 0.5})
        for (int el = -85; el <= 30; el += 5)
          for (int az = 0; az < 360; az += 30) {
            const double a = el * kPi / 180.0, b = az * kPi / 180.0;
            f(glm::dvec3(x, height, z),
              glm::dvec3(std::cos(a) * std::sin(b), std::sin(a), std::cos(a) * std::cos(b)));
          }
}

// frame_hit against the closed form of a ray meeting a plane: a floor (y = 0, 20 x 20) seen
// from above in a depth buffer written here, rays from points above it. The search iterates
// d <- g(d), the distance to the frame's surface point seen where the ray's point at d
// projects; on a plane of normal n, with e the ray and w the unit view direction to its hit,
// g'(d*) = 1 - (n.e)(e.w) / (n.w), so it contracts where |g'| < 1 and oscillates beyond. Where
// |g'| <= 1/2, four steps shrink the first one's error 16-fold, and what remains is the depth
// buffer's own: up to a texel's footprint on the floor, 1 / (1 - |g'|) times along the fixed
// point (measured: errors at most 0.43 of that bound, 0.73 footprints). A ray whose hit is
// off the screen or off the floor, or that rises into the background, meets nothing.
TEST(ThickRefractionGlsl, FrameSearchMeetsAFloorWhereItsFixedPointContracts) {
  testing::context();
  const FloorFrame frame;
  const glm::mat4& vp = frame.vp;
  const glm::vec3 eye = frame.eye;
  auto on_floor = FloorFrame::on_floor;
  const FrameDepth& depth = frame.depth;
  struct Expected {
    bool meets;  ///< the floor, on the screen
    double t, slope, footprint;
  };
  std::vector<TransmissionCase> cases;
  std::vector<Expected> expected;
  const glm::dvec3 n(0.0, 1.0, 0.0);
  for (double x : {-1.0, 0.0, 1.0})
    for (double z : {-1.0, 0.0, 1.0})
      for (double down : {-0.8, 0.0, 0.1, 0.2, 0.4, 0.7, 1.2})
        for (double side : {-0.5, 0.0, 0.5}) {
          const glm::dvec3 origin(x, 0.4, z);
          const glm::dvec3 view = glm::normalize(origin - glm::dvec3(eye));
          const glm::dvec3 across = glm::normalize(glm::cross(view, n));
          const glm::dvec3 e = glm::normalize(view + down * -n + side * across);
          TransmissionCase c;
          c.n = glm::vec3(origin);
          c.v = glm::vec3(e);
          cases.push_back(c);
          if (e.y >= 0.0) {  // rising: only the background lies ahead
            expected.push_back({false, 0.0, 0.0, 0.0});
            continue;
          }
          const double t = -origin.y / e.y;
          const glm::dvec3 hit = origin + t * e;
          const glm::vec4 clip = vp * glm::vec4(glm::vec3(hit), 1.0f);
          const glm::dvec2 uv = glm::dvec2(clip.x, clip.y) / double(clip.w) * 0.5 + 0.5;
          // A texel inside the edges either way: the search's last projection may round to
          // the other side of an edge.
          const double margin = 2.0 / kSize;
          const bool inside = std::min(uv.x, uv.y) > margin && std::max(uv.x, uv.y) < 1.0 - margin;
          const bool outside =
              std::min(uv.x, uv.y) < -margin || std::max(uv.x, uv.y) > 1.0 + margin;
          if (!inside && !outside) {
            cases.pop_back();
            continue;
          }
          const glm::dvec3 w = glm::normalize(hit - glm::dvec3(eye));
          const double slope = 1.0 - glm::dot(n, e) * glm::dot(e, w) / glm::dot(n, w);
          expected.push_back({inside && on_floor(hit), t, slope, frame.footprint(hit)});
        }
  const auto got = eval_frame_hit_glsl(cases, depth, vp);
  int contracting = 0, missed = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Expected& want = expected[i];
    if (!want.meets) {
      EXPECT_EQ(got[i].w, 0.0f) << "case " << i << ": no surface on the screen to meet";
      ++missed;
      continue;
    }
    if (std::abs(want.slope) > 0.5) continue;
    ++contracting;
    EXPECT_EQ(got[i].w, 1.0f) << "case " << i;
    EXPECT_NEAR(got[i].z, want.t, want.footprint / (1.0 - std::abs(want.slope)))
        << "case " << i << ", g' " << want.slope;
  }
  EXPECT_GE(contracting, 100);
  EXPECT_GE(missed, 20);
}

// frame_march against the closed form of a ray meeting the floor of FloorFrame: rays in
// every direction from points above it. Unlike frame_hit's fixed point, the march finds the
// floor whatever the ray's angle to the view direction: every ray whose hit lies on the
// floor and on the screen is found, at a distance within the last step's bisected bracket
// (the march's longest step, (2 x 12 - 1) / 12^2 of the ray's on-screen length, halved four
// times) plus the depth buffer's texel along the ray; and no rising ray, nor one whose hit
// is off the screen or off the floor, finds anything. The on-screen length is found here by
// stepping the ray's projection, not by the shader's frustum planes.
TEST(ThickRefractionGlsl, MarchMeetsTheFloorAtAnyAngle) {
  testing::context();
  const FloorFrame frame;
  struct Expected {
    int meets;  ///< 1: the floor on the screen; 0: nothing; -1: at an edge, either
    double t, bound;
  };
  std::vector<TransmissionCase> cases;
  std::vector<Expected> expected;
  for_each_ray_above_floor([&](glm::dvec3 origin, glm::dvec3 e) {
    auto on_screen = [&](double d) {
      const glm::dvec3 p = origin + d * e;
      const glm::vec4 clip = frame.vp * glm::vec4(glm::vec3(p), 1.0f);
      const glm::dvec2 uv = frame.uv(p);
      return clip.w > 0.0f && uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
    };
    double length = 0.0;  // where the ray leaves the screen, to 1e-3 (or 200)
    while (length < 200.0 && on_screen(length + 1e-3)) length += 1e-3;
    Expected want{0, 0.0, 0.0};
    // A nearly level ray passes the floor's far part within its depth texels'
    // resolution (one texel there spans half a unit of floor at a grazing angle):
    // either answer.
    if (e.y >= 0.0 && e.y < 0.05) want.meets = -1;
    if (e.y < 0.0) {
      want.t = -origin.y / e.y;
      const glm::dvec3 hit = origin + want.t * e;
      const glm::dvec2 uv = frame.uv(hit);
      const double margin = 2.0 / kSize;
      const bool inside = std::min(uv.x, uv.y) > margin && std::max(uv.x, uv.y) < 1.0 - margin;
      const bool far_inside = std::abs(hit.x) < 9.9 && std::abs(hit.z) < 9.9;
      want.bound = length * 23.0 / (144.0 * 16.0) + 2.0 * frame.footprint(hit) / std::abs(e.y);
      // Met where the ray goes on under the floor, by more than the bound, before it
      // leaves the screen; a ray that leaves it just past the hit is below the floor
      // by less than a depth texel's resolution there: either answer.
      if (inside && far_inside && want.t + want.bound < length)
        want.meets = 1;
      else if (inside || std::abs(want.t - length) < 0.05 * want.t + want.bound)
        want.meets = -1;  // at the screen's or the floor's edge
    }
    TransmissionCase c;
    c.n = glm::vec3(origin);
    c.v = glm::vec3(e);
    cases.push_back(c);
    expected.push_back(want);
  });
  const auto got = eval_frame_march_glsl(cases, frame.depth, frame.vp);
  int found = 0, none = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Expected& want = expected[i];
    if (want.meets < 0) continue;
    if (want.meets == 0) {
      EXPECT_EQ(got[i].w, 0.0f) << "case " << i << ": nothing to meet on the screen";
      none += got[i].w == 0.0f;
      continue;
    }
    EXPECT_EQ(got[i].w, 1.0f) << "case " << i << ", t " << want.t;
    if (got[i].w != 1.0f) continue;
    ++found;
    worst = std::max(worst, std::abs(got[i].z - want.t) / want.bound);
    EXPECT_NEAR(got[i].z, want.t, want.bound) << "case " << i;
  }
  std::printf(
      "frame_march: %zu rays, %d meet the floor on the screen and found it (worst error "
      "%.2f of its bound), %d meet nothing and found nothing\n",
      cases.size(), found, worst, none);
  EXPECT_GE(found, 1500);
  EXPECT_GE(none, 1400);
}

// reflected_frame against the closed form of a ray meeting the floor of FloorFrame, whose
// colours are its world positions: rays in every direction from points above the floor.
// Where it reads the frame, the search has settled within kSettledTolerance = 10% of its
// distance d onto the floor, so its ray point lies at most 0.1 d from the floor and the
// point read at most 0.1 d (1 + 1 / |e_y|) from the exact hit (moved along the ray onto
// the floor), plus the depth buffer's and the bilinear read's texel footprints; that holds
// too for a ray that meets the floor's plane just off the screen or off the floor, which may
// read the floor's edge within that bound. A rising ray, one that meets the plane far off
// the screen or the floor, or behind the camera must read nothing: the environment is what
// the surface reflects then. Where
// the floor is there, frame_hit's fixed point settles for most rays close to the view
// direction and for few across it (alone, within 5%: 77% of the rays within 40 degrees of the
// view direction, 38% of those 40-80 degrees off, 3% beyond); frame_march, where it has not
// settled, reads the floor for most of the others (together, within 10%, measured: 92%, 78%,
// 80%). The rest reflect the environment.
TEST(ThickRefractionGlsl, ReflectionReadsTheFloorWhereTheMirrorRayMeetsIt) {
  testing::context();
  const FloorFrame frame;
  struct Expected {
    bool may_meet;  ///< the floor, on the screen
    bool near;      ///< the floor's plane, off the screen or the floor by at most the bound
    glm::dvec3 hit;
    double t, ey, footprint, angle;  ///< angle: between the ray and the view direction
  };
  std::vector<TransmissionCase> cases;
  std::vector<Expected> expected;
  for_each_ray_above_floor([&](glm::dvec3 origin, glm::dvec3 e) {
    TransmissionCase c;
    c.n = glm::vec3(origin);
    c.v = glm::vec3(e);
    Expected want{false, false, glm::dvec3(0.0), 0.0, e.y, 0.0, 0.0};
    if (e.y < 0.0) {
      want.t = -origin.y / e.y;
      want.hit = origin + want.t * e;
      const glm::dvec2 uv = frame.uv(want.hit);
      const double margin = 2.0 / kSize;
      const bool inside = std::min(uv.x, uv.y) > margin && std::max(uv.x, uv.y) < 1.0 - margin;
      const bool outside = std::min(uv.x, uv.y) < -margin || std::max(uv.x, uv.y) > 1.0 + margin;
      if (!inside && !outside) return;  // at the screen's edge either way
      const glm::dvec3 w = glm::normalize(want.hit - glm::dvec3(frame.eye));
      want.may_meet = inside && FloorFrame::on_floor(want.hit) &&
                      glm::dot(glm::dvec3(frame.eye) - origin, w) < 0.0;
      want.footprint = frame.footprint(want.hit);
      want.angle = std::acos(std::clamp(glm::dot(w, e), -1.0, 1.0)) * 180.0 / kPi;
      // The floor's plane in front of the camera, off the screen or the floor: a read
      // of the floor's edge must lie within the bound of the hit.
      want.near = !want.may_meet && glm::dot(glm::dvec3(frame.eye) - origin, w) < 0.0;
    }
    cases.push_back(c);
    expected.push_back(want);
  });
  const auto got = eval_reflected_frame_glsl(cases, frame.depth, frame.position, frame.vp);
  int none = 0, edge = 0;
  std::array<int, 3> meets{}, read{};  // within 40 degrees of the view direction, 40-80, beyond
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Expected& want = expected[i];
    const bool found = got[i].w == 1.0f;
    const double bound = 0.1 * want.t * (1.0 + 1.0 / std::abs(want.ey)) + 3.0 * want.footprint;
    const double error = glm::length(glm::dvec3(got[i]) - want.hit);
    if (!want.may_meet) {
      if (want.near && found) {
        EXPECT_LE(error, bound) << "case " << i << ": the floor's edge, t " << want.t;
        ++edge;
        continue;
      }
      EXPECT_FALSE(found) << "case " << i << ": no floor on the screen along the ray";
      none += !found;
      continue;
    }
    const std::size_t band = std::min<std::size_t>(2, std::size_t(want.angle / 40.0));
    ++meets[band];
    if (!found) continue;
    ++read[band];
    worst = std::max(worst, error / bound);
    EXPECT_LE(error, bound) << "case " << i << ", t " << want.t;
  }
  std::printf(
      "reflected_frame: %zu rays; of those that meet the floor on the screen, read it: %d of %d "
      "within 40 degrees of the view direction, %d of %d 40-80 degrees off, %d of %d beyond; "
      "worst error %.2f of its bound; %d read nothing as they must, %d the floor's edge\n",
      cases.size(), read[0], meets[0], read[1], meets[1], read[2], meets[2], worst, none, edge);
  EXPECT_GE(none, 1500);
  EXPECT_GE(read[0], 0.85 * meets[0]);
  EXPECT_GE(read[1], 0.7 * meets[1]);
  EXPECT_GE(read[2], 0.7 * meets[2]);
}

}  // namespace
}  // namespace pbrkit::gl
