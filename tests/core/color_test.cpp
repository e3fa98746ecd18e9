// Colour: the sRGB transfer functions against IEC 61966-2-1's published constants, and
// each tone mapper against its published formula, transcribed again here in double
// precision (so a typo in one transcription shows up as a disagreement).
#include <gtest/gtest.h>

#include <cmath>

#include "pbrkit/core/color.h"
#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

using dvec3 = glm::dvec3;

TEST(Srgb, RoundTripOverUnitInterval) {
  for (int i = 0; i <= 20000; ++i) {
    const float x = i / 20000.0f;
    EXPECT_NEAR(srgb_decode(srgb_encode(x)), x, 1e-6f) << x;
    EXPECT_NEAR(srgb_encode(srgb_decode(x)), x, 1e-6f) << x;
  }
}

TEST(Srgb, ExactValuesAndBreakpoints) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_EQ(srgb_decode(0.0f), 0.0f);
  EXPECT_EQ(srgb_decode(1.0f), 1.0f);
  // Linear segment below the breakpoint: exactly 12.92 x.
  EXPECT_FLOAT_EQ(srgb_encode(0.001f), 0.01292f);
  EXPECT_FLOAT_EQ(srgb_decode(0.02f), 0.02f / 12.92f);
  // At the breakpoints both segments agree (to the precision of the published constants).
  const double lin_seg = 12.92 * 0.0031308;
  const double pow_seg = 1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055;
  EXPECT_NEAR(lin_seg, pow_seg, 1e-6);
  EXPECT_NEAR(srgb_encode(0.0031308f), lin_seg, 1e-6);
  EXPECT_NEAR(srgb_decode(0.04045f), 0.04045 / 12.92, 1e-7);
  // Just above the breakpoint: the power segment.
  EXPECT_NEAR(srgb_encode(0.01f), 1.055 * std::pow(0.01, 1.0 / 2.4) - 0.055, 1e-6);
  // Mid values (not a 2.2 gamma: 0.5^(1/2.2) = 0.7297 would fail).
  EXPECT_NEAR(srgb_encode(0.5f), 0.7353569831, 1e-6);
  EXPECT_NEAR(srgb_decode(0.5f), 0.2140411405, 1e-6);
  // Clamping outside [0,1], NaN -> 0.
  EXPECT_EQ(srgb_encode(-1.0f), 0.0f);
  EXPECT_EQ(srgb_encode(4.0f), 1.0f);
  EXPECT_EQ(srgb_encode(std::nanf("")), 0.0f);
  const glm::vec3 v = srgb_encode(glm::vec3(0.0f, 0.5f, 1.0f));
  EXPECT_NEAR(v.y, 0.7353569831, 1e-6);
}

TEST(Color, LuminanceAndExposure) {
  EXPECT_FLOAT_EQ(luminance(glm::vec3(1.0f)), 1.0f);
  EXPECT_FLOAT_EQ(luminance(glm::vec3(0, 1, 0)), 0.7152f);
  EXPECT_FLOAT_EQ(exposure_scale(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(exposure_scale(1.0f), 2.0f);
  EXPECT_FLOAT_EQ(exposure_scale(-2.0f), 0.25f);
  EXPECT_NEAR(exposure_scale(0.5f), std::sqrt(2.0), 1e-6);
}

TEST(ToneMap, NamesParseAndUnknownIsAnError) {
  for (const std::string& name : tone_mapper_names())
    EXPECT_EQ(tone_mapper_name(parse_tone_mapper(name)), name);
  EXPECT_EQ(parse_tone_mapper("agx"), ToneMapper::kAgx);
  try {
    parse_tone_mapper("reinhard");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("reinhard"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("pbr-neutral"), std::string::npos);
  }
}

TEST(ToneMap, NoneClamps) {
  const glm::vec3 out = tone_map(ToneMapper::kNone, glm::vec3(2.0f, -1.0f, 0.25f));
  EXPECT_EQ(out, glm::vec3(1.0f, 0.0f, 0.25f));
}

// Khronos PBR Neutral, from the specification's reference GLSL.
dvec3 pbr_neutral_reference(dvec3 c) {
  const double start = 0.8 - 0.04, desat = 0.15;
  const double x = std::min({c.x, c.y, c.z});
  const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  c -= dvec3(offset);
  const double peak = std::max({c.x, c.y, c.z});
  if (peak < start) return c;
  const double d = 1.0 - start;
  const double new_peak = 1.0 - d * d / (peak + d - start);
  c *= new_peak / peak;
  const double g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0);
  return c * (1.0 - g) + dvec3(new_peak) * g;
}

void expect_near(glm::vec3 got, dvec3 want, double tol, const char* what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << what << " channel " << i;
}

TEST(ToneMap, PbrNeutralMatchesPublishedFormula) {
  // Below the compression start the curve is the identity minus the 0.04 black offset.
  expect_near(tone_map(ToneMapper::kPbrNeutral, glm::vec3(0.5f)), dvec3(0.46), 1e-6, "grey 0.5");
  // Toe: offset x - 6.25 x^2 for a dark channel (x = 0.05 -> 0.034375).
  expect_near(tone_map(ToneMapper::kPbrNeutral, glm::vec3(0.05f, 0.2f, 0.3f)),
              dvec3(0.015625, 0.165625, 0.265625), 1e-6, "toe");
  // Hand-computed point above the compression start: (2, 1, 0.5) -> peak 1.96,
  // new peak 1 - 0.24^2 / 1.44 = 0.96, g = 1 - 1/1.15.
  {
    const double g = 1.0 - 1.0 / 1.15;
    const dvec3 scaled = dvec3(1.96, 0.96, 0.46) * (0.96 / 1.96);
    const dvec3 want = scaled * (1.0 - g) + dvec3(0.96) * g;
    expect_near(tone_map(ToneMapper::kPbrNeutral, glm::vec3(2.0f, 1.0f, 0.5f)), want, 1e-6, "hand");
  }
  for (dvec3 c : {dvec3(0.1, 0.7, 0.3), dvec3(0.9, 0.9, 0.9), dvec3(5, 2, 1), dvec3(100, 50, 3)})
    expect_near(tone_map(ToneMapper::kPbrNeutral, glm::vec3(c)), pbr_neutral_reference(c), 1e-5,
                "reference");
  // Very bright white approaches 1 without exceeding it.
  const glm::vec3 w = tone_map(ToneMapper::kPbrNeutral, glm::vec3(1e4f));
  EXPECT_GT(w.x, 0.999f);
  EXPECT_LE(w.x, 1.0f);
}

// Stephen Hill's ACES fit (BakingLab ACES.hlsl), matrices written row by row as published.
dvec3 aces_reference(dvec3 c) {
  const double in[3][3] = {
      {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
  const double out[3][3] = {
      {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
  dvec3 v, r;
  for (int i = 0; i < 3; ++i) v[i] = in[i][0] * c.x + in[i][1] * c.y + in[i][2] * c.z;
  for (int i = 0; i < 3; ++i)
    v[i] = (v[i] * (v[i] + 0.0245786) - 0.000090537) /
           (v[i] * (0.983729 * v[i] + 0.4329510) + 0.238081);
  for (int i = 0; i < 3; ++i)
    r[i] = std::clamp(out[i][0] * v.x + out[i][1] * v.y + out[i][2] * v.z, 0.0, 1.0);
  return r;
}

TEST(ToneMap, AcesMatchesHillFit) {
  for (double g : {0.18, 1.0}) {
    const dvec3 want = aces_reference(dvec3(g));
    expect_near(tone_map(ToneMapper::kAces, glm::vec3(float(g))), want, 1e-5, "grey");
  }
  // The matrices' rows sum to ~1, so grey stays (nearly) grey.
  const glm::vec3 mid = tone_map(ToneMapper::kAces, glm::vec3(0.18f));
  EXPECT_NEAR(mid.x, mid.y, 2e-3);
  EXPECT_NEAR(mid.y, mid.z, 2e-3);
  for (dvec3 c : {dvec3(0.5, 0.2, 0.05), dvec3(4, 1, 0.2), dvec3(0.01, 0.02, 0.5)})
    expect_near(tone_map(ToneMapper::kAces, glm::vec3(c)), aces_reference(c), 1e-5, "colour");
  EXPECT_EQ(tone_map(ToneMapper::kAces, glm::vec3(0.0f)), glm::vec3(0.0f));
  EXPECT_GT(tone_map(ToneMapper::kAces, glm::vec3(100.0f)).y, 0.99f);
}

// AgX base (polynomial formulation): inset, log2 in [-12.47393, 4.026069], 6th-order
// contrast polynomial, outset, 2.2 power.
dvec3 agx_reference(dvec3 c) {
  const double inset_cols[3][3] = {{0.842479062253094, 0.0423282422610123, 0.0423756549057051},
                                   {0.0784335999999992, 0.878468636469772, 0.0784336},
                                   {0.0792237451477643, 0.0791661274605434, 0.879142973793104}};
  const double outset_cols[3][3] = {{1.19687900512017, -0.0528968517574562, -0.0529716355144438},
                                    {-0.0980208811401368, 1.15190312990417, -0.0980434501171241},
                                    {-0.0990297440797205, -0.0989611768448433, 1.15107367264116}};
  const double min_ev = -12.47393, max_ev = 4.026069;
  dvec3 v(0.0);
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) v[row] += inset_cols[col][row] * c[col];
  for (int i = 0; i < 3; ++i) {
    const double x =
        (std::clamp(std::log2(std::max(v[i], 1e-10)), min_ev, max_ev) - min_ev) / (max_ev - min_ev);
    v[i] = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) -
           6.868 * std::pow(x, 3) + 0.4298 * x * x + 0.1191 * x - 0.00232;
  }
  dvec3 r(0.0);
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) r[row] += outset_cols[col][row] * v[col];
  for (int i = 0; i < 3; ++i) r[i] = std::clamp(std::pow(std::max(r[i], 0.0), 2.2), 0.0, 1.0);
  return r;
}

TEST(ToneMap, AgxMatchesPolynomialFormulation) {
  for (dvec3 c : {dvec3(0.18), dvec3(1.0), dvec3(0.5, 0.2, 0.05), dvec3(8, 3, 1)})
    expect_near(tone_map(ToneMapper::kAgx, glm::vec3(c)), agx_reference(c), 2e-5, "agx");
  // Black maps to ~0 (the polynomial's -0.00232 at x = 0 is clipped).
  const glm::vec3 black = tone_map(ToneMapper::kAgx, glm::vec3(0.0f));
  EXPECT_LT(std::max({black.x, black.y, black.z}), 1e-3f);
  // Monotonic along a grey ramp from -10 to +4 EV around mid grey (non-decreasing in the
  // clipped toe, strictly increasing from -8 EV), and never above 1.
  float prev = -1.0f;
  for (float ev = -10.0f; ev <= 4.0f; ev += 0.25f) {
    const float y = tone_map(ToneMapper::kAgx, glm::vec3(0.18f * std::exp2(ev))).y;
    if (ev >= -8.0f)
      EXPECT_GT(y, prev) << ev;
    else
      EXPECT_GE(y, prev) << ev;
    EXPECT_LE(y, 1.0f);
    prev = y;
  }
  // The outset matrix is the inverse of the inset one (AgX's round trip for in-gamut
  // colours): check with the published numbers.
  const double a[3][3] = {{0.842479062253094, 0.0784335999999992, 0.0792237451477643},
                          {0.0423282422610123, 0.878468636469772, 0.0791661274605434},
                          {0.0423756549057051, 0.0784336, 0.879142973793104}};
  const double b[3][3] = {{1.19687900512017, -0.0980208811401368, -0.0990297440797205},
                          {-0.0528968517574562, 1.15190312990417, -0.0989611768448433},
                          {-0.0529716355144438, -0.0980434501171241, 1.15107367264116}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += b[i][k] * a[k][j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-6);
    }
}

TEST(ToneMap, AllMappersStayInUnitRangeAndHandleBadInput) {
  for (const std::string& name : tone_mapper_names()) {
    const ToneMapper t = parse_tone_mapper(name);
    for (glm::vec3 c : {glm::vec3(0.0f), glm::vec3(1e-6f), glm::vec3(0.3f, 2.0f, 50.0f),
                        glm::vec3(1e20f), glm::vec3(-1.0f, std::nanf(""), INFINITY)}) {
      const glm::vec3 out = tone_map(t, c);
      for (int i = 0; i < 3; ++i) {
        EXPECT_GE(out[i], 0.0f) << name;
        EXPECT_LE(out[i], 1.0f) << name;
      }
    }
  }
}

TEST(DisplayTransform, IsSrgbOfToneMapOfExposure) {
  const glm::vec3 c(0.3f, 0.1f, 0.02f);
  for (const std::string& name : tone_mapper_names()) {
    const ToneMapper t = parse_tone_mapper(name);
    for (float ev : {-2.0f, 0.0f, 1.5f}) {
      const glm::vec3 want = srgb_encode(tone_map(t, c * std::exp2(ev)));
      const glm::vec3 got = display_transform(c, ev, t);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-6f) << name << " ev " << ev;
    }
  }
  // Concretely for `none`: 0.1 at +1 EV is 0.2 linear -> 1.055 0.2^(1/2.4) - 0.055.
  EXPECT_NEAR(display_transform(glm::vec3(0.1f), 1.0f, ToneMapper::kNone).x,
              1.055 * std::pow(0.2, 1.0 / 2.4) - 0.055, 1e-6);
}

}  // namespace
}  // namespace pbrkit
