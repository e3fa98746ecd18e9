// Writing a Scene as binary glTF, so the built-in scenes can be rendered by any glTF
// tool. Attributes are written as FLOAT / UNSIGNED_INT so they round-trip exactly.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <stb_image_write.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "pbrkit/core/color.h"
#include "pbrkit/scene/gltf_container.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// glTF's emissiveFactor is limited to [0, 1] (material schema); brighter emission is the
// factor times KHR_materials_emissive_strength. A factor above 1 (a built-in or loaded
// scene's) is written as its colour over its largest component, with that component
// moved into the strength, so the emitted radiance (factor * strength) is unchanged.
Material with_gltf_emission(const Material& m) {
  Material out = m;
  const float peak = std::max({m.emissive_factor.r, m.emissive_factor.g, m.emissive_factor.b});
  if (peak > 1.0f) {
    out.emissive_factor = m.emissive_factor / peak;
    out.emissive_strength = m.emissive_strength * peak;
  }
  return out;
}

class Writer {
 public:
  Writer(const Scene& scene, const GltfWriteOptions& options) : scene_(scene), options_(options) {
    model_.buffers.emplace_back();
  }

  tinygltf::Model build();

 private:
  int add_view(const void* data, std::size_t bytes, int target) {
    auto& buf = model_.buffers[0].data;
    while (buf.size() % 4 != 0) buf.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return int(model_.bufferViews.size()) - 1;
  }

  template <typename V>
  int add_attribute(const std::vector<V>& values, int type, bool with_bounds) {
    tinygltf::Accessor a;
    a.bufferView = add_view(values.data(), values.size() * sizeof(V), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = type;
    a.count = values.size();
    if (with_bounds) {  // POSITION requires min and max
      V lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (const V& v : values) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
      for (int c = 0; c < V::length(); ++c) {
        a.minValues.push_back(lo[c]);
        a.maxValues.push_back(hi[c]);
      }
    }
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
  }

  int add_texture(const Texture& t);
  tinygltf::TextureInfo texture_info(const TextureRef& ref);
  void add_material(const Material& m);
  tinygltf::ExtensionMap material_extensions(const Material& m);
  void add_mesh(const Mesh& m);
  int add_instanced_node(int mesh, const std::vector<const Instance*>& instances);

  const Scene& scene_;
  const GltfWriteOptions& options_;
  tinygltf::Model model_;
};

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* p = static_cast<const unsigned char*>(data);
  out->insert(out->end(), p, p + size);
}

int Writer::add_texture(const Texture& t) {
  // 8-bit PNG of the top mip, sRGB-encoded for colour textures (glTF's convention).
  if (t.empty()) fail("write_glb: texture '{}' has no pixels", t.name);
  const Image img = t.level_image(0);
  std::vector<unsigned char> pixels(img.pixel_count() * 4);
  for (std::size_t i = 0; i < img.pixel_count(); ++i)
    for (int c = 0; c < 4; ++c) {
      float v =
          img.data[i * std::size_t(img.channels) + std::size_t(std::min(c, img.channels - 1))];
      if (c < 3 && t.srgb) v = srgb_encode(v);
      pixels[i * 4 + std::size_t(c)] =
          static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
  std::vector<unsigned char> png;
  if (!stbi_write_png_to_func(&append_bytes, &png, img.width, img.height, 4, pixels.data(),
                              img.width * 4))
    fail("write_glb: cannot encode texture '{}' as PNG", t.name);
  tinygltf::Image image;
  image.name = t.name;
  image.mimeType = "image/png";
  image.bufferView = add_view(png.data(), png.size(), 0);
  model_.images.push_back(image);
  tinygltf::Sampler s;
  auto wrap = [](WrapMode w) {
    return w == WrapMode::kClampToEdge      ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
           : w == WrapMode::kMirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT
                                            : TINYGLTF_TEXTURE_WRAP_REPEAT;
  };
  s.wrapS = wrap(t.sampler.wrap_s);
  s.wrapT = wrap(t.sampler.wrap_t);
  s.magFilter = t.sampler.mag == FilterMode::kNearest ? TINYGLTF_TEXTURE_FILTER_NEAREST
                                                      : TINYGLTF_TEXTURE_FILTER_LINEAR;
  const bool near = t.sampler.min == FilterMode::kNearest;
  s.minFilter = t.sampler.min_mipmap
                    ? (near ? TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR
                            : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR)
                    : (near ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR);
  model_.samplers.push_back(s);
  tinygltf::Texture tex;
  tex.source = int(model_.images.size()) - 1;
  tex.sampler = int(model_.samplers.size()) - 1;
  model_.textures.push_back(tex);
  return int(model_.textures.size()) - 1;
}

tinygltf::TextureInfo Writer::texture_info(const TextureRef& ref) {
  tinygltf::TextureInfo info;
  if (!ref.valid()) return info;
  if (ref.texture >= int(scene_.textures.size()))
    fail("write_glb: texture {} does not exist", ref.texture);
  info.index = ref.texture;
  info.texCoord = ref.texcoord;
  if (ref.transform) {
    tinygltf::Value::Object o;
    o["offset"] =
        tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(ref.transform->offset.x)),
                                               tinygltf::Value(double(ref.transform->offset.y))});
    o["scale"] =
        tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(ref.transform->scale.x)),
                                               tinygltf::Value(double(ref.transform->scale.y))});
    o["rotation"] = tinygltf::Value(double(ref.transform->rotation));
    info.extensions["KHR_texture_transform"] = tinygltf::Value(o);
  }
  return info;
}

// A textureInfo inside an extension object: {"index", "texCoord", KHR_texture_transform}
// as texture_info() writes them for the core textures; `scale` for a normalTextureInfo.
void put_texture(tinygltf::Value::Object& o, const char* name, const tinygltf::TextureInfo& info,
                 std::optional<float> scale = std::nullopt) {
  if (info.index < 0) return;
  tinygltf::Value::Object t;
  t["index"] = tinygltf::Value(info.index);
  if (info.texCoord != 0) t["texCoord"] = tinygltf::Value(info.texCoord);
  if (scale && *scale != 1.0f) t["scale"] = tinygltf::Value(double(*scale));
  if (!info.extensions.empty()) {
    tinygltf::Value::Object e(info.extensions.begin(), info.extensions.end());
    t["extensions"] = tinygltf::Value(e);
  }
  o[name] = tinygltf::Value(t);
}

// The KHR_materials_* extensions the material uses, as the material schema lists them,
// each with the values that differ from the README's defaults (a value JSON cannot write,
// as an infinite attenuationDistance, is its default). KHR_materials_unlit excludes the
// others (each of their READMEs says so, and the glTF-Validator reports the combination),
// so an unlit material is written with KHR_materials_unlit only (the validator reports
// KHR_materials_emissive_strength beside it too): what a viewer would show of it.
tinygltf::ExtensionMap Writer::material_extensions(const Material& m) {
  tinygltf::ExtensionMap out;
  const auto extensions = material_schema();
  const bool exclusive = std::any_of(extensions.begin(), extensions.end(),
                                     [&](const auto& x) { return x.exclusive && x.present(m); });
  for (const MaterialExtension& x : extensions) {
    if (!x.present(m) || (exclusive && !x.exclusive)) continue;
    tinygltf::Value::Object o;
    for (const MaterialFactor& f : x.factors) {
      const float* v = f.read(m);
      bool finite = true, differs = false;
      tinygltf::Value::Array values;
      for (int c = 0; c < f.components; ++c) {
        finite &= std::isfinite(v[c]);
        differs |= v[c] != factor_default(x, f, c);
        values.emplace_back(double(v[c]));
      }
      if (finite && differs)
        o[f.json_name] = f.components == 1 ? values[0] : tinygltf::Value(std::move(values));
    }
    for (const MaterialTexture& t : x.textures)
      put_texture(
          o, t.json_name, texture_info(*m.textures()[std::size_t(t.slot)]),
          t.scale ? std::optional<float>(*t.scale(const_cast<Material&>(m))) : std::nullopt);
    out[x.name] = tinygltf::Value(std::move(o));
  }
  return out;
}

void Writer::add_material(const Material& material) {
  const Material m = with_gltf_emission(material);
  tinygltf::Material g;
  g.name = m.name;
  auto& pbr = g.pbrMetallicRoughness;
  pbr.baseColorFactor.assign(
      {m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b, m.base_color_factor.a});
  pbr.metallicFactor = m.metallic_factor;
  pbr.roughnessFactor = m.roughness_factor;
  pbr.baseColorTexture = texture_info(m.base_color_texture);
  pbr.metallicRoughnessTexture = texture_info(m.metallic_roughness_texture);
  g.emissiveFactor.assign({m.emissive_factor.r, m.emissive_factor.g, m.emissive_factor.b});
  g.emissiveTexture = texture_info(m.emissive_texture);
  for (auto& [name, value] : material_extensions(m)) g.extensions[name] = std::move(value);
  const tinygltf::TextureInfo normal = texture_info(m.normal_texture);
  g.normalTexture.index = normal.index;
  g.normalTexture.texCoord = normal.texCoord;
  g.normalTexture.extensions = normal.extensions;
  g.normalTexture.scale = m.normal_scale;
  const tinygltf::TextureInfo occlusion = texture_info(m.occlusion_texture);
  g.occlusionTexture.index = occlusion.index;
  g.occlusionTexture.texCoord = occlusion.texCoord;
  g.occlusionTexture.extensions = occlusion.extensions;
  g.occlusionTexture.strength = m.occlusion_strength;
  g.alphaMode = m.alpha_mode == AlphaMode::kMask    ? "MASK"
                : m.alpha_mode == AlphaMode::kBlend ? "BLEND"
                                                    : "OPAQUE";
  // The material schema: alphaCutoff is ignored unless alphaMode is MASK and must not be
  // given when alphaMode is absent (as tinygltf writes OPAQUE); tinygltf leaves out 0.5.
  g.alphaCutoff = m.alpha_mode == AlphaMode::kMask ? m.alpha_cutoff : 0.5f;
  g.doubleSided = m.double_sided;
  model_.materials.push_back(g);
}

// KHR_materials_variants (README, "Mappings"): each material a primitive takes under some
// variant, with the variants that choose it; null when no variant changes its material
// (entries that only change the closure are decided again when the file loads).
std::optional<tinygltf::Value> variant_mappings(const Mesh& m) {
  std::map<int, tinygltf::Value::Array> variants;  // material -> the variants choosing it
  for (const VariantMaterial& v : m.variant_materials)
    if (v.variant >= 0 && v.material >= 0 && v.material != m.variant_materials.front().material)
      variants[v.material].push_back(tinygltf::Value(v.variant));
  if (variants.empty()) return std::nullopt;
  tinygltf::Value::Array mappings;
  for (auto& [material, list] : variants)
    mappings.push_back(tinygltf::Value(tinygltf::Value::Object{
        {"material", tinygltf::Value(material)}, {"variants", tinygltf::Value(std::move(list))}}));
  return tinygltf::Value(
      tinygltf::Value::Object{{"mappings", tinygltf::Value(std::move(mappings))}});
}

void Writer::add_mesh(const Mesh& m) {
  tinygltf::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.material = m.material;
  if (!m.variant_materials.empty()) {
    // The file's own material, whichever variant the scene holds, and the others mapped.
    p.material = m.variant_materials.front().material;
    if (auto mappings = variant_mappings(m)) p.extensions["KHR_materials_variants"] = *mappings;
  }
  p.attributes["POSITION"] = add_attribute(m.positions, TINYGLTF_TYPE_VEC3, true);
  if (!m.normals.empty())
    p.attributes["NORMAL"] = add_attribute(m.normals, TINYGLTF_TYPE_VEC3, false);
  if (!m.tangents.empty())
    p.attributes["TANGENT"] = add_attribute(m.tangents, TINYGLTF_TYPE_VEC4, false);
  if (!m.texcoords0.empty())
    p.attributes["TEXCOORD_0"] = add_attribute(m.texcoords0, TINYGLTF_TYPE_VEC2, false);
  if (!m.texcoords1.empty())
    p.attributes["TEXCOORD_1"] = add_attribute(m.texcoords1, TINYGLTF_TYPE_VEC2, false);
  if (!m.colors0.empty())
    p.attributes["COLOR_0"] = add_attribute(m.colors0, TINYGLTF_TYPE_VEC4, false);
  tinygltf::Accessor idx;
  idx.bufferView =
      add_view(m.indices.data(), m.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  idx.type = TINYGLTF_TYPE_SCALAR;
  idx.count = m.indices.size();
  model_.accessors.push_back(idx);
  p.indices = int(model_.accessors.size()) - 1;
  tinygltf::Mesh g;
  g.name = m.name;
  g.primitives.push_back(p);
  model_.meshes.push_back(g);
}

// An affine transform as glTF's translation, rotation (x, y, z, w) and scale, when it is one:
// its 3x3 part's columns orthogonal (no shear), and nothing but a 1 in the last row. A
// mirror (negative determinant) becomes a negative x scale. The transform rebuilt from the
// three must match within float rounding, else there is none (the instance is written as
// a node with a matrix instead).
struct Trs {
  glm::vec3 translation;
  glm::quat rotation;
  glm::vec3 scale;
};
std::optional<Trs> decompose(const glm::mat4& m) {
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return {};
  Trs trs;
  trs.translation = glm::vec3(m[3]);
  glm::mat3 r(m);
  for (int c = 0; c < 3; ++c) {
    trs.scale[c] = glm::length(r[c]);
    if (!(trs.scale[c] > 0.0f) || !std::isfinite(trs.scale[c])) return {};
    r[c] /= trs.scale[c];
  }
  if (glm::determinant(r) < 0.0f) {
    trs.scale.x = -trs.scale.x;
    r[0] = -r[0];
  }
  trs.rotation = glm::normalize(glm::quat_cast(r));
  const glm::mat3 rebuilt = glm::mat3_cast(trs.rotation) * glm::mat3(glm::vec3(trs.scale.x, 0, 0),
                                                                     glm::vec3(0, trs.scale.y, 0),
                                                                     glm::vec3(0, 0, trs.scale.z));
  const float size = std::max({trs.scale.x, trs.scale.y, trs.scale.z, -trs.scale.x});
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (std::fabs(rebuilt[c][k] - m[c][k]) > 1e-5f * size) return {};
  return trs;
}

// EXT_mesh_gpu_instancing: one node drawing `mesh` at each instance's transform, as
// TRANSLATION, ROTATION and SCALE accessors of FLOAT (the README's table); the node's own
// transform is the identity, so an instance's world transform is its T * R * S.
int Writer::add_instanced_node(int mesh, const std::vector<const Instance*>& instances) {
  std::vector<glm::vec3> t, s;
  std::vector<glm::vec4> r;
  for (const Instance* inst : instances) {
    const Trs trs = *decompose(inst->transform);
    t.push_back(trs.translation);
    r.push_back(glm::vec4(trs.rotation.x, trs.rotation.y, trs.rotation.z, trs.rotation.w));
    s.push_back(trs.scale);
  }
  auto accessor = [&](const auto& values, int type) {
    tinygltf::Accessor a;
    a.bufferView = add_view(values.data(), values.size() * sizeof(values[0]), 0);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = type;
    a.count = values.size();
    model_.accessors.push_back(a);
    return tinygltf::Value(int(model_.accessors.size()) - 1);
  };
  tinygltf::Value::Object attributes;
  attributes["TRANSLATION"] = accessor(t, TINYGLTF_TYPE_VEC3);
  attributes["ROTATION"] = accessor(r, TINYGLTF_TYPE_VEC4);
  attributes["SCALE"] = accessor(s, TINYGLTF_TYPE_VEC3);
  tinygltf::Value::Object extension;
  extension["attributes"] = tinygltf::Value(attributes);
  tinygltf::Node n;
  n.mesh = mesh;
  n.extensions["EXT_mesh_gpu_instancing"] = tinygltf::Value(extension);
  model_.nodes.push_back(n);
  return int(model_.nodes.size()) - 1;
}

// node.matrix, column-major; empty (left out) for the identity, which is its default.
std::vector<double> matrix_values(const glm::mat4& m) {
  std::vector<double> v;
  if (m == glm::mat4(1.0f)) return v;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) v.push_back(m[c][r]);
  return v;
}

tinygltf::Model Writer::build() {
  model_.asset.version = "2.0";
  model_.asset.generator = "pbrkit";
  for (const Texture& t : scene_.textures) add_texture(t);
  for (const Material& m : scene_.materials) add_material(m);
  for (const Mesh& m : scene_.meshes) {
    if (m.material >= int(scene_.materials.size()))
      fail("write_glb: mesh '{}' has an invalid material", m.name);
    add_mesh(m);
  }
  tinygltf::Scene gscene;
  // A mesh drawn more than once (each Mesh has one material, so its instances share it) is
  // written as one node with EXT_mesh_gpu_instancing, in the order of its first instance;
  // instances whose transform is not a translation, rotation and scale stay nodes of their
  // own with a matrix. Flattened, every instance is a node of its own (sharing its mesh).
  std::vector<std::vector<const Instance*>> by_mesh(scene_.meshes.size());
  std::vector<char> has_trs(scene_.instances.size(), 0);
  for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
    const Instance& inst = scene_.instances[i];
    if (inst.mesh < 0 || std::size_t(inst.mesh) >= scene_.meshes.size())
      fail("write_glb: an instance has an invalid mesh {}", inst.mesh);
    has_trs[i] = decompose(inst.transform).has_value();
    if (has_trs[i]) by_mesh[std::size_t(inst.mesh)].push_back(&inst);
  }
  std::vector<char> written(scene_.meshes.size(), 0);
  bool instanced = false;
  for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
    const Instance& inst = scene_.instances[i];
    const auto mesh = std::size_t(inst.mesh);
    if (!options_.flatten_instances && has_trs[i] && by_mesh[mesh].size() > 1) {
      if (!written[mesh]) {
        gscene.nodes.push_back(add_instanced_node(inst.mesh, by_mesh[mesh]));
        written[mesh] = 1;
        instanced = true;
      }
      continue;
    }
    tinygltf::Node n;
    n.mesh = inst.mesh;
    n.matrix = matrix_values(inst.transform);
    model_.nodes.push_back(n);
    gscene.nodes.push_back(int(model_.nodes.size()) - 1);
  }
  for (const Camera& c : scene_.cameras) {
    tinygltf::Camera g;
    g.name = c.name;
    if (c.type == Camera::Type::kPerspective) {
      g.type = "perspective";
      g.perspective.yfov = c.yfov;
      g.perspective.aspectRatio = c.aspect_ratio.value_or(0.0f);
      g.perspective.znear = c.znear;
      g.perspective.zfar = c.zfar.value_or(0.0f);
    } else {
      g.type = "orthographic";
      g.orthographic.xmag = c.xmag;
      g.orthographic.ymag = c.ymag;
      g.orthographic.znear = c.znear;
      g.orthographic.zfar = c.zfar.value_or(c.znear + 1e6f);
    }
    model_.cameras.push_back(g);
    tinygltf::Node n;
    n.name = c.name;
    n.camera = int(model_.cameras.size()) - 1;
    n.matrix = matrix_values(c.camera_to_world);
    model_.nodes.push_back(n);
    gscene.nodes.push_back(int(model_.nodes.size()) - 1);
  }
  for (const Light& l : scene_.lights) {
    tinygltf::Light g;
    g.name = l.name;
    g.type = l.type == Light::Type::kPoint  ? "point"
             : l.type == Light::Type::kSpot ? "spot"
                                            : "directional";
    g.color = {l.color.r, l.color.g, l.color.b};
    g.intensity = l.intensity;
    // KHR_lights_punctual: range bounds point and spot lights only (tinygltf leaves out 0).
    g.range = l.type == Light::Type::kDirectional ? 0.0f : l.range.value_or(0.0f);
    g.spot.innerConeAngle = l.inner_cone_angle;
    g.spot.outerConeAngle = l.outer_cone_angle;
    model_.lights.push_back(g);
    // A node at the light's position whose -Z is the light direction.
    const glm::vec3 d = glm::normalize(l.direction);
    const glm::vec3 helper = std::fabs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 x = glm::normalize(glm::cross(helper, -d));
    const glm::vec3 y = glm::cross(-d, x);
    glm::mat4 m(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(-d, 0), glm::vec4(l.position, 1));
    tinygltf::Node n;
    n.name = l.name;
    n.matrix = matrix_values(m);
    tinygltf::Value::Object o;
    o["light"] = tinygltf::Value(int(model_.lights.size()) - 1);
    n.extensions["KHR_lights_punctual"] = tinygltf::Value(o);
    model_.nodes.push_back(n);
    gscene.nodes.push_back(int(model_.nodes.size()) - 1);
  }
  model_.scenes.push_back(gscene);
  model_.defaultScene = 0;
  model_.buffers[0].data.resize((model_.buffers[0].data.size() + 3) / 4 * 4, 0);
  // buffer.byteLength must be at least 1: a scene without meshes or textures has no buffer.
  if (model_.buffers[0].data.empty()) model_.buffers.clear();
  auto uses = [&](const char* ext) { model_.extensionsUsed.push_back(ext); };
  if (!scene_.lights.empty()) uses("KHR_lights_punctual");
  if (!scene_.variants.empty()) {
    tinygltf::Value::Array variants;
    for (const std::string& name : scene_.variants)
      variants.push_back(tinygltf::Value(tinygltf::Value::Object{{"name", tinygltf::Value(name)}}));
    model_.extensions["KHR_materials_variants"] = tinygltf::Value(
        tinygltf::Value::Object{{"variants", tinygltf::Value(std::move(variants))}});
    uses("KHR_materials_variants");
  }
  if (instanced) {
    // The README: "files that use the extension should specify it in extensionsRequired"
    // (it has no fallback for viewers without it).
    uses("EXT_mesh_gpu_instancing");
    model_.extensionsRequired.push_back("EXT_mesh_gpu_instancing");
  }
  // Each material extension once, in the order the materials first use them.
  for (const tinygltf::Material& g : model_.materials)
    for (const auto& [name, value] : g.extensions)
      if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), name) ==
          model_.extensionsUsed.end())
        uses(name.c_str());
  // Only the textures written count (an unlit material's extension textures are not).
  auto has_transform = [](const Material& m) {
    const auto slots = m.textures();
    const std::size_t written =
        m.unlit ? std::size_t(kFirstExtensionTextureSlot) : std::size_t(kTextureSlotCount);
    for (std::size_t i = 0; i < written; ++i)
      if (slots[i]->valid() && slots[i]->transform) return true;
    return false;
  };
  if (std::any_of(scene_.materials.begin(), scene_.materials.end(), has_transform))
    uses("KHR_texture_transform");
  return std::move(model_);
}

// tinygltf 2.7 writes a perspective camera's zfar always (0.0 for "none") and its
// aspectRatio when positive, but the camera.perspective schema requires both to be positive
// (zfar also greater than znear) and gives their absence a meaning: an infinite projection
// (glTF 2.0, Cameras, "Projection Matrices") and the viewport's aspect ratio. A written
// "zfar": 0.0 makes Blender clip every ray. So the GLB's JSON chunk is rewritten without
// the values the scene's cameras do not have; the BIN chunk is kept as it is (section 4.4:
// the JSON chunk is padded with spaces to 4 bytes).
std::string omit_absent_camera_values(const std::string& glb, const Scene& scene,
                                      const std::string& name) {
  const GlbChunks chunks = parse_glb(glb.data(), glb.size(), name);
  nlohmann::json gltf = nlohmann::json::parse(chunks.json, chunks.json + chunks.json_size);
  for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
    const Camera& c = scene.cameras[i];
    if (c.type != Camera::Type::kPerspective) continue;
    nlohmann::json& perspective = gltf["cameras"][i]["perspective"];  // model order = scene order
    if (!c.zfar) perspective.erase("zfar");
    if (!c.aspect_ratio) perspective.erase("aspectRatio");
  }
  std::string json = gltf.dump();
  while (json.size() % 4 != 0) json.push_back(' ');
  std::string out;
  auto u32 = [&out](std::size_t v) {
    const auto le = std::uint32_t(v);  // GLB is little-endian, like every platform we build for
    out.append(reinterpret_cast<const char*>(&le), 4);
  };
  out += "glTF";
  u32(2);
  u32(12 + 8 + json.size() + (chunks.bin ? 8 + chunks.bin_size : 0));
  u32(json.size());
  u32(0x4E4F534A);  // "JSON"
  out += json;
  if (chunks.bin) {
    u32(chunks.bin_size);
    u32(0x004E4942);  // "BIN\0"
    out.append(reinterpret_cast<const char*>(chunks.bin), chunks.bin_size);
  }
  return out;
}

}  // namespace

void write_glb(const Scene& scene, const std::filesystem::path& path,
               const GltfWriteOptions& options) {
  tinygltf::Model model = Writer(scene, options).build();
  std::ostringstream glb;
  tinygltf::TinyGLTF gltf;
  // prettyPrint, writeBinary (buffers and images go into the BIN chunk)
  if (!gltf.WriteGltfSceneToStream(&model, glb, false, true))
    fail("{}: cannot write the glTF file", path.string());
  const std::string bytes = omit_absent_camera_values(glb.str(), scene, path.string());
  write_file_atomically(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) fail("{}: cannot write the glTF file", path.string());
  });
}

}  // namespace pbrkit
