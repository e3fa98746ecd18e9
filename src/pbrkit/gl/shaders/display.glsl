// The display transform of src/pbrkit/core/color.cpp in GLSL, line by line (same constants,
// same order of operations): exposure, a tone mapper, the exact sRGB encoding. The viewer
// applies it on the GPU to show what the PNG outputs hold; tests/gl/display_glsl_test.cpp
// holds it to the C++ display_transform.

// pbrkit::ToneMapper
const int TONE_NONE = 0;
const int TONE_PBR_NEUTRAL = 1;
const int TONE_ACES = 2;
const int TONE_AGX = 3;

// IEC 61966-2-1:1999, section 5.2.
float srgb_encode(float linear) {
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

// Khronos PBR Neutral (the specification's reference implementation).
vec3 pbr_neutral(vec3 color) {
  const float kStartCompression = 0.8 - 0.04;
  const float kDesaturation = 0.15;
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  color -= offset;
  float peak = max(color.r, max(color.g, color.b));
  if (peak < kStartCompression) return color;
  const float d = 1.0 - kStartCompression;
  float new_peak = 1.0 - d * d / (peak + d - kStartCompression);
  color *= new_peak / peak;
  float g = 1.0 - 1.0 / (kDesaturation * (peak - new_peak) + 1.0);
  return mix(color, vec3(new_peak), g);
}

// ACES filmic, Stephen Hill's fit (BakingLab ACES.hlsl).
vec3 aces_hill(vec3 color) {
  const mat3 kInput = mat3(vec3(0.59719, 0.07600, 0.02840), vec3(0.35458, 0.90834, 0.13383),
                           vec3(0.04823, 0.01566, 0.83777));
  const mat3 kOutput = mat3(vec3(1.60475, -0.10208, -0.00327), vec3(-0.53108, 1.10813, -0.07276),
                            vec3(-0.07367, -0.00605, 1.07602));
  vec3 v = min(kInput * color, vec3(1e6));
  vec3 a = v * (v + 0.0245786) - 0.000090537;
  vec3 b = v * (0.983729 * v + 0.4329510) + 0.238081;
  v = kOutput * (a / b);
  return clamp(v, 0.0, 1.0);
}

// AgX base look (Wrensch's polynomial formulation).
float agx_contrast(float x) {
  float x2 = x * x;
  float x4 = x2 * x2;
  return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 +
         0.1191 * x - 0.00232;
}

vec3 agx(vec3 color) {
  const mat3 kInset =
      mat3(vec3(0.842479062253094, 0.0423282422610123, 0.0423756549057051),
           vec3(0.0784335999999992, 0.878468636469772, 0.0784336),
           vec3(0.0792237451477643, 0.0791661274605434, 0.879142973793104));
  const mat3 kOutset =
      mat3(vec3(1.19687900512017, -0.0528968517574562, -0.0529716355144438),
           vec3(-0.0980208811401368, 1.15190312990417, -0.0980434501171241),
           vec3(-0.0990297440797205, -0.0989611768448433, 1.15107367264116));
  const float kMinEv = -12.47393;
  const float kMaxEv = 4.026069;
  vec3 v = kInset * color;
  for (int i = 0; i < 3; ++i) {
    float ev = clamp(log2(max(v[i], 1e-10)), kMinEv, kMaxEv);
    v[i] = agx_contrast((ev - kMinEv) / (kMaxEv - kMinEv));
  }
  v = kOutset * v;
  for (int i = 0; i < 3; ++i) v[i] = pow(max(v[i], 0.0), 2.2);
  return clamp(v, 0.0, 1.0);
}

vec3 tone_map(int mapper, vec3 linear) {
  for (int i = 0; i < 3; ++i) linear[i] = linear[i] > 0.0 ? min(linear[i], 1e30) : 0.0;
  if (mapper == TONE_PBR_NEUTRAL) return clamp(pbr_neutral(linear), 0.0, 1.0);
  if (mapper == TONE_ACES) return aces_hill(linear);
  if (mapper == TONE_AGX) return agx(linear);
  return clamp(linear, 0.0, 1.0);
}

// pbrkit::display_transform with the exposure as a scale (exposure_scale(ev) = 2^ev,
// computed once on the CPU).
vec3 display_transform(vec3 linear, float exposure_scale, int mapper) {
  vec3 c = tone_map(mapper, linear * exposure_scale);
  return vec3(srgb_encode(c.r), srgb_encode(c.g), srgb_encode(c.b));
}
