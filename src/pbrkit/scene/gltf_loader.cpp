// glTF 2.0 loading through Debian's tinygltf, hardened for hostile files: the container
// (GLB header, JSON, URIs) is checked before tinygltf sees it, every file access goes
// through our own callbacks, and every index, offset and size in the parsed model is
// checked before it is used. Errors name the file and the JSON path of the bad element.
#include "pbrkit/scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <tiny_gltf.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "pbrkit/image/image_io.h"
#include "pbrkit/scene/asset_uri.h"
#include "pbrkit/scene/gltf_container.h"
#include "pbrkit/scene/mesh_attributes.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

namespace {

using nlohmann::json;

// Extensions this loader implements; any other one in extensionsRequired is an error.
const std::set<std::string> kSupportedExtensions = {
    "KHR_materials_emissive_strength", "KHR_texture_transform",      "KHR_lights_punctual",
    "KHR_mesh_quantization",           "KHR_draco_mesh_compression", "EXT_meshopt_compression"};

constexpr std::size_t kMaxImageFileBytes = std::size_t(1) << 30;

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

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

// One component as float; normalized integers per glTF 2.0 section 3.11 (signed values
// use max(c / (2^(b-1) - 1), -1)).
float read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? float(v) / 255.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

std::uint32_t read_index(const unsigned char* p, int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

bool finite_matrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

class Loader {
 public:
  Loader(std::filesystem::path path, const LoadOptions& options)
      : path_(std::move(path)), file_(path_.string()), options_(options) {}
  /// Loads from bytes already in memory; `path` names them and its folder resolves URIs.
  Loader(std::string bytes, std::filesystem::path path, const LoadOptions& options)
      : path_(std::move(path)),
        file_(path_.string()),
        options_(options),
        bytes_(std::move(bytes)),
        preloaded_(true) {}

  Scene load();

 private:
  [[noreturn]] void error(const std::string& where, const std::string& what) const {
    if (where.empty()) fail("{}: {}", file_, what);
    fail("{}: {}: {}", file_, where, what);
  }
  void warning(const std::string& message) {
    const std::string line = fmt::format("{}: {}", file_, message);
    warn("{}", line);
    scene_.warnings.push_back(message);
  }

  void parse_container();
  void rebuild_glb();
  bool prepare_meshopt_fallbacks(json& root);
  void decode_meshopt_views();
  void check_json(const json& root);
  void check_uris(const json& root);
  void check_buffer_views();
  void decode_draco_primitives();

  // A view of an accessor's bytes after validation.
  struct AccessorView {
    const tinygltf::Accessor* accessor = nullptr;
    const unsigned char* data = nullptr;  // null: all zeros (sparse only)
    std::size_t stride = 0;
    int components = 0;
  };
  AccessorView accessor_view(int index, const std::string& where);
  std::vector<float> read_floats(int index, const std::string& where, int expected_components,
                                 bool allow_normalized_int);
  std::vector<std::uint32_t> read_indices(int index, const std::string& where);

  std::vector<int> build_mesh(int mesh_index, const std::vector<double>& weights);
  void build_primitive(int mesh_index, int prim_index, const std::vector<double>& weights,
                       std::vector<int>& out);
  void build_materials();
  TextureRef texture_ref(int texture_index, int texcoord, const tinygltf::ExtensionMap& ext,
                         bool srgb, const std::string& where);
  int texture_for(int texture_index, bool srgb, const std::string& where);
  void build_nodes();
  glm::mat4 local_transform(int node) const;

  std::filesystem::path path_;
  std::string file_;
  LoadOptions options_;
  std::string bytes_;
  bool preloaded_ = false;
  bool is_glb_ = false;
  std::string json_text_;
  tinygltf::Model model_;
  Scene scene_;
  std::map<std::pair<int, bool>, int> texture_cache_;
  std::size_t texture_bytes_ = 0;
  std::size_t triangles_ = 0;
  std::map<std::size_t, std::size_t> meshopt_fallbacks_;  // buffer -> real byteLength
  // Decoded Draco primitives: (mesh, primitive) -> attribute name -> accessor index of a
  // synthetic accessor appended to the model.
  std::map<std::pair<int, int>, std::pair<std::map<std::string, int>, int>> draco_;
};

void Loader::parse_container() {
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
  json root;
  try {
    root = json::parse(json_text_);
  } catch (const json::exception& e) {
    error("", fmt::format("invalid JSON: {}", e.what()));
  }
  check_json(root);
  bool modified = prepare_meshopt_fallbacks(root);
  check_uris(root);
  // tinygltf insists that an indices accessor has a bufferView, which a Draco-compressed
  // primitive's does not (its indices come from the Draco stream): drop those references
  // before tinygltf parses the JSON.
  if (root.contains("meshes")) {
    for (json& mesh : root["meshes"]) {
      if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (json& prim : mesh["primitives"]) {
        if (prim.is_object() && prim.contains("extensions") && prim["extensions"].is_object() &&
            prim["extensions"].contains("KHR_draco_mesh_compression") && prim.contains("indices")) {
          prim.erase("indices");
          modified = true;
        }
      }
    }
  }
  if (modified) {
    json_text_ = root.dump();
    if (is_glb_) rebuild_glb();
  }
}

// EXT_meshopt_compression: a buffer marked {"fallback": true} may have no uri; its bytes
// are produced by decoding. tinygltf refuses uri-less buffers in .gltf files, so such a
// buffer is given a 1-byte placeholder here and sized to its byteLength after parsing.
bool Loader::prepare_meshopt_fallbacks(json& root) {
  if (!root.contains("buffers")) return false;
  bool modified = false;
  json& buffers = root["buffers"];
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    json& b = buffers[i];
    if (b.contains("uri") || !b.contains("extensions") || !b["extensions"].is_object()) continue;
    const json& ext = b["extensions"].contains("EXT_meshopt_compression")
                          ? b["extensions"]["EXT_meshopt_compression"]
                          : json();
    if (!ext.is_object() || !ext.contains("fallback") || ext["fallback"] != true) continue;
    if (is_glb_ && i == 0) continue;  // the GLB BIN chunk
    const std::string where = fmt::format("buffers[{}].byteLength", i);
    if (!b.contains("byteLength") || !b["byteLength"].is_number_unsigned())
      error(where, "missing or not a non-negative integer");
    const std::uint64_t length = b["byteLength"];
    if (length > options_.limits.max_buffer_bytes)
      error(where, fmt::format("{} bytes is more than the limit of {}", length,
                               options_.limits.max_buffer_bytes));
    meshopt_fallbacks_[i] = std::size_t(length);
    b["uri"] = "data:application/octet-stream;base64,AA==";
    b["byteLength"] = 1;
    modified = true;
  }
  return modified;
}

void Loader::decode_meshopt_views() {
  for (std::size_t i = 0; i < model_.bufferViews.size(); ++i) {
    const auto& view = model_.bufferViews[i];
    const auto it = view.extensions.find("EXT_meshopt_compression");
    if (it == view.extensions.end()) continue;
    const std::string where = fmt::format("bufferViews[{}].extensions.EXT_meshopt_compression", i);
    const tinygltf::Value& e = it->second;
    auto integer = [&](const char* name, int fallback, bool required) {
      const tinygltf::Value& v = e.Get(name);
      if (!v.IsInt()) {
        if (required || v.Type() != tinygltf::NULL_TYPE)
          error(where + "." + name, "missing or not an integer");
        return fallback;
      }
      const int x = v.GetNumberAsInt();
      if (x < 0) error(where + "." + name, "must not be negative");
      return x;
    };
    const int buffer = integer("buffer", 0, true);
    const std::size_t offset = std::size_t(integer("byteOffset", 0, false));
    const std::size_t length = std::size_t(integer("byteLength", 0, true));
    const std::size_t stride = std::size_t(integer("byteStride", 0, true));
    const std::size_t count = std::size_t(integer("count", 0, true));
    const std::string mode = e.Get("mode").IsString() ? e.Get("mode").Get<std::string>() : "";
    const std::string filter =
        e.Get("filter").IsString() ? e.Get("filter").Get<std::string>() : "NONE";
    if (std::size_t(buffer) >= model_.buffers.size())
      error(where + ".buffer", fmt::format("buffer {} does not exist", buffer));
    const auto& src = model_.buffers[std::size_t(buffer)].data;
    if (offset > src.size() || length > src.size() - offset)
      error(where, fmt::format("byteOffset {} + byteLength {} exceeds buffer {} ({} bytes)", offset,
                               length, buffer, src.size()));
    if (count * stride > view.byteLength || stride == 0)
      error(where, fmt::format("count {} x byteStride {} does not fit the bufferView's {} bytes",
                               count, stride, view.byteLength));
    std::vector<unsigned char> out(count * stride);
    int rc = -1;
    if (mode == "ATTRIBUTES") {
      if (stride % 4 != 0 || stride > 256)
        error(where + ".byteStride", "must be a multiple of 4 up to 256 for ATTRIBUTES");
      rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src.data() + offset, length);
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
      if (stride != 2 && stride != 4) error(where + ".byteStride", "must be 2 or 4 for indices");
      if (mode == "TRIANGLES" && count % 3 != 0)
        error(where + ".count", "must be a multiple of 3 for TRIANGLES");
      rc =
          mode == "TRIANGLES"
              ? meshopt_decodeIndexBuffer(out.data(), count, stride, src.data() + offset, length)
              : meshopt_decodeIndexSequence(out.data(), count, stride, src.data() + offset, length);
    } else {
      error(where + ".mode", fmt::format("invalid mode '{}'", mode));
    }
    if (rc != 0) error(where, fmt::format("meshopt decoding failed (code {})", rc));
    if (filter == "OCTAHEDRAL") {
      if (stride != 4 && stride != 8)
        error(where + ".filter", "OCTAHEDRAL needs byteStride 4 or 8");
      meshopt_decodeFilterOct(out.data(), count, stride);
    } else if (filter == "QUATERNION") {
      if (stride != 8) error(where + ".filter", "QUATERNION needs byteStride 8");
      meshopt_decodeFilterQuat(out.data(), count, stride);
    } else if (filter == "EXPONENTIAL") {
      if (stride % 4 != 0) error(where + ".filter", "EXPONENTIAL needs a byteStride multiple of 4");
      meshopt_decodeFilterExp(out.data(), count, stride);
    } else if (filter != "NONE") {
      error(where + ".filter", fmt::format("invalid filter '{}'", filter));
    }
    // The bufferView (already bounds-checked) now holds the decoded bytes.
    auto& dst = model_.buffers[std::size_t(view.buffer)].data;
    std::memcpy(dst.data() + view.byteOffset, out.data(), out.size());
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

void Loader::check_json(const json& root) {
  if (!root.is_object()) error("", "the JSON root is not an object");
  if (!root.contains("asset") || !root["asset"].is_object())
    error("asset", "missing or not an object");
  const json& asset = root["asset"];
  if (!asset.contains("version") || !asset["version"].is_string())
    error("asset.version", "missing or not a string");
  const std::string version = asset["version"];
  if (version.rfind("2.", 0) != 0)
    error("asset.version", fmt::format("unsupported glTF version '{}'", version));
  // Top-level collections must be arrays of objects (tinygltf would otherwise skip them
  // silently or misreport).
  for (const char* key :
       {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
        "meshes", "nodes", "samplers", "scenes", "skins", "textures"}) {
    if (!root.contains(key)) continue;
    const json& arr = root[key];
    if (!arr.is_array()) error(key, fmt::format("must be an array, not {}", arr.type_name()));
    for (std::size_t i = 0; i < arr.size(); ++i)
      if (!arr[i].is_object())
        error(fmt::format("{}[{}]", key, i),
              fmt::format("must be an object, not {}", arr[i].type_name()));
  }
  auto string_list = [&](const char* key) {
    std::vector<std::string> out;
    if (!root.contains(key)) return out;
    if (!root[key].is_array()) error(key, "must be an array of strings");
    for (std::size_t i = 0; i < root[key].size(); ++i) {
      if (!root[key][i].is_string()) error(fmt::format("{}[{}]", key, i), "must be a string");
      out.push_back(root[key][i].get<std::string>());
    }
    return out;
  };
  scene_.extensions_used = string_list("extensionsUsed");
  scene_.extensions_required = string_list("extensionsRequired");
  for (std::size_t i = 0; i < scene_.extensions_required.size(); ++i) {
    const std::string& e = scene_.extensions_required[i];
    if (!kSupportedExtensions.count(e))
      error(fmt::format("extensionsRequired[{}]", i),
            fmt::format("required extension '{}' is not supported", e));
  }
  for (const std::string& e : scene_.extensions_used)
    if (!kSupportedExtensions.count(e) &&
        std::find(scene_.extensions_required.begin(), scene_.extensions_required.end(), e) ==
            scene_.extensions_required.end())
      warning(fmt::format("optional extension '{}' is not supported and is ignored", e));
  // Node count for the cycle checks and `info`.
  if (root.contains("nodes")) scene_.node_count = root["nodes"].size();
}

void Loader::check_uris(const json& root) {
  const auto base = path_.parent_path().empty() ? std::filesystem::path(".") : path_.parent_path();
  auto check = [&](const char* key, std::size_t max_bytes, bool is_buffer) {
    if (!root.contains(key)) return;
    const json& arr = root[key];
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string where = fmt::format("{}[{}].uri", key, i);
      if (is_buffer) {
        const json& bl = arr[i].contains("byteLength") ? arr[i]["byteLength"] : json();
        if (!bl.is_number_unsigned() && !(bl.is_number_integer() && bl.get<std::int64_t>() >= 0))
          error(fmt::format("{}[{}].byteLength", key, i), "missing or not a non-negative integer");
        if (bl.get<std::uint64_t>() > options_.limits.max_buffer_bytes)
          error(fmt::format("{}[{}].byteLength", key, i),
                fmt::format("{} bytes is more than the limit of {}", bl.get<std::uint64_t>(),
                            options_.limits.max_buffer_bytes));
      }
      if (!arr[i].contains("uri")) {
        if (is_buffer && !(is_glb_ && i == 0))
          error(fmt::format("{}[{}]", key, i),
                "buffer has no uri (only the first buffer of a .glb may omit it)");
        continue;
      }
      if (!arr[i]["uri"].is_string()) error(where, "must be a string");
      const std::string uri = arr[i]["uri"];
      std::uint64_t size = 0;
      if (is_data_uri(uri)) {
        size = decode_data_uri(uri, max_bytes, fmt::format("{}: {}", file_, where)).size();
      } else {
        const auto file = resolve_relative_uri(base, uri, fmt::format("{}: {}", file_, where));
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec))
          error(where, fmt::format("referenced file '{}' does not exist", file.string()));
        if (!path_is_inside(base, file))
          error(where, fmt::format("'{}' resolves outside the asset's folder", uri));
        size = std::filesystem::file_size(file, ec);
        if (size > max_bytes)
          error(where,
                fmt::format("'{}' is {} bytes, more than the limit of {}", uri, size, max_bytes));
      }
      if (is_buffer && size < arr[i]["byteLength"].get<std::uint64_t>())
        error(where, fmt::format("holds {} bytes but byteLength is {}", size,
                                 arr[i]["byteLength"].get<std::uint64_t>()));
    }
  };
  check("buffers", options_.limits.max_buffer_bytes, true);
  check("images", kMaxImageFileBytes, false);
}

void Loader::check_buffer_views() {
  for (std::size_t i = 0; i < model_.bufferViews.size(); ++i) {
    const auto& v = model_.bufferViews[i];
    const std::string where = fmt::format("bufferViews[{}]", i);
    if (v.buffer < 0 || std::size_t(v.buffer) >= model_.buffers.size())
      error(where + ".buffer",
            fmt::format("buffer {} does not exist ({} buffers)", v.buffer, model_.buffers.size()));
    const std::size_t size = model_.buffers[std::size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
      error(where, fmt::format("byteOffset {} + byteLength {} exceeds the buffer's {} bytes",
                               v.byteOffset, v.byteLength, size));
    if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4 != 0))
      error(where + ".byteStride",
            fmt::format("{} is not a multiple of 4 in [4, 252]", v.byteStride));
  }
}

Loader::AccessorView Loader::accessor_view(int index, const std::string& where) {
  if (index < 0 || std::size_t(index) >= model_.accessors.size())
    error(where,
          fmt::format("accessor {} does not exist ({} accessors)", index, model_.accessors.size()));
  const auto& a = model_.accessors[std::size_t(index)];
  const std::string path = fmt::format("accessors[{}]", index);
  AccessorView view;
  view.accessor = &a;
  view.components = component_count(a.type);
  const int csize = component_size(a.componentType);
  if (view.components == 0) error(path + ".type", "invalid type");
  if (csize == 0)
    error(path + ".componentType", fmt::format("invalid component type {}", a.componentType));
  if (a.count == 0) error(path + ".count", "must be at least 1");
  const std::size_t element = std::size_t(view.components) * std::size_t(csize);
  // Bound the count before anything is allocated from it.
  const std::size_t max_elements = options_.limits.max_buffer_bytes / element + 1;
  if (a.count > max_elements)
    error(path + ".count", fmt::format("{} is larger than any buffer allows", a.count));
  if (a.bufferView >= 0) {
    if (std::size_t(a.bufferView) >= model_.bufferViews.size())
      error(path + ".bufferView", fmt::format("bufferView {} does not exist", a.bufferView));
    const auto& bv = model_.bufferViews[std::size_t(a.bufferView)];
    view.stride = bv.byteStride ? bv.byteStride : element;
    if (view.stride < element)
      error(
          fmt::format("bufferViews[{}].byteStride", a.bufferView),
          fmt::format("{} is smaller than the element size {} of {}", view.stride, element, path));
    if (a.byteOffset % std::size_t(csize) != 0)
      error(path + ".byteOffset",
            fmt::format("{} is not a multiple of the component size", a.byteOffset));
    const std::size_t need = (a.count - 1) * view.stride + element;
    if (a.byteOffset > bv.byteLength || need > bv.byteLength - a.byteOffset)
      error(path,
            fmt::format(
                "byteOffset {} + {} elements (stride {}) needs {} bytes but bufferViews[{}] has {}",
                a.byteOffset, a.count, view.stride, a.byteOffset + need, a.bufferView,
                bv.byteLength));
    view.data = model_.buffers[std::size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
  } else if (!a.sparse.isSparse) {
    error(path, "has neither a bufferView nor sparse values");
  }
  return view;
}

std::vector<float> Loader::read_floats(int index, const std::string& where, int expected_components,
                                       bool allow_normalized_int) {
  const AccessorView v = accessor_view(index, where);
  const auto& a = *v.accessor;
  const std::string path = fmt::format("accessors[{}]", index);
  if (expected_components > 0 && v.components != expected_components)
    error(where, fmt::format("{} has {} components per element, expected {}", path, v.components,
                             expected_components));
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !allow_normalized_int && !a.normalized &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    error(where, fmt::format("{} must be FLOAT or normalized integers", path));
  const int csize = component_size(a.componentType);
  std::vector<float> out(a.count * std::size_t(v.components), 0.0f);
  if (v.data) {
    for (std::size_t i = 0; i < a.count; ++i) {
      const unsigned char* e = v.data + i * v.stride;
      for (int c = 0; c < v.components; ++c)
        out[i * std::size_t(v.components) + std::size_t(c)] =
            read_component(e + std::size_t(c) * std::size_t(csize), a.componentType, a.normalized);
    }
  }
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    const std::string sp = path + ".sparse";
    if (s.count <= 0 || std::size_t(s.count) > a.count)
      error(sp + ".count", fmt::format("{} must be in [1, {}]", s.count, a.count));
    const int itype = s.indices.componentType;
    const int isize = itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                        : 0;
    if (isize == 0)
      error(sp + ".indices.componentType", fmt::format("invalid index type {}", itype));
    auto view_bytes = [&](int bv, int offset, std::size_t need, const std::string& w) {
      if (bv < 0 || std::size_t(bv) >= model_.bufferViews.size())
        error(w + ".bufferView", fmt::format("bufferView {} does not exist", bv));
      const auto& view = model_.bufferViews[std::size_t(bv)];
      if (offset < 0 || std::size_t(offset) > view.byteLength ||
          need > view.byteLength - std::size_t(offset))
        error(w, fmt::format("needs {} bytes at offset {} but bufferViews[{}] has {}", need, offset,
                             bv, view.byteLength));
      return model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset +
             std::size_t(offset);
    };
    const std::size_t element = std::size_t(v.components) * std::size_t(csize);
    const unsigned char* idx =
        view_bytes(s.indices.bufferView, s.indices.byteOffset,
                   std::size_t(s.count) * std::size_t(isize), sp + ".indices");
    const unsigned char* val = view_bytes(s.values.bufferView, s.values.byteOffset,
                                          std::size_t(s.count) * element, sp + ".values");
    for (std::size_t k = 0; k < std::size_t(s.count); ++k) {
      const std::uint32_t target = read_index(idx + k * std::size_t(isize), itype);
      if (target >= a.count)
        error(sp + ".indices", fmt::format("index {} is out of range (count {})", target, a.count));
      for (int c = 0; c < v.components; ++c)
        out[std::size_t(target) * std::size_t(v.components) + std::size_t(c)] = read_component(
            val + k * element + std::size_t(c) * std::size_t(csize), a.componentType, a.normalized);
    }
  }
  return out;
}

std::vector<std::uint32_t> Loader::read_indices(int index, const std::string& where) {
  const AccessorView v = accessor_view(index, where);
  const auto& a = *v.accessor;
  const std::string path = fmt::format("accessors[{}]", index);
  if (v.components != 1) error(where, fmt::format("{} must be SCALAR", path));
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    error(where,
          fmt::format("{} has component type {}; indices must be unsigned byte, short or int", path,
                      a.componentType));
  if (a.sparse.isSparse) {
    // Rare, but allowed: go through the float path (exact for indices below 2^24).
    const std::vector<float> f = read_floats(index, where, 1, true);
    std::vector<std::uint32_t> out(f.size());
    // Out-of-range values become UINT32_MAX, which the vertex-count check then rejects.
    for (std::size_t i = 0; i < f.size(); ++i)
      out[i] = f[i] >= 0.0f && f[i] < 4294967040.0f ? std::uint32_t(f[i]) : 0xFFFFFFFFu;
    return out;
  }
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i)
    out[i] = read_index(v.data + i * v.stride, a.componentType);
  return out;
}

// Decodes every KHR_draco_mesh_compression primitive into synthetic float accessors (and
// a uint32 index accessor) appended to the model, so the normal path reads them.
void Loader::decode_draco_primitives() {
  for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) {
      const auto& prim = model_.meshes[m].primitives[p];
      const auto it = prim.extensions.find("KHR_draco_mesh_compression");
      if (it == prim.extensions.end()) continue;
      const std::string where =
          fmt::format("meshes[{}].primitives[{}].extensions.KHR_draco_mesh_compression", m, p);
      const tinygltf::Value& ext = it->second;
      if (!ext.IsObject() || !ext.Get("bufferView").IsInt() || !ext.Get("attributes").IsObject())
        error(where, "must have an integer bufferView and an attributes object");
      const int bv = ext.Get("bufferView").GetNumberAsInt();
      if (bv < 0 || std::size_t(bv) >= model_.bufferViews.size())
        error(where + ".bufferView", fmt::format("bufferView {} does not exist", bv));
      const auto& view = model_.bufferViews[std::size_t(bv)];
      const auto* data = model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset;
      draco::DecoderBuffer buffer;
      buffer.Init(reinterpret_cast<const char*>(data), view.byteLength);
      draco::Decoder decoder;
      auto result = decoder.DecodeMeshFromBuffer(&buffer);
      if (!result.ok())
        error(where, fmt::format("Draco decoding failed: {}", result.status().error_msg_string()));
      const std::unique_ptr<draco::Mesh> mesh = std::move(result).value();
      const std::size_t points = mesh->num_points();
      const std::size_t faces = mesh->num_faces();
      if (points == 0 || faces == 0) error(where, "Draco mesh is empty");
      if (faces > options_.limits.max_triangles)
        error(where, "Draco mesh exceeds the triangle limit");

      // Synthetic buffers hold the decoded data; accessors point at them.
      auto add_accessor = [&](std::vector<unsigned char> bytes, int type, int ctype,
                              std::size_t count) {
        tinygltf::Buffer buf;
        buf.data = std::move(bytes);
        model_.buffers.push_back(std::move(buf));
        tinygltf::BufferView bview;
        bview.buffer = int(model_.buffers.size()) - 1;
        bview.byteLength = model_.buffers.back().data.size();
        model_.bufferViews.push_back(bview);
        tinygltf::Accessor acc;
        acc.bufferView = int(model_.bufferViews.size()) - 1;
        acc.type = type;
        acc.componentType = ctype;
        acc.count = count;
        model_.accessors.push_back(acc);
        return int(model_.accessors.size()) - 1;
      };
      std::map<std::string, int> attributes;
      for (const auto& key : ext.Get("attributes").Keys()) {
        const tinygltf::Value& id = ext.Get("attributes").Get(key);
        if (!id.IsInt()) error(where + ".attributes." + key, "must be an integer");
        const draco::PointAttribute* attr =
            mesh->GetAttributeByUniqueId(std::uint32_t(id.GetNumberAsInt()));
        if (!attr)
          error(where + ".attributes." + key,
                fmt::format("Draco attribute {} does not exist", id.GetNumberAsInt()));
        const int n = attr->num_components();
        if (n < 1 || n > 4) error(where + ".attributes." + key, "unsupported component count");
        std::vector<unsigned char> bytes(points * std::size_t(n) * sizeof(float));
        std::vector<float> value(static_cast<std::size_t>(n));
        for (std::size_t i = 0; i < points; ++i) {
          const auto avi = attr->mapped_index(draco::PointIndex(std::uint32_t(i)));
          if (!attr->ConvertValue<float>(avi, std::int8_t(n), value.data()))
            error(where + ".attributes." + key, "cannot convert Draco attribute values");
          std::memcpy(bytes.data() + i * std::size_t(n) * sizeof(float), value.data(),
                      std::size_t(n) * sizeof(float));
        }
        const int type = n == 1   ? TINYGLTF_TYPE_SCALAR
                         : n == 2 ? TINYGLTF_TYPE_VEC2
                         : n == 3 ? TINYGLTF_TYPE_VEC3
                                  : TINYGLTF_TYPE_VEC4;
        attributes[key] =
            add_accessor(std::move(bytes), type, TINYGLTF_COMPONENT_TYPE_FLOAT, points);
      }
      std::vector<unsigned char> index_bytes(faces * 3 * sizeof(std::uint32_t));
      for (std::size_t f = 0; f < faces; ++f) {
        const auto& face = mesh->face(draco::FaceIndex(std::uint32_t(f)));
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = face[k].value();
          std::memcpy(index_bytes.data() + (f * 3 + std::size_t(k)) * 4, &v, 4);
        }
      }
      const int indices = add_accessor(std::move(index_bytes), TINYGLTF_TYPE_SCALAR,
                                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, faces * 3);
      draco_[{int(m), int(p)}] = {std::move(attributes), indices};
    }
  }
}

void Loader::build_primitive(int mesh_index, int prim_index, const std::vector<double>& weights,
                             std::vector<int>& out) {
  const auto& gmesh = model_.meshes[std::size_t(mesh_index)];
  const auto& prim = gmesh.primitives[std::size_t(prim_index)];
  const std::string where = fmt::format("meshes[{}].primitives[{}]", mesh_index, prim_index);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
      mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
    warning(fmt::format("{}: points/lines (mode {}) are not rendered; skipped", where, mode));
    return;
  }
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN)
    error(where + ".mode", fmt::format("invalid primitive mode {}", mode));

  std::map<std::string, int> attributes(prim.attributes.begin(), prim.attributes.end());
  int indices_accessor = prim.indices;
  const auto draco = draco_.find({mesh_index, prim_index});
  if (draco != draco_.end()) {
    for (const auto& [name, acc] : draco->second.first) attributes[name] = acc;
    indices_accessor = draco->second.second;
  }
  const auto pos_it = attributes.find("POSITION");
  if (pos_it == attributes.end()) {
    warning(fmt::format("{}: no POSITION attribute; skipped", where));
    return;
  }
  Mesh mesh;
  mesh.name = gmesh.name.empty() ? fmt::format("mesh{}", mesh_index) : gmesh.name;
  if (gmesh.primitives.size() > 1) mesh.name += fmt::format(".{}", prim_index);
  auto attr_where = [&](const std::string& name) {
    return fmt::format("{}.attributes.{}", where, name);
  };
  auto read_vec = [&](const std::string& name, int comps, auto& dst) {
    const auto it = attributes.find(name);
    if (it == attributes.end()) return;
    const std::vector<float> f = read_floats(it->second, attr_where(name), comps, true);
    using V = typename std::decay_t<decltype(dst)>::value_type;
    dst.resize(f.size() / std::size_t(comps));
    for (std::size_t i = 0; i < dst.size(); ++i) {
      V v(0.0f);
      for (int c = 0; c < comps; ++c) v[c] = f[i * std::size_t(comps) + std::size_t(c)];
      dst[i] = v;
    }
  };
  read_vec("POSITION", 3, mesh.positions);
  const std::size_t n = mesh.positions.size();
  read_vec("NORMAL", 3, mesh.normals);
  read_vec("TANGENT", 4, mesh.tangents);
  read_vec("TEXCOORD_0", 2, mesh.texcoords0);
  read_vec("TEXCOORD_1", 2, mesh.texcoords1);
  if (attributes.count("COLOR_0")) {
    const int acc = attributes["COLOR_0"];
    const AccessorView cv = accessor_view(acc, attr_where("COLOR_0"));
    if (cv.components == 3) {
      std::vector<glm::vec3> rgb;
      read_vec("COLOR_0", 3, rgb);
      for (const auto& c : rgb) mesh.colors0.push_back(glm::vec4(c, 1.0f));
    } else {
      read_vec("COLOR_0", 4, mesh.colors0);
    }
  }
  auto check_count = [&](const char* name, std::size_t count) {
    if (count != 0 && count != n)
      error(attr_where(name), fmt::format("has {} elements but POSITION has {}", count, n));
  };
  check_count("NORMAL", mesh.normals.size());
  check_count("TANGENT", mesh.tangents.size());
  check_count("TEXCOORD_0", mesh.texcoords0.size());
  check_count("TEXCOORD_1", mesh.texcoords1.size());
  check_count("COLOR_0", mesh.colors0.size());

  // Morph targets at the given weights (glTF 2.0 section 3.7.2.2).
  for (std::size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
    const float w = float(weights[t]);
    if (w == 0.0f) continue;
    if (!std::isfinite(w))
      error(fmt::format("meshes[{}].weights[{}]", mesh_index, t), "is not finite");
    for (const auto& target : prim.targets[t]) {
      // (no structured binding: clang 14 cannot capture one in the lambda below)
      const std::string& name = target.first;
      const int acc = target.second;
      const std::string tw = fmt::format("{}.targets[{}].{}", where, t, name);
      auto apply = [&](auto& dst, int comps) {
        if (dst.empty()) return;
        const std::vector<float> d = read_floats(acc, tw, comps, true);
        if (d.size() / std::size_t(comps) != dst.size())
          error(tw, fmt::format("has {} elements, expected {}", d.size() / std::size_t(comps),
                                dst.size()));
        for (std::size_t i = 0; i < dst.size(); ++i)
          for (int c = 0; c < comps; ++c)
            dst[i][c] += w * d[i * std::size_t(comps) + std::size_t(c)];
      };
      if (name == "POSITION")
        apply(mesh.positions, 3);
      else if (name == "NORMAL")
        apply(mesh.normals, 3);
      else if (name == "TANGENT")
        apply(mesh.tangents, 3);
    }
  }

  if (indices_accessor >= 0) {
    std::vector<std::uint32_t> idx = read_indices(indices_accessor, where + ".indices");
    for (std::size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= n)
        error(where + ".indices",
              fmt::format("accessors[{}][{}] = {} is out of range (the primitive has {} vertices)",
                          indices_accessor, i, idx[i], n));
    mesh.indices = std::move(idx);
  } else {
    mesh.indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.indices[i] = std::uint32_t(i);
  }
  // Strips and fans to lists (glTF 2.0 section 3.7.2.1 gives the vertex order).
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    const std::vector<std::uint32_t> src = std::move(mesh.indices);
    mesh.indices.clear();
    for (std::size_t i = 0; i + 2 < src.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Triangle i is (p_i, p_{i+1+i%2}, p_{i+2-i%2}): keeps the winding consistent.
        const std::size_t odd = i % 2;
        mesh.indices.insert(mesh.indices.end(), {src[i], src[i + 1 + odd], src[i + 2 - odd]});
      } else {
        mesh.indices.insert(mesh.indices.end(), {src[i + 1], src[i + 2], src[0]});
      }
    }
  } else if (mesh.indices.size() % 3 != 0) {
    warning(fmt::format("{}: {} indices is not a multiple of 3; the last {} ignored", where,
                        mesh.indices.size(), mesh.indices.size() % 3));
    mesh.indices.resize(mesh.indices.size() / 3 * 3);
  }
  triangles_ += mesh.indices.size() / 3;
  if (triangles_ > options_.limits.max_triangles)
    error(where, fmt::format("the scene exceeds the limit of {} triangles",
                             options_.limits.max_triangles));

  // Non-finite data: positions are an error; the rest is repaired with a warning.
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      error(attr_where("POSITION"),
            fmt::format("vertex {} is not finite ({}, {}, {})", i, p.x, p.y, p.z));
  }
  auto all_finite = [](const auto& values, int comps) {
    for (const auto& v : values)
      for (int c = 0; c < comps; ++c)
        if (!std::isfinite(v[c])) return false;
    return true;
  };
  auto zero_non_finite = [&](auto& values, int comps, const char* name) {
    if (all_finite(values, comps)) return;
    warning(fmt::format("{}: NaN/Inf values set to 0", attr_where(name)));
    for (auto& v : values)
      for (int c = 0; c < comps; ++c)
        if (!std::isfinite(v[c])) v[c] = 0.0f;
  };
  zero_non_finite(mesh.texcoords0, 2, "TEXCOORD_0");
  zero_non_finite(mesh.texcoords1, 2, "TEXCOORD_1");
  zero_non_finite(mesh.colors0, 4, "COLOR_0");
  bool normals_ok = !mesh.normals.empty() && all_finite(mesh.normals, 3);
  if (!mesh.normals.empty() && !normals_ok)
    warning(
        fmt::format("{}: NaN/Inf normals; flat normals generated instead", attr_where("NORMAL")));
  if (normals_ok)
    for (auto& nrm : mesh.normals) {
      const float len = glm::length(nrm);
      // Renormalise only what is visibly off, so unit normals round-trip bit-exactly.
      if (!(std::fabs(len - 1.0f) < 1e-4f)) nrm = len > 0.0f ? nrm / len : glm::vec3(0, 0, 1);
    }
  if (!mesh.tangents.empty() && !all_finite(mesh.tangents, 4)) {
    warning(fmt::format("{}: NaN/Inf tangents; regenerated", attr_where("TANGENT")));
    mesh.tangents.clear();
  }
  if (!normals_ok) {
    mesh.normals.clear();
    mesh.tangents.clear();  // the frame changes with the normals
    generate_flat_normals(mesh);
  }

  if (prim.material >= 0) {
    if (std::size_t(prim.material) >= model_.materials.size())
      error(where + ".material", fmt::format("material {} does not exist", prim.material));
    mesh.material = prim.material;
  }
  const Material& mat =
      mesh.material >= 0 ? scene_.materials[std::size_t(mesh.material)] : Scene::default_material();
  if (mesh.tangents.empty() && mat.normal_texture.valid())
    generate_tangents(mesh, mat.normal_texture.texcoord);
  scene_.meshes.push_back(std::move(mesh));
  out.push_back(int(scene_.meshes.size()) - 1);
}

std::vector<int> Loader::build_mesh(int mesh_index, const std::vector<double>& weights) {
  std::vector<int> out;
  const auto& gmesh = model_.meshes[std::size_t(mesh_index)];
  for (std::size_t p = 0; p < gmesh.primitives.size(); ++p)
    build_primitive(mesh_index, int(p), weights, out);
  return out;
}

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

TextureRef Loader::texture_ref(int texture_index, int texcoord, const tinygltf::ExtensionMap& ext,
                               bool srgb, const std::string& where) {
  TextureRef ref;
  if (texture_index < 0) return ref;
  ref.texture = texture_for(texture_index, srgb, where);
  if (texcoord < 0 || texcoord > 1) {
    warning(fmt::format("{}.texCoord: set {} is not supported (only 0 and 1); using 0", where,
                        texcoord));
    texcoord = 0;
  }
  ref.texcoord = texcoord;
  if (const auto it = ext.find("KHR_texture_transform"); it != ext.end() && it->second.IsObject()) {
    const tinygltf::Value& v = it->second;
    TextureTransform t;
    auto vec2 = [&](const char* name, glm::vec2& dst) {
      const tinygltf::Value& a = v.Get(name);
      if (!a.IsArray()) return;
      if (a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber())
        error(where + ".extensions.KHR_texture_transform." + name, "must be an array of 2 numbers");
      dst = {float(a.Get(0).GetNumberAsDouble()), float(a.Get(1).GetNumberAsDouble())};
    };
    vec2("offset", t.offset);
    vec2("scale", t.scale);
    if (v.Get("rotation").IsNumber()) t.rotation = float(v.Get("rotation").GetNumberAsDouble());
    if (!std::isfinite(t.offset.x + t.offset.y + t.scale.x + t.scale.y + t.rotation))
      error(where + ".extensions.KHR_texture_transform", "has non-finite values");
    if (v.Get("texCoord").IsInt()) {
      const int tc = v.Get("texCoord").GetNumberAsInt();
      if (tc == 0 || tc == 1) ref.texcoord = tc;
    }
    ref.transform = t;
  }
  return ref;
}

void Loader::build_materials() {
  for (std::size_t i = 0; i < model_.materials.size(); ++i) {
    const auto& g = model_.materials[i];
    const std::string where = fmt::format("materials[{}]", i);
    Material m;
    m.name = g.name.empty() ? fmt::format("material{}", i) : g.name;
    const auto& pbr = g.pbrMetallicRoughness;
    auto number = [&](double v, const std::string& what) {
      if (!std::isfinite(v)) error(where + what, "is not finite");
      return float(v);
    };
    if (pbr.baseColorFactor.size() == 4)
      for (int c = 0; c < 4; ++c)
        m.base_color_factor[c] =
            number(pbr.baseColorFactor[std::size_t(c)], ".pbrMetallicRoughness.baseColorFactor");
    else if (!pbr.baseColorFactor.empty())
      error(where + ".pbrMetallicRoughness.baseColorFactor", "must have 4 numbers");
    m.metallic_factor = number(pbr.metallicFactor, ".pbrMetallicRoughness.metallicFactor");
    m.roughness_factor = number(pbr.roughnessFactor, ".pbrMetallicRoughness.roughnessFactor");
    if (g.emissiveFactor.size() == 3)
      for (int c = 0; c < 3; ++c)
        m.emissive_factor[c] = number(g.emissiveFactor[std::size_t(c)], ".emissiveFactor");
    else if (!g.emissiveFactor.empty())
      error(where + ".emissiveFactor", "must have 3 numbers");
    if (const auto it = g.extensions.find("KHR_materials_emissive_strength");
        it != g.extensions.end()) {
      const tinygltf::Value& s = it->second.Get("emissiveStrength");
      if (s.IsNumber()) {
        m.emissive_strength =
            number(s.GetNumberAsDouble(), ".extensions.KHR_materials_emissive_strength");
        if (m.emissive_strength < 0.0f)
          error(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
                "must not be negative");
      }
    }
    if (g.alphaMode == "MASK")
      m.alpha_mode = AlphaMode::kMask;
    else if (g.alphaMode == "BLEND")
      m.alpha_mode = AlphaMode::kBlend;
    else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
      error(where + ".alphaMode", fmt::format("invalid value '{}'", g.alphaMode));
    m.alpha_cutoff = number(g.alphaCutoff, ".alphaCutoff");
    m.double_sided = g.doubleSided;
    m.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                       pbr.baseColorTexture.extensions, true,
                                       where + ".pbrMetallicRoughness.baseColorTexture");
    m.metallic_roughness_texture =
        texture_ref(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, false,
                    where + ".pbrMetallicRoughness.metallicRoughnessTexture");
    m.normal_texture = texture_ref(g.normalTexture.index, g.normalTexture.texCoord,
                                   g.normalTexture.extensions, false, where + ".normalTexture");
    m.normal_scale = number(g.normalTexture.scale, ".normalTexture.scale");
    m.occlusion_texture =
        texture_ref(g.occlusionTexture.index, g.occlusionTexture.texCoord,
                    g.occlusionTexture.extensions, false, where + ".occlusionTexture");
    m.occlusion_strength = number(g.occlusionTexture.strength, ".occlusionTexture.strength");
    m.emissive_texture =
        texture_ref(g.emissiveTexture.index, g.emissiveTexture.texCoord,
                    g.emissiveTexture.extensions, true, where + ".emissiveTexture");
    scene_.materials.push_back(std::move(m));
  }
}

glm::mat4 Loader::local_transform(int node) const {
  const auto& n = model_.nodes[std::size_t(node)];
  const std::string where = fmt::format("nodes[{}]", node);
  glm::mat4 m(1.0f);
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(m)[i] = float(n.matrix[std::size_t(i)]);  // column-major
  } else {
    if (!n.matrix.empty()) error(where + ".matrix", "must have 16 numbers");
    glm::vec3 t(0.0f), s(1.0f);
    glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
    if (n.translation.size() == 3)
      t = {float(n.translation[0]), float(n.translation[1]), float(n.translation[2])};
    else if (!n.translation.empty())
      error(where + ".translation", "must have 3 numbers");
    if (n.rotation.size() == 4)  // glTF stores (x, y, z, w); glm::quat takes (w, x, y, z)
      r = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                    float(n.rotation[2]));
    else if (!n.rotation.empty())
      error(where + ".rotation", "must have 4 numbers");
    if (n.scale.size() == 3)
      s = {float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
    else if (!n.scale.empty())
      error(where + ".scale", "must have 3 numbers");
    const float len = glm::length(r);
    if (std::isfinite(len) && len > 0.0f) r = r / len;
    m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
  }
  if (!finite_matrix(m)) error(where, "transform has NaN or infinite values");
  return m;
}

void Loader::build_nodes() {
  const std::size_t count = model_.nodes.size();
  // The hierarchy must be a set of disjoint trees (glTF 2.0 section 3.5.3).
  std::vector<int> parent(count, -1);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t k = 0; k < model_.nodes[i].children.size(); ++k) {
      const int c = model_.nodes[i].children[k];
      const std::string where = fmt::format("nodes[{}].children[{}]", i, k);
      if (c < 0 || std::size_t(c) >= count)
        error(where, fmt::format("node {} does not exist ({} nodes)", c, count));
      if (std::size_t(c) == i) error(where, fmt::format("node {} is its own child (cycle)", c));
      if (parent[std::size_t(c)] >= 0)
        error(where, fmt::format("node {} already has parent {} (cycle or shared child)", c,
                                 parent[std::size_t(c)]));
      parent[std::size_t(c)] = int(i);
    }
  // With one parent each, a cycle is a parent chain that never reaches a root.
  std::vector<char> state(count, 0);  // 0 unknown, 1 on the current chain, 2 reaches a root
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<std::size_t> chain;
    for (std::size_t j = i;;) {
      if (state[j] == 2) break;
      if (state[j] == 1)
        error(fmt::format("nodes[{}]", j), "is part of a cycle in the node hierarchy");
      state[j] = 1;
      chain.push_back(j);
      if (parent[j] < 0) break;
      j = std::size_t(parent[j]);
    }
    for (std::size_t k : chain) state[k] = 2;
  }

  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    int s = model_.defaultScene;
    if (s < 0) s = 0;
    if (std::size_t(s) >= model_.scenes.size())
      error("scene", fmt::format("scene {} does not exist", s));
    if (model_.scenes.size() > 1)
      note("{}: {} scenes; showing scene {}", file_, model_.scenes.size(), s);
    for (std::size_t k = 0; k < model_.scenes[std::size_t(s)].nodes.size(); ++k) {
      const int r = model_.scenes[std::size_t(s)].nodes[k];
      const std::string where = fmt::format("scenes[{}].nodes[{}]", s, k);
      if (r < 0 || std::size_t(r) >= count) error(where, fmt::format("node {} does not exist", r));
      if (parent[std::size_t(r)] >= 0)
        error(where,
              fmt::format("node {} is not a root (its parent is {})", r, parent[std::size_t(r)]));
      if (std::find(roots.begin(), roots.end(), r) != roots.end())
        error(where, fmt::format("node {} is listed twice", r));
      roots.push_back(r);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i)
      if (parent[i] < 0) roots.push_back(int(i));
  }

  std::map<int, std::vector<int>> mesh_cache;  // glTF mesh -> our meshes (default weights)
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f)});
  while (!stack.empty()) {
    const auto [node, parent_world] = stack.back();
    stack.pop_back();
    const auto& n = model_.nodes[std::size_t(node)];
    const glm::mat4 world = parent_world * local_transform(node);
    if (!finite_matrix(world))
      error(fmt::format("nodes[{}]", node), "accumulated transform overflows");
    const std::string where = fmt::format("nodes[{}]", node);
    if (n.mesh >= 0) {
      if (std::size_t(n.mesh) >= model_.meshes.size())
        error(where + ".mesh", fmt::format("mesh {} does not exist", n.mesh));
      const auto& gmesh = model_.meshes[std::size_t(n.mesh)];
      std::vector<int> meshes;
      if (!n.weights.empty() && n.weights != gmesh.weights) {
        meshes = build_mesh(n.mesh, n.weights);
      } else {
        auto cached = mesh_cache.find(n.mesh);
        if (cached == mesh_cache.end())
          cached = mesh_cache.emplace(n.mesh, build_mesh(n.mesh, gmesh.weights)).first;
        meshes = cached->second;
      }
      for (int m : meshes) {
        scene_.instances.push_back({m, world, node});
        triangles_ += scene_.meshes[std::size_t(m)].triangle_count();
        if (triangles_ > options_.limits.max_triangles)
          error(where, fmt::format("the scene exceeds the limit of {} triangles",
                                   options_.limits.max_triangles));
      }
    }
    if (n.camera >= 0) {
      if (std::size_t(n.camera) >= model_.cameras.size())
        error(where + ".camera", fmt::format("camera {} does not exist", n.camera));
      const auto& g = model_.cameras[std::size_t(n.camera)];
      const std::string cpath = fmt::format("cameras[{}]", n.camera);
      Camera c;
      c.name = g.name.empty() ? cpath : g.name;
      if (g.type == "perspective") {
        const auto& p = g.perspective;
        if (!(p.yfov > 0.0 && p.yfov < 3.14159))
          error(cpath + ".perspective.yfov", fmt::format("{} is not in (0, pi)", p.yfov));
        if (!(p.znear > 0.0) || !std::isfinite(p.znear))
          error(cpath + ".perspective.znear", "must be positive");
        if (p.zfar != 0.0 && !(p.zfar > p.znear))
          error(cpath + ".perspective.zfar", "must be greater than znear");
        if (p.aspectRatio < 0.0 || !std::isfinite(p.aspectRatio))
          error(cpath + ".perspective.aspectRatio", "must be positive");
        c.type = Camera::Type::kPerspective;
        c.yfov = float(p.yfov);
        if (p.aspectRatio > 0.0) c.aspect_ratio = float(p.aspectRatio);
        c.znear = float(p.znear);
        if (p.zfar > 0.0 && std::isfinite(p.zfar)) c.zfar = float(p.zfar);
      } else if (g.type == "orthographic") {
        const auto& o = g.orthographic;
        if (!(std::fabs(o.xmag) > 0.0) || !(std::fabs(o.ymag) > 0.0) || !std::isfinite(o.xmag) ||
            !std::isfinite(o.ymag))
          error(cpath + ".orthographic", "xmag and ymag must be non-zero");
        if (!(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar))
          error(cpath + ".orthographic", "needs 0 <= znear < zfar");
        c.type = Camera::Type::kOrthographic;
        c.xmag = float(o.xmag);
        c.ymag = float(o.ymag);
        c.znear = float(o.znear);
        c.zfar = float(o.zfar);
      } else {
        error(cpath + ".type", fmt::format("invalid camera type '{}'", g.type));
      }
      // Rigid part of the node transform: the spec's cameras ignore scale.
      glm::mat4 rigid = world;
      for (int axis = 0; axis < 3; ++axis) {
        const float len = glm::length(glm::vec3(rigid[axis]));
        if (!(len > 0.0f)) error(where, "camera node has a degenerate (zero-scale) transform");
        rigid[axis] = glm::vec4(glm::vec3(rigid[axis]) / len, 0.0f);
      }
      c.camera_to_world = rigid;
      scene_.cameras.push_back(c);
    }
    if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
      const tinygltf::Value& li = it->second.Get("light");
      if (!li.IsInt()) error(where + ".extensions.KHR_lights_punctual.light", "must be an integer");
      const int index = li.GetNumberAsInt();
      if (index < 0 || std::size_t(index) >= model_.lights.size())
        error(where + ".extensions.KHR_lights_punctual.light",
              fmt::format("light {} does not exist", index));
      const auto& g = model_.lights[std::size_t(index)];
      const std::string lpath = fmt::format("extensions.KHR_lights_punctual.lights[{}]", index);
      Light l;
      l.name = g.name.empty() ? fmt::format("light{}", index) : g.name;
      if (g.type == "point")
        l.type = Light::Type::kPoint;
      else if (g.type == "spot")
        l.type = Light::Type::kSpot;
      else if (g.type == "directional")
        l.type = Light::Type::kDirectional;
      else
        error(lpath + ".type", fmt::format("invalid light type '{}'", g.type));
      if (g.color.size() == 3) l.color = {float(g.color[0]), float(g.color[1]), float(g.color[2])};
      l.intensity = float(g.intensity);
      if (g.range > 0.0) l.range = float(g.range);
      if (l.type == Light::Type::kSpot) {
        l.inner_cone_angle = float(g.spot.innerConeAngle);
        l.outer_cone_angle = float(g.spot.outerConeAngle);
        if (!(l.inner_cone_angle >= 0.0f && l.inner_cone_angle < l.outer_cone_angle &&
              l.outer_cone_angle <= 1.5707964f))
          error(lpath + ".spot", "needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
      }
      if (!std::isfinite(l.intensity) || l.intensity < 0.0f ||
          !std::isfinite(l.color.x + l.color.y + l.color.z))
        error(lpath, "color and intensity must be finite and non-negative");
      l.position = glm::vec3(world[3]);
      const glm::vec3 d = glm::vec3(world * glm::vec4(0, 0, -1, 0));
      l.direction = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, -1);
      scene_.lights.push_back(l);
    }
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world});
  }
}

Scene Loader::load() {
  scene_.source = file_;
  parse_container();

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
  for (std::size_t i = 0; i < model_.buffers.size(); ++i) {
    if (model_.buffers[i].data.size() > options_.limits.max_buffer_bytes)
      error(fmt::format("buffers[{}]", i), "exceeds the buffer size limit");
  }
  for (const auto& [index, length] : meshopt_fallbacks_)
    if (index < model_.buffers.size()) model_.buffers[index].data.assign(length, 0);
  check_buffer_views();
  decode_meshopt_views();
  decode_draco_primitives();
  if (!model_.animations.empty())
    note("{}: {} animation(s) ignored (the scene is shown at rest)", file_,
         model_.animations.size());
  if (!model_.skins.empty()) note("{}: {} skin(s) shown in bind pose", file_, model_.skins.size());
  build_materials();
  build_nodes();
  scene_.node_count = model_.nodes.size();
  return std::move(scene_);
}

}  // namespace

std::vector<std::string> supported_gltf_extensions() {
  return {kSupportedExtensions.begin(), kSupportedExtensions.end()};
}

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
  return Loader(path, options).load();
}

Scene load_gltf_from_memory(std::string bytes, const std::filesystem::path& name,
                            const LoadOptions& options) {
  return Loader(std::move(bytes), name, options).load();
}

}  // namespace pbrkit
