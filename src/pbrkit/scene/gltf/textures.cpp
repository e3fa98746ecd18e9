// Textures (glTF 2.0 section 3.8): an image is decoded once per colour space (sRGB for
// colour, linear for data), after its PNG header's size is checked against the pixel
// limit; decoded texels count against the total texture budget.
#include <cstdint>
#include <cstring>

#include "pbrkit/image/image_io.h"
#include "pbrkit/scene/asset_uri.h"
#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

int Loader::texture_for(int texture_index, bool srgb, const std::string& where) {
  if (texture_index < 0 || std::size_t(texture_index) >= model_.textures.size())
    error(where + ".index", fmt::format("texture {} does not exist ({} textures)", texture_index,
                                        model_.textures.size()));
  const auto key = std::make_pair(texture_index, srgb);
  if (const auto it = texture_cache_.find(key); it != texture_cache_.end()) return it->second;
  const auto& gtex = model_.textures[std::size_t(texture_index)];
  const std::string tpath = fmt::format("textures[{}]", texture_index);
  if (gtex.source < 0) {
    warning(fmt::format("{}: no source image (or only an unsupported extension image); ignored",
                        tpath));
    texture_cache_[key] = -1;
    return -1;
  }
  if (std::size_t(gtex.source) >= model_.images.size())
    error(tpath + ".source", fmt::format("image {} does not exist", gtex.source));
  const auto& gimg = model_.images[std::size_t(gtex.source)];
  const std::string ipath = fmt::format("images[{}]", gtex.source);
  if (gimg.image.empty()) error(ipath, "has no image data");
  // Refuse absurd PNG sizes from the header alone, before any decoder allocates.
  if (gimg.image.size() >= 24 && std::memcmp(gimg.image.data(), "\x89PNG", 4) == 0) {
    auto be32 = [&](std::size_t at) {
      const unsigned char* p = gimg.image.data() + at;
      return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) |
             (std::uint32_t(p[2]) << 8) | p[3];
    };
    const std::uint64_t w = be32(16), h = be32(20);
    if (w * h > options_.limits.max_image_pixels)
      error(ipath, fmt::format("image size {} x {} exceeds the limit of {} pixels", w, h,
                               options_.limits.max_image_pixels));
  }
  ImageReadOptions opts;
  opts.decode_srgb = srgb;
  opts.max_pixels = options_.limits.max_image_pixels;
  ImageReadReport report;
  Image img = decode_image(gimg.image.data(), gimg.image.size(),
                           fmt::format("{}: {}", file_, ipath), opts, &report);
  if (img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4)
    error(ipath, "decoded to an empty image");
  Image rgba(img.width, img.height, 4);
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    const float* s = img.data.data() + i * std::size_t(img.channels);
    float* d = rgba.data.data() + i * 4;
    switch (img.channels) {
      case 1:
        d[0] = d[1] = d[2] = s[0];
        d[3] = 1.0f;
        break;
      case 2:
        d[0] = d[1] = d[2] = s[0];
        d[3] = s[1];
        break;
      case 3:
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        d[3] = 1.0f;
        break;
      default:
        std::memcpy(d, s, 4 * sizeof(float));
    }
  }
  // A full mip chain is 4/3 of the top level.
  texture_bytes_ += rgba.data.size() * sizeof(float) * 4 / 3;
  if (texture_bytes_ > options_.limits.max_total_texture_bytes)
    error(ipath, fmt::format("decoded textures exceed the limit of {} bytes",
                             options_.limits.max_total_texture_bytes));
  Texture tex;
  tex.name = gimg.name.empty() ? (gimg.uri.empty() || is_data_uri(gimg.uri) ? ipath : gimg.uri)
                               : gimg.name;
  tex.srgb = srgb;
  tex.mips = make_mip_chain(std::move(rgba));
  if (gtex.sampler >= 0) {
    if (std::size_t(gtex.sampler) >= model_.samplers.size())
      error(tpath + ".sampler", fmt::format("sampler {} does not exist", gtex.sampler));
    const auto& s = model_.samplers[std::size_t(gtex.sampler)];
    const std::string spath = fmt::format("samplers[{}]", gtex.sampler);
    auto wrap = [&](int w, const char* name) {
      switch (w) {
        case TINYGLTF_TEXTURE_WRAP_REPEAT:
          return WrapMode::kRepeat;
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
          return WrapMode::kClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
          return WrapMode::kMirroredRepeat;
        default:
          error(spath + "." + name, fmt::format("invalid wrap mode {}", w));
      }
    };
    tex.sampler.wrap_s = wrap(s.wrapS, "wrapS");
    tex.sampler.wrap_t = wrap(s.wrapT, "wrapT");
    if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST)
      tex.sampler.mag = FilterMode::kNearest;
    else if (s.magFilter != -1 && s.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR)
      error(spath + ".magFilter", fmt::format("invalid filter {}", s.magFilter));
    switch (s.minFilter) {
      case -1:
        break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST:
        tex.sampler.min = FilterMode::kNearest;
        tex.sampler.min_mipmap = false;
        break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR:
        tex.sampler.min_mipmap = false;
        break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
        tex.sampler.min = FilterMode::kNearest;
        break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
        break;
      default:
        error(spath + ".minFilter", fmt::format("invalid filter {}", s.minFilter));
    }
  }
  scene_.textures.push_back(std::move(tex));
  const int index = int(scene_.textures.size()) - 1;
  texture_cache_[key] = index;
  return index;
}

}  // namespace pbrkit::gltf
