#pragma once
// The split-sum BRDF LUT (Karis 2013, "Real Shading in Unreal Engine 4", IntegrateBRDF): the
// directional albedo of the specular BRDF split into a scale A and a bias B of F0, plus E =
// A + B and E_avg for multiple-scattering compensation (Kulla & Conty 2017).
#include "pbrkit/core/brdf.h"
#include "pbrkit/image/image.h"

namespace pbrkit {

/// The LUT for `model` as a `size` x `size` RGBA image (1 <= size <= 4096): texel (x, y) at
/// n.v = (x + 0.5) / size, roughness = (y + 0.5) / size (at least kMinRoughness) holds
/// (A, B, E = A + B, E_avg(roughness)), integrated with the IBL G of the model (k = alpha / 2
/// for classic). Throws pbrkit::Error for a size out of range.
Image compute_brdf_lut(BrdfModel model, int size);

}  // namespace pbrkit
