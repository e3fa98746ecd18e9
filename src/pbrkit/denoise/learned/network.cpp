#include "pbrkit/denoise/learned/network.h"

#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include <oneapi/dnnl/dnnl.hpp>

#include "pbrkit/util/error.h"
#include "pbrkit/util/parallel.h"

namespace pbrkit::learned {

namespace {

using dnnl::memory;
using Tag = memory::format_tag;
constexpr auto kF32 = memory::data_type::f32;

// Where a pass's tensors live: planned in a first pass over the network that only
// records each allocation's size and each release (in program order), then served at
// the planned offsets in the second, which runs it. The same code drives both passes, so
// the plan cannot drift from what runs.
class Arena {
 public:
  explicit Arena(float* base = nullptr) : base_(base) {}

  // A new tensor's id and (when running) its floats; sizes are rounded up to 16 floats so
  // that every offset stays 64-byte aligned.
  int acquire(std::size_t floats, float** data) {
    const int id = int(sizes_.size());
    sizes_.push_back((floats + 15) / 16 * 16);
    events_.push_back(id);
    *data = base_ ? base_ + offsets_[std::size_t(id)] : nullptr;
    return id;
  }
  void release(int id) { events_.push_back(-1 - id); }

  // Greedy by size for offsets (Pisarchyk and Lee 2020, "Efficient Memory Management for
  // Deep Neural Net Inference", TensorFlow Lite's GPU planner): the tensors, largest first, each at
  // the lowest offset where it overlaps none of those placed before whose lifetimes overlap its
  // own. Returns the arena's size in floats. (First fit in program order left gaps: 97 floats per
  // pixel for this network, this 88, where 80 are alive at most.)
  std::size_t plan() {
    const std::size_t n = sizes_.size();
    std::vector<std::size_t> first(n, 0), last(n, events_.size());  // in event order
    for (std::size_t i = 0; i < events_.size(); ++i)
      (events_[i] >= 0 ? first[std::size_t(events_[i])] : last[std::size_t(-1 - events_[i])]) = i;
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return sizes_[a] > sizes_[b]; });
    offsets_.assign(n, 0);
    std::vector<std::size_t> placed;
    std::size_t total = 0;
    for (const std::size_t t : order) {
      std::vector<std::pair<std::size_t, std::size_t>> busy;  // (offset, end) alive with t
      for (const std::size_t p : placed)
        if (first[p] < last[t] && first[t] < last[p])
          busy.emplace_back(offsets_[p], offsets_[p] + sizes_[p]);
      std::sort(busy.begin(), busy.end());
      std::size_t at = 0;
      for (const auto& [begin, end] : busy) {
        if (begin >= at + sizes_[t]) break;
        at = std::max(at, end);
      }
      offsets_[t] = at;
      total = std::max(total, at + sizes_[t]);
      placed.push_back(t);
    }
    return total;
  }
  // Serves the plan from `base` (the same allocations, in the same order, follow).
  void serve(float* base) {
    base_ = base;
    sizes_.clear();
    events_.clear();
  }

 private:
  float* base_;
  std::vector<std::size_t> sizes_;
  std::vector<std::size_t> offsets_;
  std::vector<int> events_;  // acquire: the id; release: -1 - id
};

// An activation: channels x height x width floats, nhwc, in the arena; released there
// when destroyed or assigned over (so `t = conv(layer, t)` frees the old t after the new
// one is made, as the convolution needs both).
class Tensor {
 public:
  Tensor() = default;
  Tensor(Arena& arena, int c, int h, int w) : channels(c), height(h), width(w), arena_(&arena) {
    id_ = arena.acquire(std::size_t(c) * h * w, &data);
  }
  Tensor(Tensor&& o) noexcept { *this = std::move(o); }
  Tensor& operator=(Tensor&& o) noexcept {
    if (this != &o) {
      reset();
      channels = o.channels, height = o.height, width = o.width, data = o.data;
      arena_ = std::exchange(o.arena_, nullptr), id_ = o.id_;
    }
    return *this;
  }
  ~Tensor() { reset(); }
  void reset() {
    if (arena_) arena_->release(id_);
    arena_ = nullptr;
  }
  // Kept past the pass (a head's logits): never released.
  const float* keep() {
    arena_ = nullptr;
    return data;
  }

  memory::desc desc() const { return {{1, channels, height, width}, kF32, Tag::nhwc}; }
  memory wrap(const dnnl::engine& engine) const { return {desc(), engine, data}; }

  int channels = 0, height = 0, width = 0;
  float* data = nullptr;  // null while planning

 private:
  Arena* arena_ = nullptr;
  int id_ = -1;
};

// Sets the calling thread's OpenMP team size for one call, and restores it after: the
// thread's own setting (an OpenMP internal control variable of the thread), which oneDNN
// reads when it creates and runs a primitive.
class OmpThreads {
 public:
  explicit OmpThreads(int threads) : previous_(omp_get_max_threads()), set_(threads > 0) {
    if (set_) omp_set_num_threads(threads);
  }
  ~OmpThreads() {
    if (set_) omp_set_num_threads(previous_);
  }
  OmpThreads(const OmpThreads&) = delete;
  OmpThreads& operator=(const OmpThreads&) = delete;

 private:
  int previous_;
  bool set_;
};

}  // namespace

FloatBuffer::FloatBuffer(std::size_t count) : size_(count) {
  constexpr std::size_t kHugePage = std::size_t(2) << 20;
  const std::size_t bytes = std::max<std::size_t>(count * sizeof(float), 64);
  const std::size_t align = bytes >= 2 * kHugePage ? kHugePage : 64;
  const std::size_t rounded = (bytes + align - 1) / align * align;
  void* p = std::aligned_alloc(align, rounded);
  if (!p) throw std::bad_alloc();
  if (align == kHugePage) ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure is harmless
  data_.reset(static_cast<float*>(p));
}

void FloatBuffer::Free::operator()(float* p) const {
  std::free(p);
}

struct Network::Impl {
  NetworkWeights weights;
  dnnl::engine engine{dnnl::engine::kind::cpu, 0};

  // Each layer's weights in the layouts oneDNN's convolutions asked for (OIHW reordered
  // to, say, Acdb64a), made on first use: a reorder is a parallel region of its own, and
  // 18 per tile cost more than their copying on a loaded machine.
  struct LaidOut {
    memory::desc desc;
    memory values;
  };
  mutable std::mutex laid_out_mutex;
  mutable std::array<std::vector<LaidOut>, kLayerCount> laid_out;

  memory weights_for(Layer layer, const memory::desc& wanted, dnnl::stream& stream) const {
    const LayerSpec& spec = weights.spec->layers[layer];
    const memory::desc oihw({spec.out, spec.in, 3, 3}, memory::data_type::f32,
                            memory::format_tag::oihw);
    // oneDNN takes non-const handles; the weights are only read.
    memory user(oihw, engine, const_cast<float*>(weights.layers[layer].weight.data()));
    if (wanted == oihw) return user;
    const std::lock_guard lock(laid_out_mutex);
    for (const LaidOut& l : laid_out[layer])
      if (l.desc == wanted) return l.values;
    memory values(wanted, engine);
    dnnl::reorder(user, values).execute(stream, user, values);
    stream.wait();
    laid_out[layer].push_back({wanted, values});
    return values;
  }

  // One forward pass: planning (no stream: the operations only make their outputs) or
  // running.
  struct Pass {
    const Impl& net;
    Arena& arena;
    dnnl::stream* stream = nullptr;
    const std::function<bool(Layer)>* keep_going = nullptr;
    bool stopped = false;

    // relu(conv(src)) (no relu for a head), into a new tensor. Once keep_going has said
    // no, the remaining layers are planned but not computed.
    Tensor conv(Layer layer, const Tensor& src) {
      const LayerSpec& spec = net.weights.spec->layers[layer];
      assert(src.channels == spec.in);
      Tensor dst(arena, spec.out, src.height, src.width);
      if (!stream) return dst;
      if (!stopped && keep_going && *keep_going && !(*keep_going)(layer)) stopped = true;
      if (stopped) return dst;
      const memory::desc any_weights({spec.out, spec.in, 3, 3}, kF32, Tag::any);
      const memory::desc bias({spec.out}, kF32, Tag::x);
      const dnnl::convolution_forward::desc desc(
          dnnl::prop_kind::forward_inference, dnnl::algorithm::convolution_direct, src.desc(),
          any_weights, bias, dst.desc(), {1, 1}, {1, 1}, {1, 1});
      dnnl::primitive_attr attr;
      attr.set_scratchpad_mode(dnnl::scratchpad_mode::user);
      if (spec.relu) {
        dnnl::post_ops ops;
        ops.append_eltwise(1.0f, dnnl::algorithm::eltwise_relu, 0.0f, 0.0f);
        attr.set_post_ops(ops);
      }
      const dnnl::convolution_forward::primitive_desc pd(desc, attr, net.engine);
      const memory weights = net.weights_for(layer, pd.weights_desc(), *stream);
      memory bias_memory(bias, net.engine,
                         const_cast<float*>(net.weights.layers[layer].bias.data()));
      memory scratchpad(pd.scratchpad_desc(), net.engine);
      dnnl::convolution_forward(pd).execute(*stream, {{DNNL_ARG_SRC, src.wrap(net.engine)},
                                                      {DNNL_ARG_WEIGHTS, weights},
                                                      {DNNL_ARG_BIAS, bias_memory},
                                                      {DNNL_ARG_DST, dst.wrap(net.engine)},
                                                      {DNNL_ARG_SCRATCHPAD, scratchpad}});
      stream->wait();
      return dst;
    }

    // The 2x2 max pool, stride 2.
    Tensor pool(const Tensor& src) {
      Tensor dst(arena, src.channels, src.height / 2, src.width / 2);
      if (!stream) return dst;
      const dnnl::pooling_forward::desc desc(dnnl::prop_kind::forward_inference,
                                             dnnl::algorithm::pooling_max, src.desc(), dst.desc(),
                                             {2, 2}, {2, 2}, {0, 0}, {0, 0});
      dnnl::primitive_attr attr;
      attr.set_scratchpad_mode(dnnl::scratchpad_mode::user);
      const dnnl::pooling_forward::primitive_desc pd(desc, attr, net.engine);
      memory scratchpad(pd.scratchpad_desc(), net.engine);
      dnnl::pooling_forward(pd).execute(*stream, {{DNNL_ARG_SRC, src.wrap(net.engine)},
                                                  {DNNL_ARG_DST, dst.wrap(net.engine)},
                                                  {DNNL_ARG_SCRATCHPAD, scratchpad}});
      stream->wait();
      return dst;
    }

    // cat[up(low), skip]: each pixel's channels are low's at its 2x2 cell, then skip's. One
    // pass that writes the concatenation directly, rather than oneDNN's nearest resampling
    // into a tensor of its own and then its concat: at full resolution that tensor would
    // be 32 more floats per pixel alive at the pass's peak (half as much again), and a
    // second copy.
    Tensor up_concat(const Tensor& low, const Tensor& skip) {
      assert(low.width * 2 == skip.width && low.height * 2 == skip.height);
      Tensor dst(arena, low.channels + skip.channels, skip.height, skip.width);
      if (!stream) return dst;
      const std::size_t a = std::size_t(low.channels), b = std::size_t(skip.channels);
      pbrkit::parallel_for(0, skip.height, [&](int y) {
        for (int x = 0; x < skip.width; ++x) {
          float* out = dst.data + (std::size_t(y) * skip.width + x) * (a + b);
          std::memcpy(out, low.data + (std::size_t(y / 2) * low.width + x / 2) * a,
                      a * sizeof(float));
          std::memcpy(out + a, skip.data + (std::size_t(y) * skip.width + x) * b,
                      b * sizeof(float));
        }
      });
      return dst;
    }

    // The U-Net, each tensor released as soon as its last reader has run (the skip
    // connections s0..s3 wait for their decoder): the peak is at L0's decoder, s0 and the
    // concatenation beside it (64 floats per pixel), then the concatenation and dec0a.
    NetworkHeads forward(int width, int height, const std::function<void(float*)>& write_input) {
      NetworkHeads heads;
      heads.width = width, heads.height = height;
      Tensor x(arena, net.weights.spec->input_channels(), height, width);
      if (stream) write_input(x.data);
      Tensor t = conv(kEnc0a, x);
      x.reset();
      Tensor s0 = conv(kEnc0b, t);
      t = pool(s0);
      Tensor s1 = conv(kEnc1, t);
      t = pool(s1);
      Tensor s2 = conv(kEnc2, t);
      t = pool(s2);
      Tensor s3 = conv(kEnc3, t);
      t = pool(s3);
      t = conv(kBotA, t);
      Tensor b = conv(kBotB, t);

      t = up_concat(b, s3);
      b.reset();
      s3.reset();
      t = conv(kDec3a, t);
      Tensor d = conv(kDec3b, t);

      t = up_concat(d, s2);
      s2.reset();
      t = conv(kDec2a, t);
      d = conv(kDec2b, t);
      heads.head2 = conv(kHead2, d).keep();

      t = up_concat(d, s1);
      s1.reset();
      t = conv(kDec1a, t);
      d = conv(kDec1b, t);
      heads.head1 = conv(kHead1, d).keep();

      t = up_concat(d, s0);
      s0.reset();
      d.reset();
      t = conv(kDec0a, t);
      d = conv(kDec0b, t);
      t.reset();
      heads.head0 = conv(kHead0, d).keep();
      heads.stopped = stopped;
      return heads;
    }
  };
};

Network::Network(const NetworkWeights& weights) : impl_(std::make_unique<Impl>()) {
  impl_->weights = weights;
}
Network::~Network() = default;
const NetworkSpec& Network::spec() const {
  return *impl_->weights.spec;
}
Network::Network(Network&&) noexcept = default;
Network& Network::operator=(Network&&) noexcept = default;

NetworkHeads Network::run(NetworkWorkspace& workspace, int width, int height,
                          const std::function<void(float* input)>& write_input, int threads,
                          const std::function<bool(Layer)>& keep_going) const {
  assert(width % kAlignment == 0 && height % kAlignment == 0);
  Arena arena;
  Impl::Pass{*impl_, arena}.forward(width, height, write_input);
  const std::size_t floats = arena.plan();
  if (workspace.arena_.size() < floats) {
    workspace.arena_ = {};  // the old arena goes before the larger one comes
    workspace.arena_ = FloatBuffer(floats);
  }
  arena.serve(workspace.arena_.data());
  const OmpThreads omp(threads);
  try {
    dnnl::stream stream(impl_->engine);
    return Impl::Pass{*impl_, arena, &stream, &keep_going}.forward(width, height, write_input);
  } catch (const dnnl::error& e) {
    fail("learned denoiser: oneDNN failed on a {}x{} tile: {}", width, height, e.what());
  }
}

}  // namespace pbrkit::learned
