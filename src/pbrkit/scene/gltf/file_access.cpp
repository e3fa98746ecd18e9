// Reading a glTF file: its bytes (size-limited), the binary container (glTF 2.0 section
// 4.4, checked by parse_glb before any parser runs) and tinygltf's parse, with every file
// tinygltf asks for read through our own callbacks, which refuse paths outside the
// asset's folder.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>

#include "pbrkit/scene/asset_uri.h"
#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/scene/gltf_container.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gltf {

namespace {

// State shared with tinygltf's callbacks.
struct FsContext {
  std::filesystem::path base_dir;
  std::size_t max_bytes = 0;
};

bool fs_file_exists(const std::string& path, void* user) {
  const auto* ctx = static_cast<const FsContext*>(user);
  std::error_code ec;
  return path_is_inside(ctx->base_dir, path) && std::filesystem::is_regular_file(path, ec);
}

std::string fs_expand(const std::string& path, void*) {
  return path;
}

bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
             void* user) {
  const auto* ctx = static_cast<const FsContext*>(user);
  if (!path_is_inside(ctx->base_dir, path)) {
    *err = "refusing to read '" + path + "' outside the asset's folder";
    return false;
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > ctx->max_bytes) {
    *err = "cannot read '" + path + "' (missing or larger than the limit)";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(size);
  if (!in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    *err = "cannot read '" + path + "'";
    return false;
  }
  return true;
}

bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "the loader never writes files";
  return false;
}

// Images are decoded later, once we know whether a texture is colour (sRGB) or data: the
// callback only keeps the encoded bytes.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string* err, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  // tinygltf points into an image's bufferView without checking that the view lies inside
  // its buffer: such images are copied later, by read_image_buffer_views.
  if (image->bufferView >= 0) {
    image->as_is = true;
    image->width = image->height = -1;
    return true;
  }
  if (size <= 0 || bytes == nullptr) {
    *err = "empty image data";
    return false;
  }
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  image->width = image->height = -1;
  return true;
}

std::string read_file_limited(const std::filesystem::path& path, std::size_t limit) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: no such file", path.string());
  if (!std::filesystem::is_regular_file(path, ec)) fail("{}: not a regular file", path.string());
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) fail("{}: cannot determine the file size", path.string());
  if (size > limit)
    fail("{}: file is {} bytes, more than the limit of {}", path.string(), size, limit);
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size, '\0');
  if (!in.read(bytes.data(), std::streamsize(size)))
    fail("{}: cannot read the file", path.string());
  return bytes;
}

}  // namespace

void Loader::read_container() {
  const std::size_t limit = options_.limits.max_buffer_bytes + (std::size_t(64) << 20);
  if (!preloaded_) bytes_ = read_file_limited(path_, limit);
  if (bytes_.size() > limit)
    error("", fmt::format("{} bytes is more than the limit of {}", bytes_.size(), limit));
  is_glb_ = bytes_.size() >= 4 && std::memcmp(bytes_.data(), "glTF", 4) == 0;
  if (is_glb_) {
    const GlbChunks chunks = parse_glb(bytes_.data(), bytes_.size(), file_);
    json_text_.assign(chunks.json, chunks.json_size);
  } else {
    std::string ext = path_.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".glb") error("", "not a binary glTF (the file does not start with 'glTF')");
    json_text_ = bytes_;
  }
}

void Loader::rebuild_glb() {
  const GlbChunks chunks = parse_glb(bytes_.data(), bytes_.size(), file_);
  std::string json = json_text_;
  while (json.size() % 4 != 0) json.push_back(' ');
  auto u32 = [](std::string& out, std::uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), 4);
  };
  std::string glb = "glTF";
  u32(glb, 2);
  u32(glb, 0);  // total length, patched below
  u32(glb, std::uint32_t(json.size()));
  u32(glb, 0x4E4F534A);
  glb += json;
  if (chunks.bin) {
    u32(glb, std::uint32_t(chunks.bin_size));
    u32(glb, 0x004E4942);
    glb.append(reinterpret_cast<const char*>(chunks.bin), chunks.bin_size);
    while (glb.size() % 4 != 0) glb.push_back('\0');
  }
  const std::uint32_t total = std::uint32_t(glb.size());
  std::memcpy(glb.data() + 8, &total, 4);
  bytes_ = std::move(glb);
}

// The bytes of images stored in a bufferView (keep_encoded_image left them out), copied
// once check_buffer_views has put every view inside its buffer.
void Loader::read_image_buffer_views() {
  for (std::size_t i = 0; i < model_.images.size(); ++i) {
    tinygltf::Image& image = model_.images[i];
    if (image.bufferView < 0) continue;
    if (std::size_t(image.bufferView) >= model_.bufferViews.size())
      error(fmt::format("images[{}].bufferView", i),
            fmt::format("bufferView {} does not exist", image.bufferView));
    const auto& view = model_.bufferViews[std::size_t(image.bufferView)];
    const auto begin =
        model_.buffers[std::size_t(view.buffer)].data.begin() + std::ptrdiff_t(view.byteOffset);
    image.image.assign(begin, begin + std::ptrdiff_t(view.byteLength));
  }
}

void Loader::parse_model() {
  tinygltf::TinyGLTF gltf;
  FsContext fs_context{
      path_.parent_path().empty() ? std::filesystem::path(".") : path_.parent_path(),
      std::max(options_.limits.max_buffer_bytes, kMaxImageFileBytes)};
  tinygltf::FsCallbacks fs{&fs_file_exists, &fs_expand, &fs_read, &fs_write, &fs_context};
  gltf.SetFsCallbacks(fs);
  gltf.SetImageLoader(&keep_encoded_image, nullptr);
  std::string err, warn_text;
  const std::string base = fs_context.base_dir.string();
  const bool ok =
      is_glb_ ? gltf.LoadBinaryFromMemory(&model_, &err, &warn_text,
                                          reinterpret_cast<const unsigned char*>(bytes_.data()),
                                          unsigned(bytes_.size()), base)
              : gltf.LoadASCIIFromString(&model_, &err, &warn_text, json_text_.data(),
                                         unsigned(json_text_.size()), base);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    error("", fmt::format("invalid glTF: {}", err.empty() ? "tinygltf refused the file" : err));
  }
  bytes_.clear();
  bytes_.shrink_to_fit();
}

}  // namespace pbrkit::gltf
