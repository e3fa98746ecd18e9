// Region means of a denoised image against the raw image's, in raw standard errors
// (src/pbrkit/denoise/energy.h).
#include "pbrkit/denoise/energy.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {
struct Accumulator {
  double raw = 0.0, denoised = 0.0, half_difference_sq = 0.0;
  std::size_t pixels = 0;
  RegionEnergy finish(int id) const {
    RegionEnergy r;
    r.id = id;
    r.pixels = pixels;
    if (pixels == 0) return r;
    const double n = double(pixels);
    r.raw = raw / n;
    r.denoised = denoised / n;
    r.error = std::sqrt(half_difference_sq) / n;
    const double diff = r.denoised - r.raw;
    r.z = r.error > 0.0
              ? diff / r.error
              : (diff == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), diff));
    return r;
  }
};

RegionEnergy worst_of(const std::vector<RegionEnergy>& regions) {
  RegionEnergy worst;
  for (const RegionEnergy& r : regions)
    if (worst.id < 0 || std::abs(r.z) > std::abs(worst.z)) worst = r;
  return worst;
}
}  // namespace

EnergyReport measure_energy(const DenoiseInput& input, const Image& denoised, int block,
                            const std::vector<int>* ids, std::size_t min_pixels) {
  const Image& a = input.color[0];
  const Image& b = input.color[1];
  const int w = a.width, h = a.height;
  if (b.width != w || b.height != h || denoised.width != w || denoised.height != h ||
      a.channels != 3 || b.channels != 3 || denoised.channels != 3)
    fail("measure_energy: the halves and the denoised image must be {}x{} RGB", w, h);
  if (block < 1) fail("measure_energy: block must be >= 1 (it is {})", block);
  if (ids && ids->size() != a.pixel_count())
    fail("measure_energy: {} ids for {} pixels", ids->size(), a.pixel_count());
  const int bw = (w + block - 1) / block, bh = (h + block - 1) / block;
  Accumulator frame;
  std::vector<Accumulator> blocks(std::size_t(bw) * std::size_t(bh));
  int id_count = 0;
  if (ids)
    for (int id : *ids) id_count = std::max(id_count, id + 1);
  std::vector<Accumulator> objects(static_cast<std::size_t>(id_count));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double m = 0.0, d = 0.0, f = 0.0;
      for (int c = 0; c < 3; ++c) {
        m += 0.5 * (double(a.pixel(x, y)[c]) + b.pixel(x, y)[c]) / 3.0;
        d += 0.5 * (double(a.pixel(x, y)[c]) - b.pixel(x, y)[c]) / 3.0;
        f += double(denoised.pixel(x, y)[c]) / 3.0;
      }
      auto add = [&](Accumulator& acc) {
        acc.raw += m;
        acc.denoised += f;
        acc.half_difference_sq += d * d;
        ++acc.pixels;
      };
      add(frame);
      add(blocks[std::size_t(y / block) * std::size_t(bw) + std::size_t(x / block)]);
      if (ids) {
        const int id = (*ids)[std::size_t(y) * std::size_t(w) + std::size_t(x)];
        if (id >= 0) add(objects[std::size_t(id)]);
      }
    }
  EnergyReport out;
  out.frame = frame.finish(-1);
  for (std::size_t i = 0; i < blocks.size(); ++i) out.blocks.push_back(blocks[i].finish(int(i)));
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].pixels >= std::max<std::size_t>(1, min_pixels))
      out.objects.push_back(objects[i].finish(int(i)));
  out.worst_block = worst_of(out.blocks);
  out.worst_object = worst_of(out.objects);
  return out;
}

}  // namespace pbrkit
