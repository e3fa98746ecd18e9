// Reading accessors (glTF 2.0 section 3.6): every accessor is checked against its buffer
// view (overflow-safe, count bounded first) before a byte is read, sparse substitutions
// included; normalized integers are converted per section 3.11.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

namespace {

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

}  // namespace

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

}  // namespace pbrkit::gltf
