// The pixel filters (pt/pixel_filter.h): the tent's inverse CDF against the tent's CDF
// written independently here, the box's support, and the filter names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pbrkit/pt/pixel_filter.h"
#include "pbrkit/util/error.h"

namespace pbrkit::test {
namespace {

// CDF of the density 1 - |x| on [-1, 1]: (1 + x)^2 / 2 below 0, 1 - (1 - x)^2 / 2 above.
double tent_cdf(double x) {
  return x < 0.0 ? 0.5 * (1.0 + x) * (1.0 + x) : 1.0 - 0.5 * (1.0 - x) * (1.0 - x);
}

TEST(PixelFilter, TentSamplesInvertTheTentCdf) {
  for (int i = 0; i <= 4096; ++i) {
    const float u = std::min(float(i) / 4096.0f, 0x1.fffffep-1f);  // [0, 1)
    const float x = sample_tent(u);
    ASSERT_GE(x, -1.0f);
    ASSERT_LE(x, 1.0f);
    EXPECT_NEAR(tent_cdf(x), u, 1e-6) << "u " << u;
  }
  EXPECT_EQ(sample_tent(0.5f), 0.0f);  // the median is the pixel centre
  for (float u : {0.1f, 0.3f, 0.45f})  // symmetric about the centre
    EXPECT_NEAR(sample_tent(u), -sample_tent(1.0f - u), 1e-6f);
}

TEST(PixelFilter, OffsetsStayInTheFilterSupport) {
  for (float ux : {0.0f, 0.25f, 0.5f, 0.999f})
    for (float uy : {0.0f, 0.75f, 0.999f}) {
      const glm::vec2 box = sample_pixel_filter(PixelFilter::kBox, {ux, uy});
      EXPECT_GE(box.x, -0.5f);
      EXPECT_LT(box.x, 0.5f);
      EXPECT_GE(box.y, -0.5f);
      EXPECT_LT(box.y, 0.5f);
      const glm::vec2 tent = sample_pixel_filter(PixelFilter::kTent, {ux, uy});
      EXPECT_EQ(tent.x, sample_tent(ux));
      EXPECT_EQ(tent.y, sample_tent(uy));
    }
}

TEST(PixelFilter, NamesParseAndUnknownIsAnError) {
  for (PixelFilter f : {PixelFilter::kBox, PixelFilter::kTent})
    EXPECT_EQ(parse_pixel_filter(pixel_filter_name(f)), f);
  EXPECT_EQ(pixel_filter_name(PixelFilter::kTent), "tent");
  EXPECT_EQ(parse_pixel_filter("box"), PixelFilter::kBox);
  EXPECT_THROW(parse_pixel_filter("gaussian"), Error);
  // The CLI's choices: every filter once, the default first.
  EXPECT_EQ(pixel_filter_names(), (std::vector<std::string>{"tent", "box"}));
  EXPECT_EQ(pixel_filter_names()[0], pixel_filter_name(PathTracerSettings{}.filter));
  for (const std::string& name : pixel_filter_names())
    EXPECT_EQ(pixel_filter_name(parse_pixel_filter(name)), name);
}

}  // namespace
}  // namespace pbrkit::test
