// Checking a glTF file's JSON before anything trusts it (types, version, extensions, URIs
// and the sizes they declare), and the buffers and buffer views tinygltf produced; every
// message names the file and the JSON path of the bad element.
#include <algorithm>
#include <cstdint>
#include <set>

#include "pbrkit/scene/asset_uri.h"
#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit {

namespace gltf {

namespace {

// Extensions this loader implements; any other one in extensionsRequired is an error. The
// KHR_materials_* ones are the material schema's.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> kNames = [] {
    std::set<std::string> names = {
        "KHR_texture_transform",      "KHR_lights_punctual",     "KHR_mesh_quantization",
        "KHR_draco_mesh_compression", "EXT_meshopt_compression", "EXT_mesh_gpu_instancing",
        "KHR_materials_variants",     "KHR_node_visibility",     "KHR_animation_pointer"};
    for (const MaterialExtension& e : material_schema()) names.insert(e.name);
    return names;
  }();
  return kNames;
}

}  // namespace

void Loader::error(const std::string& where, const std::string& what) const {
  if (where.empty()) fail("{}: {}", file_, what);
  fail("{}: {}: {}", file_, where, what);
}

void Loader::warning(const std::string& message) {
  const std::string line = fmt::format("{}: {}", file_, message);
  warn("{}", line);
  scene_.warnings.push_back(message);
}

json Loader::parse_json() const {
  json root;
  try {
    root = json::parse(json_text_);
  } catch (const json::exception& e) {
    error("", fmt::format("invalid JSON: {}", e.what()));
  }
  return root;
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
    if (!supported_extensions().count(e))
      error(fmt::format("extensionsRequired[{}]", i),
            fmt::format("required extension '{}' is not supported", e));
  }
  for (const std::string& e : scene_.extensions_used)
    if (!supported_extensions().count(e) &&
        std::find(scene_.extensions_required.begin(), scene_.extensions_required.end(), e) ==
            scene_.extensions_required.end())
      warning(fmt::format("optional extension '{}' is not supported and is ignored", e));
  // Each material's extensions object as the file has it, for material_extensions.cpp.
  material_extensions_.clear();
  if (root.contains("materials"))
    for (const json& material : root["materials"]) {
      const auto it = material.find("extensions");
      material_extensions_.push_back(it != material.end() && it->is_object() ? *it
                                                                             : json::object());
    }
  // Node count for the cycle checks and `info`; each EXT_mesh_gpu_instancing object as the
  // file has it, for instancing.cpp (tinygltf drops a value that is not an object).
  node_instancing_.clear();
  if (root.contains("nodes")) {
    scene_.node_count = root["nodes"].size();
    for (std::size_t i = 0; i < root["nodes"].size(); ++i) {
      const json& node = root["nodes"][i];
      const auto ext = node.find("extensions");
      if (ext == node.end() || !ext->is_object()) continue;
      const auto it = ext->find("EXT_mesh_gpu_instancing");
      if (it != ext->end()) node_instancing_.emplace(int(i), *it);
    }
  }
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
        // The buffer schema's minimum; tinygltf would throw std::out_of_range copying a
        // BIN chunk into 0 bytes.
        if (is_buffer && arr[i]["byteLength"].get<std::uint64_t>() == 0)
          error(fmt::format("{}[{}].byteLength", key, i), "must be at least 1");
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

void Loader::check_buffers() const {
  for (std::size_t i = 0; i < model_.buffers.size(); ++i) {
    if (model_.buffers[i].data.size() > options_.limits.max_buffer_bytes)
      error(fmt::format("buffers[{}]", i), "exceeds the buffer size limit");
  }
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

}  // namespace gltf

std::vector<std::string> supported_gltf_extensions() {
  return {gltf::supported_extensions().begin(), gltf::supported_extensions().end()};
}

}  // namespace pbrkit
