#pragma once
// Thin-film iridescence (KHR_materials_iridescence): the Fresnel reflectance of a base
// coated with a thin dielectric film, after Belcour & Barla 2017, "A Practical Extension to
// Microfacet Theory for the Modeling of Varying Iridescence" (ACM TOG 36(4)). The GLSL twin,
// line by line, is src/pbrkit/gl/shaders/iridescence.glsl.
#include <glm/glm.hpp>

namespace pbrkit {

/// Thin-film Fresnel reflectance (Belcour & Barla 2017, as KHR_materials_iridescence specifies):
/// light from a medium of ior 1 (outside) through a film of ior `film_ior` and thickness
/// `thickness_nm` onto a base whose normal-incidence reflectance is `base_F0` (per channel;
/// a dielectric base passes its F0 from its ior, a metal its baseColor). `cos_theta` = |v.h|.
/// Returns RGB reflectance in [0, 1] (linear Rec.709).
///
/// The base's ior per channel is n = (1 + sqrt(F0)) / (1 - sqrt(F0)) (F0 clamped to
/// [0, 0.9999]; a metal is treated as a dielectric of that ior, as the extension says). The
/// interference is the Airy series in Fourier form, orders 0 to 3, integrated against the
/// CIE 1931 matching functions (Belcour & Barla's Gaussian fits, the extension's constants),
/// OPD = 2 film_ior thickness cos(theta in the film). Where the extension's non-normative
/// GLSL approximates, this follows the paper: both interfaces use the exact dielectric Fresnel
/// amplitudes (not Schlick), s and p summed apart and averaged, with their phases (0 or pi)
/// from the amplitudes' signs; the sensitivity is white-normalised (an OPD of 0 integrates to
/// 1 in every channel, as a reflectance constant over the spectrum must); three orders, not two.
///
/// At `thickness_nm` = 0 (and for `film_ior` = 1 at any thickness) the film vanishes: its ior
/// fades to the outside's over the first 0.03 nm (a smoothstep, as the Khronos sample viewer
/// does), and the result is then exactly the unpolarised Fresnel reflectance
/// (Rs + Rp) / 2 of the interface from ior 1 to ior n (per channel, n from base_F0 as above),
/// at incidence cos_theta: not Schlick's approximation of it.
glm::vec3 iridescence_fresnel(float cos_theta, float film_ior, float thickness_nm,
                              glm::vec3 base_F0);

}  // namespace pbrkit
