// Image comparison metrics on tiny synthetic images whose values are computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/image/compare.h"
#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

// A = [(1,1,1), (0,0,0), (0.2,0.4,0.6)], B = [(0.5,0.5,0.5), (0,0,0), (0.2,0.4,0.6)].
struct Fixture {
  Image a{3, 1, 3}, b{3, 1, 3};
  Fixture() {
    a.set_rgb(0, 0, glm::vec3(1.0f));
    b.set_rgb(0, 0, glm::vec3(0.5f));
    a.set_rgb(2, 0, glm::vec3(0.2f, 0.4f, 0.6f));
    b.set_rgb(2, 0, glm::vec3(0.2f, 0.4f, 0.6f));
  }
};

TEST(Compare, MetricsMatchHandComputedValues) {
  Fixture f;
  const CompareMetrics m = compare_images(f.a, f.b);
  // 9 samples: three differ by 0.5, six are equal.
  EXPECT_EQ(m.pixels, 3u);
  EXPECT_NEAR(m.mse, 3 * 0.25 / 9, 1e-9);
  EXPECT_NEAR(m.rmse, std::sqrt(0.75 / 9), 1e-9);
  EXPECT_NEAR(m.psnr, 10 * std::log10(9 / 0.75), 1e-9);  // peak 1
  EXPECT_NEAR(m.relative_mse, 3 * (0.25 / (0.25 + 0.01)) / 9, 1e-9);
  EXPECT_NEAR(m.mean_relative_error, 3 * (0.5 / (0.5 + 0.01)) / 9, 1e-9);
}

TEST(Compare, MaskSelectsPixels) {
  Fixture f;
  Image mask(3, 1, 1, 0.0f);
  mask.pixel(0, 0)[0] = 1.0f;
  CompareMetrics m = compare_images(f.a, f.b, &mask);
  EXPECT_EQ(m.pixels, 1u);
  EXPECT_NEAR(m.mse, 0.25, 1e-9);
  EXPECT_NEAR(m.psnr, 10 * std::log10(4.0), 1e-9);
  EXPECT_NEAR(m.mean_relative_error, 0.5 / 0.51, 1e-9);
  // Only identical pixels selected: zero error, infinite PSNR.
  mask.pixel(0, 0)[0] = 0.0f;
  mask.pixel(2, 0)[0] = 0.3f;
  m = compare_images(f.a, f.b, &mask);
  EXPECT_EQ(m.mse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
  // A mask that selects nothing is an error.
  Image none(3, 1, 1, 0.0f);
  EXPECT_THROW(compare_images(f.a, f.b, &none), Error);
}

TEST(Compare, SizeMismatchIsAClearError) {
  Fixture f;
  const Image other(2, 2, 3);
  try {
    compare_images(f.a, other, nullptr, "render.exr", "ref.exr");
    FAIL();
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("render.exr is 3 x 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ref.exr is 2 x 2"), std::string::npos) << msg;
  }
  const Image bad_mask(1, 1, 1, 1.0f);
  EXPECT_THROW(compare_images(f.a, f.b, &bad_mask), Error);
}

TEST(Compare, GreyAndRgbImagesCompareChannelWise) {
  Image grey(1, 1, 1, 0.25f);
  Image rgb(1, 1, 3);
  rgb.set_rgb(0, 0, glm::vec3(0.25f, 0.25f, 0.75f));
  const CompareMetrics m = compare_images(grey, rgb);
  EXPECT_NEAR(m.mse, 0.25 / 3, 1e-9);
}

TEST(Compare, HeatmapUsesTheViridisRampAndScale) {
  Fixture f;
  const Image err = relative_error_image(f.a, f.b);
  ASSERT_EQ(err.channels, 1);
  EXPECT_NEAR(err.pixel(0, 0)[0], 0.5 / 0.51, 1e-6);
  EXPECT_EQ(err.pixel(1, 0)[0], 0.0f);
  Image mask(3, 1, 1, 1.0f);
  mask.pixel(2, 0)[0] = 0.0f;
  const Image heat = error_heatmap(err, 0.5f, &mask);
  ASSERT_EQ(heat.channels, 3);
  // Error 0.98 > scale 0.5: top of the ramp (viridis yellow 253,231,37).
  EXPECT_NEAR(heat.rgb(0, 0).r, 253 / 255.0f, 1e-6);
  EXPECT_NEAR(heat.rgb(0, 0).b, 37 / 255.0f, 1e-6);
  // Error 0: bottom of the ramp (68,1,84).
  EXPECT_NEAR(heat.rgb(1, 0).g, 1 / 255.0f, 1e-6);
  // Masked out: mid grey.
  EXPECT_EQ(heat.rgb(2, 0), glm::vec3(0.5f));
  // Half way: the middle sample of the 9-point ramp (33,144,141).
  EXPECT_NEAR(viridis(0.5f).g, 144 / 255.0f, 1e-6);
  EXPECT_THROW(error_heatmap(err, 0.0f), Error);
}

}  // namespace
}  // namespace pbrkit
