// The denoiser's quality and speed, the figures of BENCHMARKS.md's "Denoiser" (and of the
// "the denoiser" sections of docs/benchmarks_archive.md): relative MSE of the raw and the denoised
// image against converged references, at 16 and 64 spp and at equal time, for the built-in spheres
// and cornell and for two shared models under two shared HDRIs; the mean of every 1/8 x 1/8 block
// against the reference; the time to denoise 512x512. Also writes a grid of crops (raw, each
// denoiser's image, reference) as a PNG. Each row names its denoiser: the classic
// feature-guided filter (denoise/denoiser.h) or the learned network
// (denoise/learned_denoiser.h, docs/LEARNED_DENOISER.md).
//
// Usage: denoise_bench [--size N] [--ref-spp N] [--cache DIR] [--crops PNG] [--threads N]
//                      [--only NAME] [--spp-count 1|2] [--skip-timing 1] [--debug 1]
//                      [--denoiser classic|learned|both (default both)] [--weights FILE]
//                      [--set main|heldout (heldout: the environments and models the
//                       learned denoiser's training left out, tools/denoiser/scenes.py)]
//                      [--noise-threshold X (adaptive sampling of the raw renders, as
//                       `pbrkit render`'s default 0.02; default 0: off)]
//                      [DenoiseOptions: --radius --variance-radius --error-radius
//                       --selection-radius --prefilter-radius --patch-radius --feature-k
//                       --feature-gradient --candidates k1[:r1],k2,... --outlier-k
//                       --outlier-radius --outlier-quantile --outlier-spread-radius
//                       --feature-tau --normal-tau --first-order k1,k2,...
//                       --first-order-ridge --first-order-energy-radius
//                       --cross-selection 0|1 --zero-order-energy-radius
//                       --symmetric-colour-distance 0|1 --keep-direct-environment 0|1
//                       --variance-level-ratio X]
//                      [--ablate 1 (the energy of each stage: the 16-spp image denoised
//                       with one stage or candidate at a time, in raw standard errors)]
//                      [--energy-block N (block size of the energy columns, default 32)]
// --debug 1 prints the pixels with the largest errors and each object's signed mean
// deviation, and writes heat maps (red: the denoised image's relative squared error,
// green: the raw one's) into the cache folder.
// The references (rendered once, cached as float EXRs under --cache, default
// build/denoise_refs) take minutes each on two cores.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "pbrkit/denoise/denoiser.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/denoise/energy.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/denoise/learned_denoiser.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/camera_rays.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

namespace fs = std::filesystem;
using namespace pbrkit;

namespace {

struct BenchScene {
  std::string name;   // table label and cache key
  std::string scene;  // built-in name or model path
  std::string env;    // "" = the built-in default
};

double rel_mse(const Image& x, const Image& ref) {
  return compare_images(x, ref).relative_mse;
}

// The largest relative difference of a block mean (8 x 8 blocks, luminance-free: the mean
// of the channels) from the reference's, over blocks whose reference mean is above 0.01.
double worst_block_mean_error(const Image& x, const Image& ref) {
  double worst = 0.0;
  const int n = 8;
  for (int by = 0; by < n; ++by)
    for (int bx = 0; bx < n; ++bx) {
      double a = 0.0, b = 0.0;
      for (int y = by * ref.height / n; y < (by + 1) * ref.height / n; ++y)
        for (int x0 = bx * ref.width / n; x0 < (bx + 1) * ref.width / n; ++x0)
          for (int c = 0; c < 3; ++c) {
            a += x.pixel(x0, y)[c];
            b += ref.pixel(x0, y)[c];
          }
      const double area = double(ref.width / n) * double(ref.height / n) * 3.0;
      if (b / area > 0.01) worst = std::max(worst, std::abs(a - b) / b);
    }
  return worst;
}

// Which object each pixel's centre sees: the instance index of the first hit, or -1 for
// the environment. The goal "the mean of every object within 1% of the reference" is
// measured over these masks.
std::vector<int> object_ids(const Scene& scene, const RenderView& view) {
  const SceneGeometry geometry(scene);
  const int w = view.size.width, h = view.size.height;
  const CameraRays rays(view.camera, float(w) / float(h));
  std::vector<int> ids(std::size_t(w) * std::size_t(h), -1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec2 ndc((float(x) + 0.5f) / float(w) * 2.0f - 1.0f,
                          1.0f - (float(y) + 0.5f) / float(h) * 2.0f);
      const Ray ray = rays.generate(ndc);
      std::uint32_t geom = 0, prim = 0;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      if (geometry.intersect(ray.origin, ray.direction, std::numeric_limits<float>::infinity(),
                             kMaskOpaque | kMaskAlpha, geom, prim, t, u, v))
        ids[std::size_t(y) * std::size_t(w) + std::size_t(x)] = int(geom);
    }
  return ids;
}

// Per object (at least kMinPixels pixels, reference mean above 0.01): the relative
// difference of the image's mean over the object's pixels (and channels) from the
// reference's. Returns the largest and how many objects are within 1%.
struct ObjectMeans {
  double worst = 0.0;
  int within = 0, objects = 0;
};
ObjectMeans object_mean_errors(const Image& x, const Image& ref, const std::vector<int>& ids) {
  constexpr std::size_t kMinPixels = 16;
  int count = 0;
  for (int id : ids) count = std::max(count, id + 1);
  std::vector<double> a(std::size_t(count), 0.0), b(std::size_t(count), 0.0);
  std::vector<std::size_t> n(std::size_t(count), 0);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0) continue;
    const auto k = std::size_t(ids[i]);
    for (int c = 0; c < 3; ++c) {
      a[k] += x.data[i * 3 + std::size_t(c)];
      b[k] += ref.data[i * 3 + std::size_t(c)];
    }
    ++n[k];
  }
  ObjectMeans out;
  for (std::size_t k = 0; k < std::size_t(count); ++k) {
    if (n[k] < kMinPixels || b[k] / double(3 * n[k]) <= 0.01) continue;
    const double e = std::abs(a[k] - b[k]) / b[k];
    out.worst = std::max(out.worst, e);
    ++out.objects;
    if (e <= 0.01) ++out.within;
  }
  return out;
}

struct Renderer {
  Scene scene;
  Environment env;
  RenderView view;
  int threads = 2;
  /// Adaptive sampling of the raw renders (0: off); the references never use it.
  float noise_threshold = 0.0f;

  PathTracerResult render(std::uint32_t spp, std::uint32_t seed, bool adaptive = true) const {
    PathTracerSettings s;
    s.width = view.size.width;
    s.height = view.size.height;
    s.spp = spp;
    s.seed = seed;
    s.noise_threshold = adaptive ? noise_threshold : 0.0f;
    s.threads = threads;
    return render_path(scene, &env, view.camera, s);
  }
};

Image crop(const Image& image, int x0, int y0, int size) {
  Image out(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      out.set_rgb(x, y,
                  image.rgb(std::min(image.width - 1, x0 + x), std::min(image.height - 1, y0 + y)));
  return out;
}

void paste(Image& dst, const Image& src, int x0, int y0, int scale) {
  for (int y = 0; y < src.height * scale; ++y)
    for (int x = 0; x < src.width * scale; ++x)
      dst.set_rgb(x0 + x, y0 + y, src.rgb(x / scale, y / scale));
}

// The same input through one stage or candidate at a time: which one moves energy
// (denoised region means against the raw ones, in raw standard errors).
void ablate_energy(const std::string& name, std::uint32_t spp, const DenoiseInput& input,
                   const DenoiseOptions& options, int energy_block, const std::vector<int>& ids) {
  struct Variant {
    const char* name;
    DenoiseOptions o;
  };
  std::vector<Variant> variants;
  variants.push_back({"all stages", options});
  DenoiseOptions o = options;
  o.outlier_k = 0.0f;
  variants.push_back({"no firefly pass", o});
  for (std::size_t c = 0; c < options.candidates.size(); ++c) {
    o = options;
    o.candidates = {options.candidates[c]};
    o.first_order_k.clear();
    variants.push_back({c == 0 ? "zero-order 0 alone" : "zero-order 1 alone", o});
  }
  DenoiseOptions fo = options;
  fo.candidates.clear();
  variants.push_back({"first-order alone, restored vs raw", fo});
  fo.first_order_energy_radius = 0;
  variants.push_back({"first-order alone, unrestored", fo});
  o = options;
  o.error_radius = 0;
  o.selection_radius = 0;
  variants.push_back({"selection unsmoothed", o});
  o = options;
  o.zero_order_energy_radius = options.zero_order_energy_radius > 0 ? 0 : 3;
  variants.push_back({options.zero_order_energy_radius > 0
                          ? "zero-order candidates' energy not restored"
                          : "zero-order candidates' energy restored (box 7x7)",
                      o});
  o = options;
  o.symmetric_colour_distance = !options.symmetric_colour_distance;
  variants.push_back({options.symmetric_colour_distance ? "colour distance as Rousselle 2012"
                                                        : "symmetric colour distance",
                      o});
  o.candidates = {options.candidates.back()};
  o.first_order_k.clear();
  variants.push_back({options.symmetric_colour_distance
                          ? "zero-order 1 alone, colour distance as Rousselle 2012"
                          : "zero-order 1 alone, symmetric colour distance",
                      o});
  o = options;
  o.cross_selection = !options.cross_selection;
  variants.push_back({options.cross_selection ? "one selection from both halves"
                                              : "cross selection (each half by the other's)",
                      o});
  std::printf(
      "\n%s, %u spp, %dx%d blocks: | stage | frame mean vs raw | frame (SE) | "
      "worst block (SE) | worst object (SE) |\n",
      name.c_str(), spp, energy_block, energy_block);
  for (const Variant& v : variants) {
    const EnergyReport e = measure_energy(input, denoise(input, v.o), energy_block, &ids);
    std::printf("| %s | %+.3f%% | %+.2f | %+.2f (block %d) | %+.2f (object %d) |\n", v.name,
                100.0 * (e.frame.denoised / e.frame.raw - 1.0), e.frame.z, e.worst_block.z,
                e.worst_block.id, e.worst_object.z, e.worst_object.id);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  int size = 128, threads = 2;
  bool skip_timing = false, debug = false, ablate = false;
  int energy_block = 32;
  float noise_threshold = 0.0f;
  DenoiseOptions options;
  int spp_count = 2;
  std::string only;
  std::uint32_t ref_spp = 4096;
  std::string which = "both", set = "main";
  fs::path weights;
  fs::path cache = "build/denoise_refs", crops_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--size")
      size = std::stoi(v);
    else if (a == "--ref-spp")
      ref_spp = std::uint32_t(std::stoul(v));
    else if (a == "--cache")
      cache = v;
    else if (a == "--denoiser")
      which = v;
    else if (a == "--weights")
      weights = v;
    else if (a == "--set")
      set = v;
    else if (a == "--crops")
      crops_path = v;
    else if (a == "--threads")
      threads = std::stoi(v);
    else if (a == "--radius")
      options.radius = std::stoi(v);
    else if (a == "--variance-radius")
      options.variance_radius = std::stoi(v);
    else if (a == "--error-radius")
      options.error_radius = std::stoi(v);
    else if (a == "--selection-radius")
      options.selection_radius = std::stoi(v);
    else if (a == "--prefilter-radius")
      options.prefilter_radius = std::stoi(v);
    else if (a == "--patch-radius")
      options.patch_radius = std::stoi(v);
    else if (a == "--raw-candidate")
      options.raw_candidate = v == "1";
    else if (a == "--variance-level-ratio")
      options.variance_level_ratio = std::stof(v);
    else if (a == "--keep-direct-environment")
      options.keep_direct_environment = v == "1";
    else if (a == "--feature-gradient")
      options.feature_gradient = std::stof(v);
    else if (a == "--zero-order-energy-radius")
      options.zero_order_energy_radius = std::stoi(v);
    else if (a == "--cross-selection")
      options.cross_selection = v == "1";
    else if (a == "--relative-variance")
      options.relative_variance = v == "1";
    else if (a == "--first-order") {
      options.first_order_k.clear();
      for (std::size_t at = 0; at < v.size();) {
        const std::size_t end = std::min(v.find(',', at), v.size());
        options.first_order_k.push_back(std::stof(v.substr(at, end - at)));
        at = end + 1;
      }
    } else if (a == "--first-order-energy-radius")
      options.first_order_energy_radius = std::stoi(v);
    else if (a == "--first-order-ridge")
      options.first_order_ridge = std::stof(v);
    else if (a == "--normal-tau")
      options.normal_tau = std::stof(v);
    else if (a == "--feature-tau")
      options.feature_tau = std::stof(v);
    else if (a == "--outlier-k")
      options.outlier_k = std::stof(v);
    else if (a == "--symmetric-colour-distance")
      options.symmetric_colour_distance = v == "1";
    else if (a == "--outlier-quantile")
      options.outlier_quantile = std::stof(v);
    else if (a == "--outlier-radius")
      options.outlier_radius = std::stoi(v);
    else if (a == "--outlier-spread-radius")
      options.outlier_spread_radius = std::stoi(v);
    else if (a == "--feature-k")
      options.feature_k = std::stof(v);
    else if (a == "--candidates") {
      options.candidates.clear();
      for (std::size_t p = 0; p < v.size();) {
        const std::size_t q = v.find(',', p);
        // k or k:radius
        const std::string item = v.substr(p, q - p);
        const std::size_t colon = item.find(':');
        options.candidates.push_back(
            {std::stof(item.substr(0, colon)),
             colon == std::string::npos ? 0 : std::stoi(item.substr(colon + 1))});
        p = q == std::string::npos ? v.size() : q + 1;
      }
    } else if (a == "--spp-count")
      spp_count = std::stoi(v);
    else if (a == "--ablate")
      ablate = v == "1";
    else if (a == "--energy-block")
      energy_block = std::stoi(v);
    else if (a == "--debug")
      debug = v == "1";
    else if (a == "--only")
      only = v;
    else if (a == "--noise-threshold")
      noise_threshold = std::stof(v);
    else if (a == "--skip-timing")
      skip_timing = v == "1";
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const std::string assets = PBRKIT_ASSETS_DIR;
  if (which != "classic" && which != "learned" && which != "both") {
    std::fprintf(stderr, "--denoiser: classic, learned or both\n");
    return 2;
  }
  const bool use_classic = which != "learned", use_learned = which != "classic";
  std::optional<LearnedDenoiser> learned;
  if (use_learned) {
    LearnedDenoiserOptions lo;
    lo.weights = weights;
    lo.threads = threads;
    learned.emplace(lo);
    const LearnedWeightsInfo& info = learned->info();
    std::printf("learned denoiser: %s, %s, trained %lld steps on %s (commit %s)\n",
                info.file.string().c_str(), info.network.c_str(), (long long)info.steps,
                info.dataset.c_str(), info.commit.c_str());
  }
  // The held-out set: environments and models tools/denoiser/scenes.py keeps out of the
  // learned denoiser's training (HELD_OUT_ENVS, HELD_OUT_MODELS).
  const std::vector<BenchScene> heldout_scenes = {
      {"suzi / forest", assets + "/models/suzi_uncompressed.glb", assets + "/hdri/forest.exr"},
      {"suzi / city", assets + "/models/suzi_uncompressed.glb", assets + "/hdri/city.exr"},
      {"engine / forest", assets + "/models/2CylinderEngine/2CylinderEngine.glb",
       assets + "/hdri/forest.exr"},
      {"engine / city", assets + "/models/2CylinderEngine/2CylinderEngine.glb",
       assets + "/hdri/city.exr"},
      {"spheres / forest", "spheres", assets + "/hdri/forest.exr"},
      {"spheres / city", "spheres", assets + "/hdri/city.exr"},
  };
  const std::vector<BenchScene> main_scenes = {
      {"spheres", "spheres", ""},
      {"cornell", "cornell", ""},
      {"suzi / studio", assets + "/models/suzi.glb", assets + "/hdri/studio.exr"},
      {"suzi / sunset", assets + "/models/suzi.glb", assets + "/hdri/sunset.exr"},
      {"bunny / studio", assets + "/models/bunny.glb", assets + "/hdri/studio.exr"},
      {"bunny / sunset", assets + "/models/bunny.glb", assets + "/hdri/sunset.exr"},
      // Heavy-tailed: rough metal reflecting the warehouse's small, very bright ceiling
      // lights (the brightest 1% of its pixels hold 64% of the energy).
      {"spheres / warehouse", "spheres", assets + "/hdri/warehouse.exr"},
      // The street lamps of a night scene (the brightest 1% of its pixels: 19% of the
      // energy) in the same rough metals.
      {"spheres / night", "spheres", assets + "/hdri/night.exr"},
  };
  const std::vector<BenchScene>& scenes = set == "heldout" ? heldout_scenes : main_scenes;
  fs::create_directories(cache);
  std::printf("%dx%d, references %u spp, %d threads, raw renders' noise threshold %g%s\n\n", size,
              size, ref_spp, threads, double(noise_threshold),
              noise_threshold > 0.0f ? " (adaptive sampling, min 16 spp)" : " (off)");
  std::printf(
      "| scene | denoiser | spp | raw relMSE | denoised relMSE | ratio | raw at equal time (spp) | "
      "its relMSE | ratio | worst block mean, raw | denoised | worst object mean, raw | "
      "denoised | objects within 1%%, raw | denoised | frame mean vs raw (SE) | worst block "
      "(SE) | worst object (SE) | denoise s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Image> crop_rows;
  // Per denoiser (classic, learned) and spp (16, 64): the sum of log(raw / denoised).
  double log_ratio[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  int scenes_run = 0;
  for (const BenchScene& bs : scenes) {
    if (!only.empty() && bs.name.find(only) == std::string::npos) continue;
    ++scenes_run;
    Renderer r;
    r.scene = load_scene(bs.scene);
    r.env = load_environment_or_default(bs.env, 0.0f, 1.0f);
    r.view = select_view(r.scene, std::nullopt, size, size);
    r.threads = threads;
    r.noise_threshold = noise_threshold;
    const std::vector<int> ids = object_ids(r.scene, r.view);
    if (ablate) {  // no reference needed
      ablate_energy(bs.name, 16, denoise_input(r.render(16, 1).film), options, energy_block, ids);
      continue;
    }
    std::string key = bs.name;
    for (char& c : key)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    const fs::path ref_path =
        cache / (key + "_" + std::to_string(size) + "_" + std::to_string(ref_spp) + ".exr");
    Image reference;
    if (fs::exists(ref_path)) {
      reference = read_image(ref_path);
    } else {
      std::fprintf(stderr, "rendering the reference of %s (%u spp)...\n", bs.name.c_str(), ref_spp);
      reference = r.render(ref_spp, 12345, false).film.color();
      write_exr(ref_path, reference, ExrPixelType::kFloat);
    }
    for (int k = 0; k < spp_count; ++k) {
      const std::uint32_t spp = k == 0 ? 16 : 64;
      const PathTracerResult noisy = r.render(spp, 1);
      const Image raw = noisy.film.color();
      const DenoiseInput input = denoise_input(noisy.film);
      std::vector<Image> row_images;
      for (int d = 0; d < 2; ++d) {
        if ((d == 0 && !use_classic) || (d == 1 && !use_learned)) continue;
        DenoiseStats stats;
        Image denoised;
        if (d == 0) {
          denoised = denoise(input, options, {}, &stats);
        } else {
          // As the product runs it (denoise/denoiser_choice.h): the halves' mean, and the
          // pixels that saw only the environment passed through.
          DenoiserChoice choice;
          choice.kind = DenoiserKind::kLearned;
          choice.weights = learned->info().file;
          choice.threads = threads;
          DenoiseRun run = denoise_render(input, choice);
          denoised = std::move(run.image);
          stats.seconds = run.seconds;
        }
        const char* denoiser_name = d == 0 ? "classic" : "learned";
        const EnergyReport energy = measure_energy(input, denoised, energy_block, &ids);
        const double e_raw = rel_mse(raw, reference), e_dn = rel_mse(denoised, reference);
        // Equal time: the raw render given the render and the denoising time.
        const double t = noisy.stats.render_seconds;
        const auto equal_spp = std::uint32_t(std::lround(spp * (t + stats.seconds) / t));
        const Image equal = r.render(equal_spp, 2).film.color();
        const double e_equal = rel_mse(equal, reference);
        log_ratio[d][k] += std::log(e_raw / e_dn);
        if (debug) {
          std::vector<std::pair<double, std::size_t>> worst;
          for (std::size_t i = 0; i < raw.pixel_count(); ++i) {
            double e = 0.0;
            for (int c = 0; c < 3; ++c) {
              const double d = double(denoised.data[i * 3 + c]) - reference.data[i * 3 + c];
              e += d * d / (double(reference.data[i * 3 + c]) * reference.data[i * 3 + c] + 0.01);
            }
            worst.push_back({e, i});
          }
          {
            Image heat(size, size, 3);
            for (std::size_t i = 0; i < raw.pixel_count(); ++i) {
              double er = 0.0;
              for (int c = 0; c < 3; ++c) {
                const double d = double(raw.data[i * 3 + c]) - reference.data[i * 3 + c];
                er +=
                    d * d / (double(reference.data[i * 3 + c]) * reference.data[i * 3 + c] + 0.01);
              }
              heat.data[i * 3] = float(worst[i].first * 20.0);
              heat.data[i * 3 + 1] = float(er * 20.0);
            }
            write_display_png(cache / ("heat_" + key + "_" + std::to_string(spp) + ".png"), heat,
                              {});
          }
          std::sort(worst.rbegin(), worst.rend());
          double total = 0.0;
          for (const auto& [e, i] : worst) total += e;
          double top = 0.0;
          for (std::size_t j = 0; j < worst.size() / 20; ++j) top += worst[j].first;
          std::fprintf(stderr,
                       "  top 5%% of pixels hold %.0f%% of the error; shares:", 100 * top / total);
          for (double sh : stats.candidate_share) std::fprintf(stderr, " %.2f", sh);
          std::fprintf(stderr, "; outliers %d", stats.outliers);
          double m[3] = {0, 0, 0};
          for (std::size_t i = 0; i < raw.data.size(); ++i) {
            m[0] += raw.data[i];
            m[1] += denoised.data[i];
            m[2] += reference.data[i];
          }
          std::fprintf(stderr, "; means raw %.4f dn %.4f ref %.4f\n",
                       m[0] / double(raw.data.size()), m[1] / double(raw.data.size()),
                       m[2] / double(raw.data.size()));
          for (int j = 0; j < 8; ++j) {
            const std::size_t i = worst[std::size_t(j)].second;
            std::fprintf(stderr, "  (%zu,%zu) err %.3f raw %.3f dn %.3f ref %.3f\n",
                         i % std::size_t(size), i / std::size_t(size), worst[std::size_t(j)].first,
                         raw.data[i * 3], denoised.data[i * 3], reference.data[i * 3]);
          }
        }
        const ObjectMeans om_raw = object_mean_errors(raw, reference, ids);
        const ObjectMeans om_dn = object_mean_errors(denoised, reference, ids);
        if (debug) {
          // Each object's signed deviation from the reference, raw and denoised: a bias
          // shows as one sign for most objects.
          int count = 0;
          for (int id : ids) count = std::max(count, id + 1);
          const auto objects = std::size_t(count);
          std::vector<double> sum_raw(objects, 0.0), sum_dn(objects, 0.0), sum_ref(objects, 0.0);
          std::vector<int> pixels(objects, 0);
          for (std::size_t i = 0; i < ids.size(); ++i) {
            if (ids[i] < 0) continue;
            const auto k = std::size_t(ids[i]);
            for (std::size_t ch = 0; ch < 3; ++ch) {
              sum_raw[k] += raw.data[i * 3 + ch];
              sum_dn[k] += denoised.data[i * 3 + ch];
              sum_ref[k] += reference.data[i * 3 + ch];
            }
            ++pixels[k];
          }
          for (std::size_t k = 0; k < objects; ++k)
            if (pixels[k] >= 16 && sum_ref[k] > 0.0)
              std::fprintf(stderr, "  object %zu: %d px, raw %+.2f%%, denoised %+.2f%%\n", k,
                           pixels[k], 100.0 * (sum_raw[k] / sum_ref[k] - 1.0),
                           100.0 * (sum_dn[k] / sum_ref[k] - 1.0));
        }
        std::printf(
            "| %s | %s | %u | %.4g | %.4g | %.1fx | %u | %.4g | %.1fx | %.2f%% | %.2f%% | %.2f%% | "
            "%.2f%% | %d/%d | %d/%d | %+.2f | %+.2f | %+.2f | %.3f |\n",
            bs.name.c_str(), denoiser_name, spp, e_raw, e_dn, e_raw / e_dn, equal_spp, e_equal,
            e_equal / e_dn, 100.0 * worst_block_mean_error(raw, reference),
            100.0 * worst_block_mean_error(denoised, reference), 100.0 * om_raw.worst,
            100.0 * om_dn.worst, om_raw.within, om_raw.objects, om_dn.within, om_dn.objects,
            energy.frame.z, energy.worst_block.z, energy.worst_object.z, stats.seconds);
        std::fflush(stdout);
        row_images.push_back(std::move(denoised));
      }
      if (k == 0 && !crops_path.empty()) {
        const int cs = std::min(64, size), x0 = (size - cs) / 2, y0 = (size - cs) / 2;
        const int columns = int(row_images.size()) + 2;
        Image row(columns * (cs * 2 + 4) - 4, cs * 2, 3);
        paste(row, crop(raw, x0, y0, cs), 0, 0, 2);
        int at = 1;
        for (const Image& im : row_images)
          paste(row, crop(im, x0, y0, cs), (at++) * (cs * 2 + 4), 0, 2);
        paste(row, crop(reference, x0, y0, cs), at * (cs * 2 + 4), 0, 2);
        crop_rows.push_back(std::move(row));
      }
    }
  }
  const double n = double(std::max(1, scenes_run));
  for (int d = 0; d < 2; ++d)
    if ((d == 0 && use_classic) || (d == 1 && use_learned))
      std::printf("\n%s: geometric mean of raw / denoised relMSE: 16 spp %.1fx, 64 spp %.1fx\n",
                  d == 0 ? "classic" : "learned", std::exp(log_ratio[d][0] / n),
                  std::exp(log_ratio[d][1] / n));
  if (!crop_rows.empty()) {
    const int w = crop_rows.front().width, h = crop_rows.front().height;
    Image grid(w, int(crop_rows.size()) * (h + 4), 3);
    for (std::size_t i = 0; i < crop_rows.size(); ++i)
      paste(grid, crop_rows[i], 0, int(i) * (h + 4), 1);
    write_display_png(crops_path, grid, {});
    std::printf("wrote %s (per row: raw 16 spp, %s, reference)\n", crops_path.string().c_str(),
                which == "both" ? "classic, learned" : which.c_str());
  }
  // The time to denoise: a cornell film at 16 spp, denoised three times, at 512x512 by
  // each denoiser and at 256x256 and 1920x1080 by the learned one (its peak memory is
  // `pbrkit denoise --denoiser learned` under /usr/bin/time -v, bench/run denoise).
  if (!skip_timing) {
    struct Size {
      int w, h;
    };
    for (const Size sz : {Size{256, 256}, Size{512, 512}, Size{1920, 1080}}) {
      const bool classic_here = use_classic && sz.w == 512;
      if (!classic_here && !use_learned) continue;
      Renderer r;
      r.scene = load_scene("cornell");
      r.env = load_environment_or_default("", 0.0f, 1.0f);
      r.view = select_view(r.scene, std::nullopt, sz.w, sz.h);
      r.threads = threads;
      const PathTracerResult noisy = r.render(16, 1);
      const DenoiseInput in = denoise_input(noisy.film);
      const Image color = noisy.film.color(), albedo = noisy.film.albedo_image(),
                  normal = noisy.film.normal_image();
      for (int d = 0; d < 2; ++d) {
        if ((d == 0 && !classic_here) || (d == 1 && !use_learned)) continue;
        std::vector<double> times, cpu;
        for (int i = 0; i < 3; ++i) {
          const auto t0 = std::chrono::steady_clock::now();
          const std::clock_t c0 = std::clock();
          const Image out = d == 0 ? denoise(in, options) : learned->denoise(color, albedo, normal);
          cpu.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
          times.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(times.begin(), times.end());
        std::sort(cpu.begin(), cpu.end());
        // CPU time (all threads) is what the cores spent; on a machine shared with other
        // work, wall time / (CPU time / threads) says how much of them the run got.
        std::printf(
            "%dx%d %s denoise on %d threads: wall min %.3f s, median %.3f s, max %.3f s; CPU "
            "time min %.3f s, median %.3f s (3 runs)\n",
            sz.w, sz.h, d == 0 ? "classic" : "learned", threads, times[0], times[1], times[2],
            cpu[0], cpu[1]);
      }
    }
  }
  return 0;
}
