#pragma once
// The learned denoiser's output stage (docs/LEARNED_DENOISER.md, "Output: kernels at three
// scales, then the scale compositor"): each scale's 5x5 kernels, softmax-normalised, applied
// to the noisy colour at that scale (Bako et al. 2017), and the scales blended coarse to
// fine (Vogels et al. 2018, section 4.2). Plain loops over rows, in parallel
// (pbrkit::parallel_for); each pixel's sums in a fixed order, so the result does not
// depend on the thread count.
#include <cstddef>
#include <vector>

namespace pbrkit::learned {

/// An RGB image, pixels interleaved, row-major.
struct RgbBuffer {
  int width = 0, height = 0;
  std::vector<float> values;

  RgbBuffer() = default;
  RgbBuffer(int w, int h) : width(w), height(h), values(std::size_t(w) * h * 3, 0.0f) {}
  float* at(int x, int y) { return values.data() + (std::size_t(y) * width + x) * 3; }
  const float* at(int x, int y) const { return values.data() + (std::size_t(y) * width + x) * 3; }
};

/// A head's output: `channels` logits per pixel, interleaved (oneDNN's nhwc), row-major,
/// at the size of the colour it applies to.
struct HeadView {
  const float* logits = nullptr;
  int channels = 0;  ///< 25 (head2), 26 (head1; head0 of kpcn-unet-v1) or 27 (head0 of
                     ///< kpcn-blend-v2): the 26th is the scale blend's, the 27th the classic's
  const float* at(int x, int y, int width) const {
    return logits + (std::size_t(y) * width + x) * channels;
  }
};

/// D: the 2x2 box mean, stride 2 (width and height even).
RgbBuffer box_down(const RgbBuffer& c);

/// d(y, x) = sum over dy, dx in [-2, 2] of w[(dy + 2) * 5 + (dx + 2)](y, x) *
/// c(clamp(y + dy), clamp(x + dx)), with w the softmax of the head's first 25 channels.
RgbBuffer apply_kernels(const HeadView& head, const RgbBuffer& c);

/// The scale compositor's step r = d - a * U(D(d)) + a * U(coarse), with a the sigmoid of
/// the head's channel 25 and U the 2x nearest upsampling; `coarse` has half d's size.
RgbBuffer blend_scales(const RgbBuffer& d, const HeadView& head, const RgbBuffer& coarse);

/// kpcn-blend-v2's last step: b * classic + (1 - b) * r0, with b the sigmoid of head0's
/// channel 26 (docs/LEARNED_DENOISER.md, "kpcn-blend-v2"); `classic` is the classic
/// denoiser's output (sanitised) at r0's size.
RgbBuffer blend_classic(const RgbBuffer& r0, const HeadView& head0, const RgbBuffer& classic);

}  // namespace pbrkit::learned
