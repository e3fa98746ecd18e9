#pragma once
// KHR_materials_dispersion: the ior as a function of wavelength, and the path tracer's
// choice of one wavelength per path where a dispersive surface is met.
//
// The README's normative form (Cauchy's first two terms fitted to the Abbe number
// V_d = 20 / dispersion at the Fraunhofer F, d and C lines):
//
//   n(lambda) = max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1)   lambda in nm
//
// The renderers are RGB, so a path that meets dispersion picks one of the three channels
// (probability 1/3 each), carries only that channel from then on (its throughput is
// multiplied by 3 e_c) and refracts with the ior of that channel's wavelength. The
// channels' wavelengths are the ones at which n(lambda) equals the README's real-time
// sample, (ior - halfSpread, ior, ior + halfSpread) with halfSpread = (ior - 1) 0.025
// dispersion, i.e. 523655 / lambda^2 - 1.5168 = -1/2, 0, +1/2: the path tracer and the
// GL renderer use the same three iors.
#include <glm/glm.hpp>

namespace pbrkit {

/// The wavelengths (nm) the R, G and B channels stand for: sqrt(523655 / 1.0168),
/// sqrt(523655 / 1.5168) (the d line) and sqrt(523655 / 2.0168).
inline constexpr float kChannelWavelengthR = 717.64f;
inline constexpr float kChannelWavelengthG = 587.57f;
inline constexpr float kChannelWavelengthB = 509.56f;

/// The README's n(lambda) for ior n_d (KHR_materials_ior) and `dispersion` = 20 / V_d.
/// dispersion <= 0 (V_d infinite) or ior <= 1 give `ior` unchanged.
float dispersion_ior(float ior, float dispersion, float lambda_nm);

/// n(lambda) at the three channels' wavelengths (R, G, B): G is `ior` itself.
glm::vec3 dispersion_iors(float ior, float dispersion);

/// One channel chosen for a path.
struct ChannelSample {
  int channel = 1;         ///< 0, 1, 2: R, G, B
  float lambda_nm = 0.0f;  ///< its wavelength
  glm::vec3 weight{0.0f};  ///< what the path's throughput is multiplied by: 3 e_channel
};

/// Chooses the channel floor(3 u) (u in [0, 1)) with probability 1/3; the expected value of
/// weight is (1, 1, 1), so the estimate stays unbiased.
ChannelSample sample_channel(float u);

}  // namespace pbrkit
