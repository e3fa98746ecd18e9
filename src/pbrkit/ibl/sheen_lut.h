#pragma once
// The sheen terms of the split-sum LUT (KHR_materials_sheen; Estevez & Kulla 2017).
//
// Which integral the real-time sheen IBL needs. With the split sum (Karis 2013) applied to
// the sheen lobe f = sheenColor D_Charlie V_Charlie (V including 1 / (4 n.v n.l)):
//   int L(l) f (n.l) dl ~= [int L D (n.l) dl / int D (n.l) dl]_{n = v = R}  x  int f (n.l) dl
// The first factor is the Charlie-prefiltered cube (ibl/sheen_prefilter.h, normalised: a
// constant environment gives the constant); the second, with sheenColor = 1, is
//   DG(n.v, r) = int D_Charlie(h) V_Charlie(v, l) (n.l) dl   over the upper hemisphere,
// the lobe's directional albedo: the same integral as SheenTable::E (core/sheen.h), which
// the albedo scaling of the base needs (1 - max3(sheenColor) E(n.v), README). With the
// README's Charlie visibility the two are one function, so one channel serves both:
//   sheen_ibl = sheenColor * prefiltered_charlie(R, r) * lut.R
//   base     *= 1 - max3(sheenColor) * lut.R
// (The Khronos Sample Viewer's Charlie LUT and Filament's cloth DFG use Ashikhmin's
// visibility for the IBL term instead, so theirs differ from their E; ours stays
// consistent with the path tracer's lobe.)
#include "pbrkit/image/image.h"

namespace pbrkit {

/// The sheen LUT as a `size` x `size` RGBA image (1 <= size <= 4096) over
/// (x: n.v = (x + 0.5) / size, y: sheen roughness = (y + 0.5) / size, clamped to at least
/// kMinSheenRoughness):
///   R = DG = E_sheen(n.v, r) = int D_Charlie V_Charlie (n.l) dl (SheenTable::E),
///   G = E_sheen_avg(r) = 2 int_0^1 E_sheen(mu, r) mu dmu (the cosine-weighted average over
///       directions, for the albedo scaling of the base's irradiance: README's
///       min(1 - c E(n.v), 1 - c E(n.l)) averaged over l becomes 1 - c E_avg),
///   B = 0, A = 1.
/// Throws pbrkit::Error for a size out of range.
Image compute_sheen_lut(int size);

}  // namespace pbrkit
