#include "pbrkit/core/color.h"

#include <algorithm>
#include <cmath>

#include "pbrkit/util/error.h"

namespace pbrkit {

// IEC 61966-2-1:1999, section 5.2 (encode) and 5.3 (decode). The breakpoints 0.0031308
// (linear) and 0.04045 (encoded) are the published ones; the two segments meet there to
// within 1e-7.
float srgb_encode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (linear >= 1.0f) return 1.0f;
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  if (!(encoded > 0.0f)) return 0.0f;
  if (encoded >= 1.0f) return 1.0f;
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 srgb_encode(glm::vec3 linear) {
  return {srgb_encode(linear.r), srgb_encode(linear.g), srgb_encode(linear.b)};
}
glm::vec3 srgb_decode(glm::vec3 encoded) {
  return {srgb_decode(encoded.r), srgb_decode(encoded.g), srgb_decode(encoded.b)};
}

float exposure_scale(float ev) {
  return std::exp2(ev);
}

namespace {

// Khronos PBR Neutral tone mapper (Khronos 3D Commerce, 2024; the published GLSL
// reference, "PBR Neutral Specification" section "Reference Implementation").
// Below startCompression the mapping is the identity up to a small black-level offset;
// above it the peak channel is compressed towards 1 and the colour desaturated towards the
// new peak.
glm::vec3 pbr_neutral(glm::vec3 color) {
  constexpr float kStartCompression = 0.8f - 0.04f;
  constexpr float kDesaturation = 0.15f;
  const float x = std::min(color.r, std::min(color.g, color.b));
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  color -= offset;
  const float peak = std::max(color.r, std::max(color.g, color.b));
  if (peak < kStartCompression) return color;
  constexpr float d = 1.0f - kStartCompression;
  const float new_peak = 1.0f - d * d / (peak + d - kStartCompression);
  color *= new_peak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - new_peak) + 1.0f);
  return glm::mix(color, glm::vec3(new_peak), g);
}

// ACES filmic, Stephen Hill's fit (BakingLab ACES.hlsl, 2016): the RRT + sRGB ODT
// approximated by a rational function in the ACES AP1 space. The input matrix takes linear
// sRGB to AP1 (sRGB -> XYZ -> D65->D60 -> AP1, with the RRT's saturation folded in); the
// output matrix goes back (ODT saturation -> XYZ -> D60->D65 -> sRGB). Linear in, linear out.
// glm matrices are column-major: each glm::vec3 below is a column of the published rows.
glm::vec3 aces_hill(glm::vec3 color) {
  const glm::mat3 kInput(glm::vec3(0.59719f, 0.07600f, 0.02840f),
                         glm::vec3(0.35458f, 0.90834f, 0.13383f),
                         glm::vec3(0.04823f, 0.01566f, 0.83777f));
  const glm::mat3 kOutput(glm::vec3(1.60475f, -0.10208f, -0.00327f),
                          glm::vec3(-0.53108f, 1.10813f, -0.07276f),
                          glm::vec3(-0.07367f, -0.00605f, 1.07602f));
  // The fit saturates long before 1e6; clamping there keeps v^2 from overflowing to inf/inf.
  glm::vec3 v = glm::min(kInput * color, glm::vec3(1e6f));
  const glm::vec3 a = v * (v + 0.0245786f) - 0.000090537f;
  const glm::vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
  v = kOutput * (a / b);
  return glm::clamp(v, 0.0f, 1.0f);
}

// AgX base look (Troy Sobotka's AgX as in Blender 4; the polynomial formulation of
// B. Wrensch, "Minimal AgX implementation", 2023, used by three.js and Filament):
// inset matrix, log2 encoding between kMinEv and kMaxEv, a 6th-order polynomial fit of the
// default contrast sigmoid, the outset (inverse inset) matrix, and finally the 2.2 power
// that undoes the display encoding built into the sigmoid, giving linear display values.
float agx_contrast(float x) {
  const float x2 = x * x;
  const float x4 = x2 * x2;
  return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 +
         0.1191f * x - 0.00232f;
}

glm::vec3 agx(glm::vec3 color) {
  const glm::mat3 kInset(glm::vec3(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f),
                         glm::vec3(0.0784335999999992f, 0.878468636469772f, 0.0784336f),
                         glm::vec3(0.0792237451477643f, 0.0791661274605434f, 0.879142973793104f));
  const glm::mat3 kOutset(glm::vec3(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f),
                          glm::vec3(-0.0980208811401368f, 1.15190312990417f, -0.0980434501171241f),
                          glm::vec3(-0.0990297440797205f, -0.0989611768448433f, 1.15107367264116f));
  constexpr float kMinEv = -12.47393f;
  constexpr float kMaxEv = 4.026069f;
  glm::vec3 v = kInset * color;
  for (int i = 0; i < 3; ++i) {
    const float ev = std::clamp(std::log2(std::max(v[i], 1e-10f)), kMinEv, kMaxEv);
    v[i] = agx_contrast((ev - kMinEv) / (kMaxEv - kMinEv));
  }
  v = kOutset * v;
  for (int i = 0; i < 3; ++i) v[i] = std::pow(std::max(v[i], 0.0f), 2.2f);
  return glm::clamp(v, 0.0f, 1.0f);
}

}  // namespace

ToneMapper parse_tone_mapper(std::string_view name) {
  if (name == "none") return ToneMapper::kNone;
  if (name == "pbr-neutral") return ToneMapper::kPbrNeutral;
  if (name == "aces") return ToneMapper::kAces;
  if (name == "agx") return ToneMapper::kAgx;
  fail("unknown tone mapper '{}' (expected one of: none, pbr-neutral, aces, agx)", name);
}

std::string_view tone_mapper_name(ToneMapper t) {
  switch (t) {
    case ToneMapper::kNone:
      return "none";
    case ToneMapper::kPbrNeutral:
      return "pbr-neutral";
    case ToneMapper::kAces:
      return "aces";
    case ToneMapper::kAgx:
      return "agx";
  }
  return "none";
}

std::vector<std::string> tone_mapper_names() {
  return {"none", "pbr-neutral", "aces", "agx"};
}

glm::vec3 tone_map(ToneMapper t, glm::vec3 linear) {
  // Scene-referred input is non-negative by the input policy; guard anyway so a stray
  // negative or NaN never reaches a pow or log.
  for (int i = 0; i < 3; ++i) linear[i] = linear[i] > 0.0f ? std::min(linear[i], 1e30f) : 0.0f;
  switch (t) {
    case ToneMapper::kNone:
      return glm::clamp(linear, 0.0f, 1.0f);
    case ToneMapper::kPbrNeutral:
      return glm::clamp(pbr_neutral(linear), 0.0f, 1.0f);
    case ToneMapper::kAces:
      return aces_hill(linear);
    case ToneMapper::kAgx:
      return agx(linear);
  }
  return glm::clamp(linear, 0.0f, 1.0f);
}

glm::vec3 display_transform(glm::vec3 linear, float exposure_ev, ToneMapper t) {
  return srgb_encode(tone_map(t, linear * exposure_scale(exposure_ev)));
}

}  // namespace pbrkit
