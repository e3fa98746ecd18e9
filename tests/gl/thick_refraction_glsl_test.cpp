// thick_refraction.glsl evaluated on the GPU (llvmpipe in CI) against closed forms of a ray
// through a sphere and a plane, written here in double: a ray entering a sphere at impact
// parameter b = sin(theta_i) leaves it deviated by 2 (theta_i - theta_t) towards the axis
// (Snell at both interfaces; the chord inside subtends pi - 2 theta_t at the centre and is
// 2 R cos(theta_t) long), and a ray inside glass meeting a face beyond the critical angle
// asin(1 / ior) is reflected at the angle it came in.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "pbrkit/gl/testing/transmission_eval.h"

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

}  // namespace
}  // namespace pbrkit::gl
