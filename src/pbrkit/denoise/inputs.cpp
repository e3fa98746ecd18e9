#include "pbrkit/denoise/inputs.h"

#include <fmt/ranges.h>

#include "pbrkit/image/image_io.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

DenoiseInput denoise_input(const Film& film) {
  DenoiseInput in;
  for (int h = 0; h < 2; ++h) {
    in.color[h] = film.color_half(h);
    in.albedo[h] = film.albedo_half(h);
    in.normal[h] = film.normal_half(h);
    in.depth[h] = film.depth_half(h);
  }
  return in;
}

Image mean_of_halves(const Image (&halves)[2]) {
  Image out = halves[0];
  for (std::size_t i = 0; i < out.data.size(); ++i)
    out.data[i] = 0.5f * (halves[0].data[i] + halves[1].data[i]);
  return out;
}

DenoiseInput read_denoise_input(const std::filesystem::path& path) {
  auto layers = read_exr_layers(path);
  auto take = [&](const std::string& name) -> Image {
    for (auto& [n, image] : layers)
      if (n == name) return std::move(image);
    return {};
  };
  DenoiseInput in;
  const std::string ab[2] = {"_a", "_b"};
  for (int h = 0; h < 2; ++h) {
    in.color[h] = take("color" + ab[h]);
    in.albedo[h] = take("albedo" + ab[h]);
    in.normal[h] = take("normal" + ab[h]);
    in.depth[h] = take("depth" + ab[h]);
  }
  // The normals are stored encoded as 0.5 n + 0.5 (write_render_exr).
  for (Image& n : in.normal)
    for (float& v : n.data) v = 2.0f * v - 1.0f;
  std::vector<std::string> missing;
  const Image* images[8] = {&in.color[0],  &in.color[1],  &in.albedo[0], &in.albedo[1],
                            &in.normal[0], &in.normal[1], &in.depth[0],  &in.depth[1]};
  const std::vector<std::string> names = denoise_layer_names();
  for (int i = 0; i < 8; ++i)
    if (images[i]->empty()) missing.push_back(names[std::size_t(i)]);
  if (!missing.empty())
    throw MissingDenoiseLayers(fmt::format("{}: missing the layers the denoiser needs: {}",
                                           path.string(), fmt::join(missing, ", ")),
                               missing);
  try {
    validate_denoise_input(in);
  } catch (const Error& e) {
    fail("{}: {}", path.string(), e.what());
  }
  return in;
}

}  // namespace pbrkit
