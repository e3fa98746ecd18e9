// Textures (glTF 2.0 section 3.8): an image becomes one texture per colour space it is used
// in (sRGB for colour, linear for data: the mips are filtered in that space), kept at its
// source's precision, after its header's size is checked against the pixel limit and the
// total texture budget; the kept texels count against that budget.
#include <algorithm>
#include <cstdint>

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
  // Refuse images whose decoded texels (with the mip chain, 4/3 of the top level) would
  // not fit, from the header alone, before any decoder allocates.
  ImageHeader header;
  if (read_image_header(gimg.image.data(), gimg.image.size(), header)) {
    const std::uint64_t w = std::uint64_t(std::max(header.width, 0));
    const std::uint64_t h = std::uint64_t(std::max(header.height, 0));
    if (w * h > options_.limits.max_image_pixels)
      error(ipath, fmt::format("image size {} x {} exceeds the limit of {} pixels", w, h,
                               options_.limits.max_image_pixels));
    const std::uint64_t need =
        w * h * std::uint64_t(header.channels) * std::uint64_t(header.bits / 8) * 4 / 3;
    if (texture_bytes_ + need > options_.limits.max_total_texture_bytes)
      error(ipath, fmt::format("image {} x {} with {} channels of {} bits needs {} bytes with "
                               "its mips; with the {} bytes of the textures before it, that "
                               "exceeds the limit of {} bytes of decoded textures",
                               w, h, header.channels, header.bits, need, texture_bytes_,
                               options_.limits.max_total_texture_bytes));
  }
  ImageReadOptions opts;
  opts.decode_srgb = srgb;
  opts.max_pixels = options_.limits.max_image_pixels;
  const std::string name = fmt::format("{}: {}", file_, ipath);
  // 8/16-bit sources stay at their precision (sRGB decoded at lookup); float ones stay float.
  Texture tex;
  IntegerImage stored;
  if (decode_integer_image(gimg.image.data(), gimg.image.size(), name, opts, stored)) {
    tex = stored.bits == 16 ? Texture::from_unorm16(stored.width, stored.height, stored.channels,
                                                    std::move(stored.u16), srgb)
                            : Texture::from_unorm8(stored.width, stored.height, stored.channels,
                                                   std::move(stored.u8), srgb);
  } else {
    ImageReadReport report;
    Image img = decode_image(gimg.image.data(), gimg.image.size(), name, opts, &report);
    if (img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4)
      error(ipath, "decoded to an empty image");
    tex = Texture::from_linear(std::move(img), srgb);
  }
  texture_bytes_ += tex.bytes();
  if (texture_bytes_ > options_.limits.max_total_texture_bytes)
    error(ipath, fmt::format("decoded textures exceed the limit of {} bytes",
                             options_.limits.max_total_texture_bytes));
  tex.name = gimg.name.empty() ? (gimg.uri.empty() || is_data_uri(gimg.uri) ? ipath : gimg.uri)
                               : gimg.name;
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
