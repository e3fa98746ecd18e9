// CameraRays (the path tracer's primary rays with the per-camera set-up hoisted) against
// generate_ray: the same bits for perspective and orthographic cameras, with and without
// their own aspect ratio.
#include <gtest/gtest.h>

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/camera_rays.h"

namespace pbrkit::test {
namespace {

bool same_bits(glm::vec3 a, glm::vec3 b) {
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

TEST(CameraRays, BitIdenticalToGenerateRay) {
  Camera perspective;
  perspective.yfov = 0.7f;
  perspective.camera_to_world = glm::inverse(
      glm::lookAt(glm::vec3(1.0f, 2.0f, 5.0f), glm::vec3(0.1f, 0.2f, -0.3f), glm::vec3(0, 1, 0)));
  Camera with_aspect = perspective;
  with_aspect.aspect_ratio = 1.7f;
  Camera ortho;
  ortho.type = Camera::Type::kOrthographic;
  ortho.xmag = 2.0f;
  ortho.ymag = 1.5f;
  ortho.camera_to_world = perspective.camera_to_world;
  Pcg32 rng(1);
  for (const Camera& camera : {perspective, with_aspect, ortho})
    for (float aspect : {1.0f, 1.333f})
      for (int i = 0; i < 10000; ++i) {
        const glm::vec2 ndc = 2.0f * rng.next_2d() - 1.0f;
        const Ray a = generate_ray(camera, aspect, ndc);
        const Ray b = CameraRays(camera, aspect).generate(ndc);
        ASSERT_TRUE(same_bits(a.origin, b.origin));
        ASSERT_TRUE(same_bits(a.direction, b.direction));
      }
}

}  // namespace
}  // namespace pbrkit::test
