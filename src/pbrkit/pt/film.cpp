#include "pbrkit/pt/film.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "pbrkit/pt/adaptive_sampling.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

Film::Film(int w, int h)
    : width(w),
      height(h),
      sum(std::size_t(w) * h, glm::vec3(0.0f)),
      sum_even(std::size_t(w) * h, glm::vec3(0.0f)),
      albedo(std::size_t(w) * h, glm::vec3(0.0f)),
      normal(std::size_t(w) * h, glm::vec3(0.0f)),
      depth(std::size_t(w) * h, 0.0f),
      albedo_even(std::size_t(w) * h, glm::vec3(0.0f)),
      normal_even(std::size_t(w) * h, glm::vec3(0.0f)),
      depth_even(std::size_t(w) * h, 0.0f),
      count(std::size_t(w) * h, 0.0f),
      done(std::size_t(w) * h, 0.0f) {}

namespace {

Image vec3_mean(const Film& f, const std::vector<glm::vec3>& v, float scale, float bias) {
  Image image(f.width, f.height, 3);
  for (std::size_t i = 0; i < f.pixel_count(); ++i) {
    const float n = f.count[i];
    const glm::vec3 m = n > 0.0f ? v[i] / n * scale + bias : glm::vec3(0.0f);
    for (int c = 0; c < 3; ++c) image.data[i * 3 + c] = m[c];
  }
  return image;
}

Image vec3_image(const Film& f, const std::vector<glm::vec3>& v) {
  Image image(f.width, f.height, 3);
  for (std::size_t i = 0; i < f.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) image.data[i * 3 + c] = v[i][c];
  return image;
}

Image scalar_image(const Film& f, const std::vector<float>& v) {
  Image image(f.width, f.height, 1);
  std::copy(v.begin(), v.end(), image.data.begin());
  return image;
}

}  // namespace

Image Film::color() const {
  return vec3_mean(*this, sum, 1.0f, 0.0f);
}
Image Film::albedo_image() const {
  return vec3_mean(*this, albedo, 1.0f, 0.0f);
}
// Normals are accumulated encoded as 0.5 n + 0.5 so that every stored sum is
// non-negative (EXR readers clamp negative samples); decode here.
Image Film::normal_image() const {
  return vec3_mean(*this, normal, 2.0f, -1.0f);
}

Image Film::depth_image() const {
  Image image(width, height, 1);
  for (std::size_t i = 0; i < pixel_count(); ++i)
    image.data[i] = count[i] > 0.0f ? depth[i] / count[i] : 0.0f;
  return image;
}

Image Film::count_image() const {
  return scalar_image(*this, count);
}

Image Film::noise_image() const {
  Image image(width, height, 1);
  for (std::size_t i = 0; i < pixel_count(); ++i) image.data[i] = pixel_noise(i);
  return image;
}

namespace {

// Samples in each half of a pixel with `n` samples: ranges start on an even index
// (half_buffer_error's convention), so the even half has ceil(n / 2).
float half_count(float n, int half) {
  const float even = std::ceil(n * 0.5f);
  return half == 0 ? even : n - even;
}

// The mean of one half of `total` (a vec3 or float sum) given the even half's sum.
template <typename T>
T half_mean(T total, T even, float n, int half) {
  const float m = half_count(n, half);
  if (!(m > 0.0f)) return n > 0.0f ? total / n : T(0.0f);
  return (half == 0 ? even : total - even) / m;
}

Image vec3_half(const Film& f, const std::vector<glm::vec3>& sum,
                const std::vector<glm::vec3>& even, int half, float scale, float bias) {
  Image image(f.width, f.height, 3);
  for (std::size_t i = 0; i < f.pixel_count(); ++i) {
    const glm::vec3 m = f.count[i] > 0.0f
                            ? half_mean(sum[i], even[i], f.count[i], half) * scale + bias
                            : glm::vec3(0.0f);
    for (int c = 0; c < 3; ++c) image.data[i * 3 + c] = m[c];
  }
  return image;
}

}  // namespace

Image Film::color_half(int half) const {
  return vec3_half(*this, sum, sum_even, half, 1.0f, 0.0f);
}
Image Film::albedo_half(int half) const {
  return vec3_half(*this, albedo, albedo_even, half, 1.0f, 0.0f);
}
Image Film::normal_half(int half) const {
  return vec3_half(*this, normal, normal_even, half, 2.0f, -1.0f);
}
Image Film::depth_half(int half) const {
  Image image(width, height, 1);
  for (std::size_t i = 0; i < pixel_count(); ++i)
    image.data[i] = count[i] > 0.0f ? half_mean(depth[i], depth_even[i], count[i], half) : 0.0f;
  return image;
}

float Film::pixel_noise(std::size_t i) const {
  return half_buffer_error(sum[i], sum_even[i], count[i]);
}

void Film::merge(const Film& other) {
  if (other.width != width || other.height != height)
    fail("cannot merge a {}x{} film into a {}x{} one", other.width, other.height, width, height);
  if (denoiser_passes > 0 || other.denoiser_passes > 0)
    fail(
        "cannot merge a film of denoiser-driven sampling: its samples went where its own "
        "earlier samples said, so it is not a sample range");
  for (std::size_t i = 0; i < pixel_count(); ++i) {
    sum[i] += other.sum[i];
    sum_even[i] += other.sum_even[i];
    albedo[i] += other.albedo[i];
    normal[i] += other.normal[i];
    depth[i] += other.depth[i];
    albedo_even[i] += other.albedo_even[i];
    normal_even[i] += other.normal_even[i];
    depth_even[i] += other.depth_even[i];
    count[i] += other.count[i];
    done[i] = std::max(done[i], other.done[i]);
  }
  non_finite_samples += other.non_finite_samples;
  medium_overflows += other.medium_overflows;
  sample_begin = std::min(sample_begin, other.sample_begin);
}

namespace {

// The film's counts as EXR header attributes (film.h); only the non-zero ones, so that a
// clean render's files carry nothing new.
ExrAttributes film_attributes(const Film& film) {
  ExrAttributes a;
  if (film.non_finite_samples > 0)
    a[kNonFiniteSamplesAttribute] = std::to_string(film.non_finite_samples);
  if (film.medium_overflows > 0)
    a[kMediumOverflowsAttribute] = std::to_string(film.medium_overflows);
  if (film.denoiser_passes > 0) a[kDenoiserPassesAttribute] = std::to_string(film.denoiser_passes);
  return a;
}

// A count attribute read back: absent is 0; anything but a whole decimal number is an error
// naming the file.
std::uint64_t count_attribute(const ExrAttributes& a, const char* key,
                              const std::filesystem::path& path) {
  const auto it = a.find(key);
  if (it == a.end()) return 0;
  const std::string& v = it->second;
  std::uint64_t n = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size())
    fail("{}: header attribute '{}' is '{}', expected a whole number", path.string(), key, v);
  return n;
}

}  // namespace

void write_film(const std::filesystem::path& path, const Film& film) {
  const Image color = film.color();
  const Image s = vec3_image(film, film.sum), se = vec3_image(film, film.sum_even);
  const Image al = vec3_image(film, film.albedo), no = vec3_image(film, film.normal);
  const Image de = scalar_image(film, film.depth), co = scalar_image(film, film.count);
  const Image dn = scalar_image(film, film.done);
  const Image ae = vec3_image(film, film.albedo_even), ne = vec3_image(film, film.normal_even);
  const Image de_even = scalar_image(film, film.depth_even);
  const std::vector<std::string> rgb{"R", "G", "B"}, y{"Y"};
  const auto f = ExrPixelType::kFloat;
  write_exr_layers(path,
                   {{"", rgb, &color, f},
                    {"pbrkit_sum", rgb, &s, f},
                    {"pbrkit_sum_even", rgb, &se, f},
                    {"pbrkit_albedo_sum", rgb, &al, f},
                    {"pbrkit_normal_sum", rgb, &no, f},
                    {"pbrkit_depth_sum", y, &de, f},
                    {"pbrkit_albedo_even_sum", rgb, &ae, f},
                    {"pbrkit_normal_even_sum", rgb, &ne, f},
                    {"pbrkit_depth_even_sum", y, &de_even, f},
                    {"pbrkit_count", y, &co, f},
                    {"pbrkit_done", y, &dn, f}},
                   film_attributes(film));
}

Film read_film(const std::filesystem::path& path) {
  ExrAttributes attributes;
  const auto layers = read_exr_layers(path, &attributes);
  auto find_optional = [&](const std::string& name, int channels) -> const Image* {
    for (const auto& [n, image] : layers)
      if (n == name) {
        if (image.channels != channels)
          fail("{}: layer '{}' has {} channels, expected {}", path.string(), name, image.channels,
               channels);
        return &image;
      }
    return nullptr;
  };
  auto find = [&](const std::string& name, int channels) -> const Image& {
    if (const Image* image = find_optional(name, channels)) return *image;
    fail("{}: not a pbrkit accumulation file (no layer '{}')", path.string(), name);
  };
  const Image& s = find("pbrkit_sum", 3);
  Film film(s.width, s.height);
  auto load3 = [&](const Image& image, std::vector<glm::vec3>& v) {
    if (image.width != film.width || image.height != film.height)
      fail("{}: layers have different sizes", path.string());
    for (std::size_t i = 0; i < film.pixel_count(); ++i)
      v[i] = glm::vec3(image.data[i * 3], image.data[i * 3 + 1], image.data[i * 3 + 2]);
  };
  auto load1 = [&](const Image& image, std::vector<float>& v) {
    if (image.width != film.width || image.height != film.height)
      fail("{}: layers have different sizes", path.string());
    std::copy(image.data.begin(), image.data.end(), v.begin());
  };
  load3(s, film.sum);
  load3(find("pbrkit_sum_even", 3), film.sum_even);
  load3(find("pbrkit_albedo_sum", 3), film.albedo);
  load3(find("pbrkit_normal_sum", 3), film.normal);
  load1(find("pbrkit_depth_sum", 1), film.depth);
  load1(find("pbrkit_count", 1), film.count);
  load1(find("pbrkit_done", 1), film.done);
  for (float c : film.count)
    if (!(c >= 0.0f) || c != std::floor(c))
      fail("{}: sample counts must be whole numbers >= 0", path.string());
  const Image* ae = find_optional("pbrkit_albedo_even_sum", 3);
  const Image* ne = find_optional("pbrkit_normal_even_sum", 3);
  const Image* de = find_optional("pbrkit_depth_even_sum", 1);
  if (ae && ne && de) {
    load3(*ae, film.albedo_even);
    load3(*ne, film.normal_even);
    load1(*de, film.depth_even);
  } else {
    // Written before the features had half buffers: give each half its share of the
    // total, which the denoiser reads as noise-free features.
    warn(
        "{}: no feature half buffers (an older accumulation file); the denoiser will treat "
        "its albedo, normal and depth as noise-free",
        path.string());
    for (std::size_t i = 0; i < film.pixel_count(); ++i) {
      const float n = film.count[i];
      const float share = n > 0.0f ? std::ceil(n * 0.5f) / n : 0.0f;
      film.albedo_even[i] = film.albedo[i] * share;
      film.normal_even[i] = film.normal[i] * share;
      film.depth_even[i] = film.depth[i] * share;
    }
  }
  film.non_finite_samples = count_attribute(attributes, kNonFiniteSamplesAttribute, path);
  film.medium_overflows = count_attribute(attributes, kMediumOverflowsAttribute, path);
  const std::uint64_t passes = count_attribute(attributes, kDenoiserPassesAttribute, path);
  if (passes > 1000000)
    fail("{}: attribute {} is {}, not a number of passes", path.string(), kDenoiserPassesAttribute,
         passes);
  film.denoiser_passes = std::uint32_t(passes);
  return film;
}

const std::vector<std::string>& render_aov_names() {
  static const std::vector<std::string> names{"albedo",  "normal", "depth",
                                              "samples", "noise",  "denoise"};
  return names;
}

void write_render_exr(const std::filesystem::path& path, const Film& film,
                      const std::vector<std::string>& aovs, ExrPixelType type, const Image* main) {
  std::vector<Image> images;
  images.reserve(aovs.size() + 16);
  std::vector<ExrLayer> layers;
  const std::vector<std::string> rgb{"R", "G", "B"}, xyz{"X", "Y", "Z"}, y{"Y"};
  images.push_back(main ? *main : film.color());
  layers.push_back({"", rgb, nullptr, type});
  if (main) {
    images.push_back(film.color());
    layers.push_back({"raw", rgb, nullptr, type});
  }
  for (const auto& name : aovs) {
    if (name == "denoise") {
      // Float: the denoiser's variance estimate is the difference of the two halves.
      const auto f = ExrPixelType::kFloat;
      for (int h = 0; h < 2; ++h) {
        const std::string s = h == 0 ? "_a" : "_b";
        images.push_back(film.color_half(h));
        layers.push_back({"color" + s, rgb, nullptr, f});
        images.push_back(film.albedo_half(h));
        layers.push_back({"albedo" + s, rgb, nullptr, f});
        // Encoded 0.5 n + 0.5 like the film's sums: EXR reading clamps negative samples.
        images.push_back(film.normal_half(h));
        for (float& v : images.back().data) v = 0.5f * v + 0.5f;
        layers.push_back({"normal" + s, xyz, nullptr, f});
        images.push_back(film.depth_half(h));
        layers.push_back({"depth" + s, {"Z"}, nullptr, f});
      }
      continue;
    }
    if (name == "albedo") {
      images.push_back(film.albedo_image());
      layers.push_back({name, rgb, nullptr, type});
    } else if (name == "normal") {
      images.push_back(film.normal_image());
      layers.push_back({name, xyz, nullptr, type});
    } else if (name == "depth") {
      images.push_back(film.depth_image());
      // Depth and counts keep full precision whatever the colour type.
      layers.push_back({name, {"Z"}, nullptr, ExrPixelType::kFloat});
    } else if (name == "samples") {
      images.push_back(film.count_image());
      layers.push_back({name, y, nullptr, ExrPixelType::kFloat});
    } else if (name == "noise") {
      Image noise = film.noise_image();
      for (float& v : noise.data)
        if (!std::isfinite(v)) v = 0.0f;
      images.push_back(std::move(noise));
      layers.push_back({name, y, nullptr, type});
    } else {
      fail("unknown AOV '{}' (known: albedo, normal, depth, samples, noise, denoise)", name);
    }
  }
  for (std::size_t i = 0; i < layers.size(); ++i) layers[i].image = &images[i];
  write_exr_layers(path, layers, film_attributes(film));
}

}  // namespace pbrkit
