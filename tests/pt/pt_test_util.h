#pragma once
// Helpers shared by the path tracer's tests: small scenes, a deterministic quadrature of
// the BRDF's directional albedo (the closed forms the renders are checked against), and a
// t-test on per-pixel residuals (so tolerances come from the measured noise, not guesses).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/math.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/primitives.h"

namespace pbrkit::test {

inline Material make_material(glm::vec3 base, float metallic, float roughness,
                              glm::vec3 emissive = glm::vec3(0.0f), bool double_sided = false) {
  Material m;
  m.base_color_factor = glm::vec4(base, 1.0f);
  m.metallic_factor = metallic;
  m.roughness_factor = roughness;
  m.emissive_factor = emissive;
  m.double_sided = double_sided;
  return m;
}

/// An orthographic camera at (0, 0, z) looking down -Z with half extent `half`.
inline Camera ortho_camera(float half, float z = 5.0f) {
  Camera c;
  c.type = Camera::Type::kOrthographic;
  c.xmag = c.ymag = half;
  c.znear = 0.01f;
  c.camera_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, z));
  return c;
}

/// Directional albedo a(mu) = int f(wo, wi) cos(theta_i) dwi of the model's BRDF at
/// wo = (sqrt(1 - mu^2), 0, mu), by a deterministic midpoint rule in (cos theta_i, phi)
/// (dense enough that its error is far below the render noise).
inline double directional_albedo(const Brdf& brdf, double mu, int n = 256) {
  const glm::vec3 wo(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu));
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = (i + 0.5) / n;  // cos theta_i
    const double s = std::sqrt(1.0 - c * c);
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) / (2 * n) * 2.0 * kPi;
      const glm::vec3 wi(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
      const glm::vec3 f = brdf.eval(wo, wi);
      sum += double(f.x) * c;  // red channel; tests use grey materials
    }
  }
  return sum * (1.0 / n) * (2.0 * kPi / (2 * n));
}

/// Result of a t-test on residuals r_i = value_i - expected_i, independent across pixels.
struct ResidualStats {
  double mean = 0.0, std_error = 0.0, max_abs = 0.0;
  std::size_t n = 0;
};
inline ResidualStats residual_stats(const std::vector<double>& r) {
  ResidualStats s;
  s.n = r.size();
  if (r.empty()) return s;
  for (double x : r) s.mean += x;
  s.mean /= double(r.size());
  double var = 0.0;
  for (double x : r) {
    var += (x - s.mean) * (x - s.mean);
    s.max_abs = std::max(s.max_abs, std::fabs(x));
  }
  var /= double(std::max<std::size_t>(r.size() - 1, 1));
  s.std_error = std::sqrt(var / double(r.size()));
  return s;
}

// a(mu) tabulated on [0,1] for interpolation (the quadrature is too slow per pixel).
struct AlbedoTable {
  std::vector<double> a;
  AlbedoTable() = default;
  explicit AlbedoTable(const Brdf& brdf, int n = 32) {
    for (int i = 0; i <= n; ++i)
      a.push_back(directional_albedo(brdf, std::max(i, 1) / double(n), 96));
  }
  template <typename F>
  static AlbedoTable from(F f, int n = 64) {
    AlbedoTable t;
    for (int i = 0; i <= n; ++i) t.a.push_back(f(i / double(n)));
    return t;
  }
  double operator()(double mu) const {
    const double x = std::clamp(mu, 0.0, 1.0) * double(a.size() - 1);
    const std::size_t i = std::min(std::size_t(x), a.size() - 2);
    const double f = x - double(i);
    return a[i] * (1.0 - f) + a[i + 1] * f;
  }
};

inline Scene sphere_scene(const Material& m) {
  Scene scene;
  scene.source = "test:sphere";
  scene.materials.push_back(m);
  add_mesh_instance(scene, make_uv_sphere(1.0f, 128, 64), 0);
  return scene;
}

// Residuals of an orthographic render of the unit sphere against L * a(n.z), for pixels
// whose whole footprint is on the sphere (box filter: the pixel value is the footprint
// average, which the expectation averages over 4x4 points).
inline std::vector<double> sphere_residuals(const Image& image, float half, double L,
                                            const AlbedoTable& albedo, float max_radius,
                                            float min_mu = 0.0f, float max_mu = 1.0f) {
  std::vector<double> r;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double expected = 0.0;
      bool inside = true;
      float mu_c = 0.0f;
      for (int j = 0; j < 4 && inside; ++j)
        for (int i = 0; i < 4 && inside; ++i) {
          const float X = ((float(x) + (float(i) + 0.5f) / 4.0f) / float(w) * 2.0f - 1.0f) * half;
          const float Y = (1.0f - (float(y) + (float(j) + 0.5f) / 4.0f) / float(h) * 2.0f) * half;
          const float r2 = X * X + Y * Y;
          if (r2 > max_radius * max_radius) inside = false;
          expected += L * albedo(std::sqrt(std::max(0.0f, 1.0f - r2))) / 16.0;
          mu_c = std::sqrt(std::max(0.0f, 1.0f - r2));
        }
      if (!inside || mu_c < min_mu || mu_c > max_mu) continue;
      r.push_back(double(image.rgb(x, y).x) - expected);
    }
  return r;
}

/// The path tracer's tests render through this: pbrkit::render_path, then a test failure if
/// any sample's radiance was not finite (the integrator drops it to 0, which would show only
/// as a darkening that a tolerance might absorb) or any path overflowed the medium stack.
/// It is an object, not a function: an unqualified render_path(...) in namespace
/// pbrkit::test finds it, and because it is not a function, argument-dependent lookup does
/// not add pbrkit::render_path ([basic.lookup.argdep]/3), so every test's renders are
/// checked. A test that expects such samples calls pbrkit::render_path itself.
struct CheckedRenderPath {
  PathTracerResult operator()(const Scene& scene, const Environment* env, const Camera& camera,
                              const PathTracerSettings& settings,
                              const ProgressCallback& progress = {}) const {
    PathTracerResult r = pbrkit::render_path(scene, env, camera, settings, progress);
    EXPECT_EQ(r.stats.non_finite_samples, 0u)
        << scene.source << ": samples whose radiance was not finite";
    EXPECT_EQ(r.stats.medium_overflows, 0u)
        << scene.source << ": paths deeper than the medium stack";
    return r;
  }
};
inline constexpr CheckedRenderPath render_path{};

inline PathTracerSettings small_settings(int size, std::uint32_t spp) {
  PathTracerSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.noise_threshold = 0.0f;
  s.filter = PixelFilter::kBox;
  s.threads = 2;
  return s;
}

}  // namespace pbrkit::test
