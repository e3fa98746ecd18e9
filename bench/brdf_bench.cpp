// Cost of one call of Brdf::eval / sample / pdf (core/brdf.h) for both G models, with
// and without multiple-scattering compensation, and of the layered Bsdf (core/bsdf.h) with
// each KHR_materials_* lobe. Directions, random numbers and materials
// are generated before timing, so the figures are of the BRDF, not of the RNG.
#include <benchmark/benchmark.h>

#include <vector>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/bsdf.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {
namespace {

constexpr std::size_t kCount = 4096;  // power of two: index with a mask
constexpr std::size_t kMaterials = 64;

struct Inputs {
  std::vector<glm::vec3> wo, wi;
  std::vector<float> u_lobe;
  std::vector<glm::vec2> u;
  std::vector<Brdf> brdfs;

  Inputs(BrdfModel model, bool multiscatter) {
    Pcg32 rng(2024);
    for (std::size_t i = 0; i < kCount; ++i) {
      // Cosine-distributed directions: the typical inputs of a path tracer.
      wo.push_back(sample_cosine_hemisphere(rng.next_2d()).direction);
      wi.push_back(sample_cosine_hemisphere(rng.next_2d()).direction);
      u_lobe.push_back(rng.next_float());
      u.push_back(rng.next_2d());
    }
    for (std::size_t m = 0; m < kMaterials; ++m)
      brdfs.emplace_back(glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()),
                         rng.next_float(), rng.next_float(), BrdfOptions{model, multiscatter});
  }
};

const Inputs& inputs(BrdfModel model, bool multiscatter) {
  static const Inputs sets[4] = {{BrdfModel::kReference, false},
                                 {BrdfModel::kReference, true},
                                 {BrdfModel::kClassic, false},
                                 {BrdfModel::kClassic, true}};
  return sets[(model == BrdfModel::kClassic ? 2 : 0) + (multiscatter ? 1 : 0)];
}

template <BrdfModel kModel, bool kMultiscatter>
void BM_Eval(benchmark::State& state) {
  const Inputs& in = inputs(kModel, kMultiscatter);
  std::size_t i = 0;
  for (auto _ : state) {
    const Brdf& brdf = in.brdfs[i & (kMaterials - 1)];
    benchmark::DoNotOptimize(brdf.eval(in.wo[i], in.wi[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

template <BrdfModel kModel, bool kMultiscatter>
void BM_Sample(benchmark::State& state) {
  const Inputs& in = inputs(kModel, kMultiscatter);
  std::size_t i = 0;
  for (auto _ : state) {
    const Brdf& brdf = in.brdfs[i & (kMaterials - 1)];
    benchmark::DoNotOptimize(brdf.sample(in.wo[i], in.u_lobe[i], in.u[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

template <BrdfModel kModel, bool kMultiscatter>
void BM_Pdf(benchmark::State& state) {
  const Inputs& in = inputs(kModel, kMultiscatter);
  std::size_t i = 0;
  for (auto _ : state) {
    const Brdf& brdf = in.brdfs[i & (kMaterials - 1)];
    benchmark::DoNotOptimize(brdf.pdf(in.wo[i], in.wi[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

// Constructing a Brdf (per hit point in a path tracer): parameter clamping, F0 and, with
// compensation, the table lookups for E_avg and Fms.
template <bool kMultiscatter>
void BM_Construct(benchmark::State& state) {
  const Inputs& in = inputs(BrdfModel::kReference, kMultiscatter);
  std::size_t i = 0;
  for (auto _ : state) {
    const float r = in.u[i].x, m = in.u[i].y;
    Brdf brdf(in.wi[i], m, r, {BrdfModel::kReference, kMultiscatter});
    benchmark::DoNotOptimize(brdf);
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

// ---- The layered material (core/bsdf.h): each extension alone and all together, with the
// default options (reference, compensated), bound once per call as the path tracer does. ----

// kRoughGlass, kSmoothGlass, kDiffuseTransmission: transmission through a
// volume boundary (eta 1.5) and the diffuse BTDF; their eval and pdf take every other wi
// mirrored below the surface, so that half the calls evaluate the transmission.
enum class Layer {
  kNone,
  kAnisotropy,
  kIridescence,
  kClearcoat,
  kSheen,
  kAll,
  kRoughGlass,
  kSmoothGlass,
  kDiffuseTransmission
};

constexpr bool transmits(Layer l) {
  return l == Layer::kRoughGlass || l == Layer::kSmoothGlass || l == Layer::kDiffuseTransmission;
}

template <Layer kLayer>
glm::vec3 layered_wi(glm::vec3 wi, std::size_t i) {
  if (transmits(kLayer) && (i & 1)) wi.z = -wi.z;
  return wi;
}

struct LayeredInputs {
  std::vector<Bsdf> bsdfs;
  explicit LayeredInputs(Layer layer) {
    Pcg32 rng(7);
    for (std::size_t m = 0; m < kMaterials; ++m) {
      SurfaceParams p;
      p.base.base_color = glm::vec3(rng.next_float(), rng.next_float(), rng.next_float());
      p.base.metallic = rng.next_float();
      p.base.roughness = rng.next_float();
      const bool all = layer == Layer::kAll;
      if (all || layer == Layer::kAnisotropy) p.base.anisotropy = rng.next_float();
      if (all || layer == Layer::kIridescence) {
        p.base.iridescence = 1.0f;
        p.base.iridescence_thickness = 100.0f + 400.0f * rng.next_float();
      }
      if (all || layer == Layer::kClearcoat) {
        p.coat.weight = 1.0f;
        p.coat.roughness = rng.next_float();
      }
      if (all || layer == Layer::kSheen) {
        p.sheen.color = glm::vec3(rng.next_float());
        p.sheen.roughness = rng.next_float();
      }
      if (layer == Layer::kRoughGlass || layer == Layer::kSmoothGlass) {
        p.base.metallic = 0.0f;
        p.transmission.weight = 1.0f;
        p.transmission.eta = 1.5f;
        p.transmission.thin_walled = false;
        if (layer == Layer::kSmoothGlass) p.base.roughness = 0.0f;
      }
      if (layer == Layer::kDiffuseTransmission) {
        p.base.metallic = 0.0f;
        p.diffuse_transmission.weight = rng.next_float();
        p.diffuse_transmission.color = glm::vec3(rng.next_float());
      }
      bsdfs.emplace_back(p);
    }
  }
};

template <Layer kLayer>
const LayeredInputs& layered_inputs() {
  static const LayeredInputs in(kLayer);
  return in;
}

template <Layer kLayer>
void BM_LayeredEval(benchmark::State& state) {
  const Inputs& in = inputs(BrdfModel::kReference, true);
  const LayeredInputs& li = layered_inputs<kLayer>();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        li.bsdfs[i & (kMaterials - 1)].eval(in.wo[i], layered_wi<kLayer>(in.wi[i], i)));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

template <Layer kLayer>
void BM_LayeredSample(benchmark::State& state) {
  const Inputs& in = inputs(BrdfModel::kReference, true);
  const LayeredInputs& li = layered_inputs<kLayer>();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        li.bsdfs[i & (kMaterials - 1)].sample(in.wo[i], in.u_lobe[i], in.u[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

template <Layer kLayer>
void BM_LayeredPdf(benchmark::State& state) {
  const Inputs& in = inputs(BrdfModel::kReference, true);
  const LayeredInputs& li = layered_inputs<kLayer>();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        li.bsdfs[i & (kMaterials - 1)].pdf(in.wo[i], layered_wi<kLayer>(in.wi[i], i)));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

#define PBRKIT_LAYERED(layer, name)                                        \
  BENCHMARK(BM_LayeredEval<Layer::layer>)->Name("layered/eval/" name);     \
  BENCHMARK(BM_LayeredSample<Layer::layer>)->Name("layered/sample/" name); \
  BENCHMARK(BM_LayeredPdf<Layer::layer>)->Name("layered/pdf/" name)
PBRKIT_LAYERED(kNone, "base");
PBRKIT_LAYERED(kAnisotropy, "anisotropy");
PBRKIT_LAYERED(kIridescence, "iridescence");
PBRKIT_LAYERED(kClearcoat, "clearcoat");
PBRKIT_LAYERED(kSheen, "sheen");
PBRKIT_LAYERED(kAll, "all");
PBRKIT_LAYERED(kRoughGlass, "rough-glass");
PBRKIT_LAYERED(kSmoothGlass, "smooth-glass");
PBRKIT_LAYERED(kDiffuseTransmission, "diffuse-transmission");
#undef PBRKIT_LAYERED

constexpr BrdfModel kRef = BrdfModel::kReference;
constexpr BrdfModel kClassic = BrdfModel::kClassic;

BENCHMARK(BM_Eval<kRef, false>)->Name("eval/reference");
BENCHMARK(BM_Eval<kRef, true>)->Name("eval/reference/multiscatter");
BENCHMARK(BM_Eval<kClassic, false>)->Name("eval/classic");
BENCHMARK(BM_Eval<kClassic, true>)->Name("eval/classic/multiscatter");
BENCHMARK(BM_Sample<kRef, false>)->Name("sample/reference");
BENCHMARK(BM_Sample<kRef, true>)->Name("sample/reference/multiscatter");
BENCHMARK(BM_Sample<kClassic, false>)->Name("sample/classic");
BENCHMARK(BM_Sample<kClassic, true>)->Name("sample/classic/multiscatter");
BENCHMARK(BM_Pdf<kRef, false>)->Name("pdf/reference");
BENCHMARK(BM_Pdf<kRef, true>)->Name("pdf/reference/multiscatter");
BENCHMARK(BM_Pdf<kClassic, false>)->Name("pdf/classic");
BENCHMARK(BM_Pdf<kClassic, true>)->Name("pdf/classic/multiscatter");
BENCHMARK(BM_Construct<false>)->Name("construct/reference");
BENCHMARK(BM_Construct<true>)->Name("construct/reference/multiscatter");

}  // namespace
}  // namespace pbrkit

BENCHMARK_MAIN();
