// EXT_meshopt_compression: buffer views whose bytes are decoded by meshoptimizer, and the
// fallback buffers those bytes are decoded into.
#include <cstdint>
#include <cstring>

#include <meshoptimizer.h>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

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

// The placeholder buffers get their declared size once tinygltf has parsed the file.
void Loader::size_meshopt_fallbacks() {
  for (const auto& [index, length] : meshopt_fallbacks_)
    if (index < model_.buffers.size()) model_.buffers[index].data.assign(length, 0);
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

}  // namespace pbrkit::gltf
