// KHR_draco_mesh_compression: primitives whose attributes and indices come from a Draco
// stream, decoded into synthetic accessors so the ordinary mesh path reads them.
#include <cstdint>
#include <cstring>
#include <memory>

#include <draco/compression/decode.h>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

// tinygltf insists that an indices accessor has a bufferView, which a Draco-compressed
// primitive's does not (its indices come from the Draco stream): drop those references
// before tinygltf parses the JSON.
bool Loader::drop_draco_indices(json& root) const {
  bool modified = false;
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
  return modified;
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

}  // namespace pbrkit::gltf
