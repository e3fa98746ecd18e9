#pragma once
// The foundation's EnergyTable (core/energy.h) uploaded as a texture, so the GLSL model
// (shaders/brdf.glsl: energy_AB, energy_AB_avg) reads exactly the numbers the C++ Brdf
// and the path tracer use.
#include "pbrkit/core/microfacet.h"

namespace pbrkit::gl {

/// A new 32 x 33 GL_RGBA32F texture (nearest filtering; the shader interpolates by hand):
/// rows 0..31 hold (A, B) at the table's nodes mu = i / 31, roughness = j / 31 in .xy and
/// the next node along mu in .zw; row 32 holds (A_avg, B_avg) at x = j and at j + 1. The
/// caller owns the texture name.
unsigned create_energy_texture(GeometryModel model);

/// The sheen's tables (core/sheen.h SheenTable) for sheen.glsl: a 64 x 240 GL_RGBA32F
/// texture (nearest filtering; the shader interpolates by hand) of five 48-row blocks:
/// E (texel (i, j): the four corners of the cell (i, j)), lobe_mean (texel (i, j): nodes
/// (i, j) and (i + 1, j)), E_max_avg (corners), lobe_second_moments' (tt, nn) (nodes (i, j)
/// and (i + 1, j)) and its tn (corners). The caller owns the texture name.
unsigned create_sheen_lut_texture();

/// The anisotropic GGX lobe's albedo (ibl/anisotropic_albedo.h AnisotropicAlbedoTable) for
/// anisotropy_ibl.glsl: a kMu x kPhi x (kR (kS - 1)) GL_RG32F 3D texture, linear filtering,
/// clamped at the edges (node i of n at the texel centre (i + 0.5) / n); block l of kR
/// slices holds the nodes s = l in .r and s = l + 1 in .g, so one fetch reads both
/// neighbours along s. The caller owns the texture name.
unsigned create_anisotropic_albedo_texture();

/// The anisotropic GGX lobe's multiple-scattering compensation (core/anisotropic_energy.h
/// AnisotropicEnergyTable) for brdf.glsl (anisotropic_energy, anisotropic_energy_averages):
/// a 2 kMu x kPhi x (kR kS + 1) GL_RGBA32F 3D texture (nearest filtering; the shader
/// interpolates by hand as AnisotropicEnergyTable::lookup does). Slice l kR + k holds node
/// (i, j, k, l) at x = 2 i as (h, E_tot) in .xy and node i + 1's in .zw (clamped at the last
/// node), and at x = 2 i + 1 its E_ss and node i + 1's in .xy; the last slice holds at (k, l)
/// E_tot_avg at (k, l) and (k + 1, l) in .xy and E_ss_avg likewise in .zw. The caller owns
/// the texture name.
unsigned create_anisotropic_energy_texture();

}  // namespace pbrkit::gl
