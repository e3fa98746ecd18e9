#pragma once
// The U-Net of docs/LEARNED_DENOISER.md ("The network (`kpcn-unet-v1`)") on oneDNN:
// 3x3 convolutions with relu as a post-op, 2x2 max pooling, and each decoder's input,
// cat[up(a), s], written in one pass. Activations are float32 in oneDNN's nhwc layout
// (channels interleaved per pixel): oneDNN 2.6 runs its fastest convolutions on it
// (brgconv on AVX-512, jit:avx2 otherwise), and the heads' 25 or 26 logits of a pixel then
// lie side by side for the kernels (kernels.h).
//
// Threads: Debian's libdnnl is built with the OpenMP runtime (DNNL_CPU_RUNTIME OMP in
// dnnl_config.h; `ldd libdnnl.so` shows libgomp), not oneTBB, so the convolutions run on the
// calling thread's OpenMP team (OMP_NUM_THREADS, or Network::run's `threads`) while the
// rest of pbrkit, the decoder's concatenation included, runs on oneTBB. A call from several
// threads at once gets one OpenMP team per calling thread.
#include <cstddef>
#include <functional>
#include <memory>

#include "pbrkit/denoise/learned/weights_file.h"

namespace pbrkit::learned {

/// Uninitialised floats, 64-byte aligned (a cache line, oneDNN's preferred alignment). A
/// buffer of 4 MB or more is 2 MB aligned and asks for transparent huge pages (Debian's
/// default is `madvise`): a 1056x640 tile's arena is 238 MB, 58,000 page faults in 4 kB
/// pages, a few hundred in 2 MB ones.
class FloatBuffer {
 public:
  FloatBuffer() = default;
  explicit FloatBuffer(std::size_t count);
  float* data() { return data_.get(); }
  const float* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  void reset() { data_.reset(), size_ = 0; }

 private:
  struct Free {
    void operator()(float* p) const;
  };
  std::unique_ptr<float[], Free> data_;
  std::size_t size_ = 0;
};

/// The memory one Network::run works in, kept from one tile to the next: one arena of
/// FloatBuffer holding every activation at an offset planned from the pass's order of
/// allocations and releases (first fit), so that tensors alive at the same time never
/// overlap and the peak is the largest set alive at once. Reused, it is faulted in once
/// per call, not once per tile and layer.
class NetworkWorkspace {
 public:
  std::size_t floats() const { return arena_.size(); }

 private:
  friend class Network;
  FloatBuffer arena_;
};

/// The three heads' logits, nhwc: head0 (26 channels, 27 for kpcn-blend-v2) at the input's
/// size, head1 (26) at
/// half of it, head2 (25) at a quarter. They point into the workspace: valid until its
/// next run.
struct NetworkHeads {
  int width = 0, height = 0;  ///< the input's (full-resolution) size
  const float* head0 = nullptr;
  const float* head1 = nullptr;
  const float* head2 = nullptr;
  /// keep_going said no: the heads were not computed.
  bool stopped = false;
};

class Network {
 public:
  /// Keeps a copy of the weights (OIHW, as read); oneDNN gets them laid out as the
  /// convolutions it picks want them, once per layout.
  explicit Network(const NetworkWeights& weights);
  ~Network();
  Network(Network&&) noexcept;
  Network& operator=(Network&&) noexcept;

  /// Runs the network on a width x height input (multiples of 16) that `write_input`
  /// writes into the pointer it gets (spec().input_channels() floats per pixel, nhwc:
  /// network_input_pixel's order, then classic_input_pixel's for kpcn-blend-v2). `threads` > 0 sets
  /// the OpenMP team's size for this call. `keep_going`, if set, is asked before each convolution
  /// (a 1080p tile's layers take up to a few hundred ms each, so a stop is seen promptly); once it
  /// returns false the rest is skipped and NetworkHeads::stopped is set. Throws pbrkit::Error when
  /// oneDNN fails (out of memory).
  NetworkHeads run(NetworkWorkspace& workspace, int width, int height,
                   const std::function<void(float* input)>& write_input, int threads = 0,
                   const std::function<bool(Layer)>& keep_going = {}) const;

  /// The network the weights are for.
  const NetworkSpec& spec() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pbrkit::learned
