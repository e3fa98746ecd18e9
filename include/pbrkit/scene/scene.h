#pragma once
// The renderer-neutral scene: what the glTF loader (and the built-in scene generators)
// produce and what both renderers consume. Everything is flattened to world space:
// instances carry the accumulated node transform (Embree supports one instancing level).
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"

namespace pbrkit {

struct SceneMotion;  // scene/pose.h

enum class WrapMode { kRepeat, kClampToEdge, kMirroredRepeat };
enum class FilterMode { kNearest, kLinear };

/// glTF sampler state (mipmapped minification uses trilinear when `min_mipmap`).
struct Sampler {
  WrapMode wrap_s = WrapMode::kRepeat;
  WrapMode wrap_t = WrapMode::kRepeat;
  FilterMode mag = FilterMode::kLinear;
  FilterMode min = FilterMode::kLinear;
  bool min_mipmap = true;
};

/// How a texture keeps its texels: at its source's precision.
enum class TexelFormat : std::uint8_t {
  kUnorm8,   ///< 8-bit PNG/JPEG samples (sRGB-encoded colour when `srgb`)
  kUnorm16,  ///< 16-bit PNG samples (sRGB-encoded colour when `srgb`)
  kFloat32,  ///< linear floats (OpenEXR, Radiance HDR, generated images)
};

/// One level of a texture's mip chain: its size and where its samples start in the
/// texture's storage (in samples, not bytes).
struct TextureLevel {
  int width = 0;
  int height = 0;
  std::size_t offset = 0;
};

/// A texture kept at its source's precision, with a full mip chain in the same precision
/// (levels[0] is the full-resolution image). 8/16-bit colour textures (`srgb`) hold
/// sRGB-encoded samples, decoded at lookup (8-bit through a 256-entry table); their mips
/// are box-filtered in linear space and re-encoded. Alpha is always linear. Channels are
/// the source's: 1 grey, 2 grey-alpha, 3 RGB, 4 RGBA; lookups expand them to RGBA.
struct Texture {
  std::string name;
  Sampler sampler;
  /// Colour data (baseColor, emissive, ...): integer samples are sRGB-encoded. Float
  /// samples are linear either way.
  bool srgb = false;
  TexelFormat format = TexelFormat::kFloat32;
  int channels = 0;
  std::vector<TextureLevel> levels;
  std::vector<std::uint8_t> texels8;    ///< kUnorm8 samples of every level
  std::vector<std::uint16_t> texels16;  ///< kUnorm16 samples of every level
  std::vector<float> texels32;          ///< kFloat32 samples of every level

  /// A float texture from linear `level0` (1 to 4 channels) and its box-filtered mips.
  static Texture from_linear(Image level0, bool srgb);
  /// An 8-bit texture from `channels`-interleaved samples (sRGB-encoded when `srgb`).
  static Texture from_unorm8(int width, int height, int channels, std::vector<std::uint8_t> samples,
                             bool srgb);
  /// A 16-bit texture, as from_unorm8.
  static Texture from_unorm16(int width, int height, int channels,
                              std::vector<std::uint16_t> samples, bool srgb);

  bool empty() const { return levels.empty(); }
  int width() const { return levels.empty() ? 0 : levels[0].width; }
  int height() const { return levels.empty() ? 0 : levels[0].height; }
  /// Memory the texels take, every level included (bytes).
  std::size_t bytes() const;
  /// The linear RGBA value of texel (x, y) of `level` (in range; no wrapping).
  glm::vec4 texel(int level, int x, int y) const;
  /// A level as a linear float RGBA image (for writers and float uploads).
  Image level_image(int level) const;
  /// The smallest alpha of the full-resolution level (1 without an alpha channel).
  float min_alpha() const;
  /// Filtered lookup (bilinear, or trilinear between mips at `lod`), honouring the wrap
  /// modes; uv origin is the top-left of the image, as glTF specifies.
  glm::vec4 sample(glm::vec2 uv, float lod = 0.0f) const;
};

/// KHR_texture_transform: uv' = T * R * S * uv.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
  glm::mat3 matrix() const;
};

/// A material's reference to a texture.
struct TextureRef {
  int texture = -1;  ///< index into Scene::textures, -1 for none
  int texcoord = 0;  ///< which TEXCOORD_n set
  std::optional<TextureTransform> transform;
  bool valid() const { return texture >= 0; }
};

enum class AlphaMode { kOpaque, kMask, kBlend };

// The KHR_materials_* surface extensions (docs/MODEL.md, "Inputs"). Each is absent
// (std::nullopt) when the material does not use it; the values are the extension's own
// factors with its README's defaults, and the textures hold the channels the README names.

/// KHR_materials_specular: the dielectric's F0 tint and strength.
struct SpecularExtension {
  float factor = 1.0f;           ///< specularFactor
  TextureRef texture;            ///< specularTexture, A channel (linear)
  glm::vec3 color_factor{1.0f};  ///< specularColorFactor (linear, may exceed 1)
  TextureRef color_texture;      ///< specularColorTexture, RGB (sRGB)
};

/// KHR_materials_clearcoat: a GGX dielectric coat (ior 1.5) over the whole material.
struct ClearcoatExtension {
  float factor = 0.0f;            ///< clearcoatFactor
  TextureRef texture;             ///< clearcoatTexture, R channel
  float roughness_factor = 0.0f;  ///< clearcoatRoughnessFactor
  TextureRef roughness_texture;   ///< clearcoatRoughnessTexture, G channel
  TextureRef normal_texture;      ///< clearcoatNormalTexture (tangent space)
  float normal_scale = 1.0f;      ///< clearcoatNormalTexture.scale
};

/// KHR_materials_sheen: the Charlie sheen layer (Estevez & Kulla 2017).
struct SheenExtension {
  glm::vec3 color_factor{0.0f};   ///< sheenColorFactor (linear)
  TextureRef color_texture;       ///< sheenColorTexture, RGB (sRGB)
  float roughness_factor = 0.0f;  ///< sheenRoughnessFactor
  TextureRef roughness_texture;   ///< sheenRoughnessTexture, A channel
};

/// KHR_materials_anisotropy: anisotropic GGX along a direction in the tangent frame.
struct AnisotropyExtension {
  float strength = 0.0f;  ///< anisotropyStrength, [0, 1]
  float rotation = 0.0f;  ///< anisotropyRotation, radians from the tangent
  TextureRef texture;     ///< anisotropyTexture: RG direction, B strength (linear)
};

/// KHR_materials_iridescence: a thin film over the base (Belcour & Barla 2017).
struct IridescenceExtension {
  float factor = 0.0f;           ///< iridescenceFactor
  TextureRef texture;            ///< iridescenceTexture, R channel
  float ior = 1.3f;              ///< iridescenceIor (the film's)
  float thickness_min = 100.0f;  ///< iridescenceThicknessMinimum, nm
  float thickness_max = 400.0f;  ///< iridescenceThicknessMaximum, nm
  TextureRef thickness_texture;  ///< iridescenceThicknessTexture, G channel
};

// The transmission extensions (docs/MODEL.md, "The dielectric interface and transmission").

/// KHR_materials_transmission: the dielectric's specular transmission (a rough dielectric
/// BTDF with the base roughness), mixed with the diffuse base by the factor.
struct TransmissionExtension {
  float factor = 0.0f;  ///< transmissionFactor
  TextureRef texture;   ///< transmissionTexture, R channel
};

/// KHR_materials_volume: the mesh bounds a homogeneous absorbing medium (thin-walled when
/// the thickness is 0).
struct VolumeExtension {
  float thickness_factor = 0.0f;  ///< thicknessFactor, in the mesh's object space units
  TextureRef thickness_texture;   ///< thicknessTexture, G channel
  /// attenuationDistance: the distance at which light's radiance falls to attenuationColor
  /// (infinity when absent: no absorption).
  float attenuation_distance = std::numeric_limits<float>::infinity();
  glm::vec3 attenuation_color{1.0f};  ///< attenuationColor (linear)
};

/// KHR_materials_dispersion: the ior varies with wavelength through the Abbe number
/// V = 20 / dispersion (0: none).
struct DispersionExtension {
  float dispersion = 0.0f;  ///< dispersion
};

/// KHR_materials_diffuse_transmission: a Lambertian transmission lobe beside the diffuse.
struct DiffuseTransmissionExtension {
  float factor = 0.0f;           ///< diffuseTransmissionFactor
  TextureRef texture;            ///< diffuseTransmissionTexture, A channel
  glm::vec3 color_factor{1.0f};  ///< diffuseTransmissionColorFactor (linear)
  TextureRef color_texture;      ///< diffuseTransmissionColorTexture, RGB (sRGB)
};

/// Material::textures()'s slots (the GL renderer's texture bits and SLOT_<name>s use these
/// numbers; material_schema.h names each and says which extension and channels fill it).
enum class TextureSlot {
  kBaseColor,
  kMetallicRoughness,
  kNormal,
  kOcclusion,
  kEmissive,
  kSpecular,
  kSpecularColor,
  kClearcoat,
  kClearcoatRoughness,
  kClearcoatNormal,
  kSheenColor,
  kSheenRoughness,
  kAnisotropy,
  kIridescence,
  kIridescenceThickness,
  kTransmission,
  kThickness,
  kDiffuseTransmission,
  kDiffuseTransmissionColor,
};
inline constexpr int kTextureSlotCount = int(TextureSlot::kDiffuseTransmissionColor) + 1;
/// The slots before this one are the core glTF material's; from it on, the extensions'.
inline constexpr TextureSlot kFirstExtensionTextureSlot = TextureSlot::kSpecular;

/// glTF 2.0 metallic-roughness material with the spec's defaults.
struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  glm::vec3 emissive_factor{0.0f};
  float emissive_strength = 1.0f;  ///< KHR_materials_emissive_strength
  float normal_scale = 1.0f;
  float occlusion_strength = 1.0f;
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  TextureRef base_color_texture;          ///< sRGB, RGBA
  TextureRef metallic_roughness_texture;  ///< linear; roughness in G, metallic in B
  TextureRef normal_texture;              ///< linear, tangent space
  TextureRef occlusion_texture;           ///< linear, R channel
  TextureRef emissive_texture;            ///< sRGB

  float ior = 1.5f;  ///< KHR_materials_ior (1.5 when absent; 1.0: no dielectric specular)
  std::optional<SpecularExtension> specular;
  std::optional<ClearcoatExtension> clearcoat;
  std::optional<SheenExtension> sheen;
  std::optional<AnisotropyExtension> anisotropy;
  std::optional<IridescenceExtension> iridescence;
  bool unlit = false;  ///< KHR_materials_unlit: the base colour is shown as is
  std::optional<TransmissionExtension> transmission;
  std::optional<VolumeExtension> volume;
  std::optional<DispersionExtension> dispersion;
  std::optional<DiffuseTransmissionExtension> diffuse_transmission;

  /// Every texture slot, in the order of TextureSlot (texture_slot_name() names them); the
  /// slots of an absent extension point at an empty TextureRef.
  std::array<const TextureRef*, kTextureSlotCount> textures() const;
};

/// KHR_materials_variants: the material a primitive takes while a variant is active
/// (scene/variants.h switches them).
struct VariantMaterial {
  int variant = -1;    ///< index into Scene::variants; -1: no variant (the file's material)
  int material = -1;   ///< index into Scene::materials, -1: the glTF default material
  bool closed = true;  ///< Mesh::closed with this material on (decided at load)
};

/// One glTF primitive as an indexed triangle list (strips and fans converted), with
/// attributes in object space. Optional attributes are empty when absent.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   ///< always present after loading (generated if missing)
  std::vector<glm::vec4> tangents;  ///< xyz + handedness w; generated when a normal map needs them
  std::vector<glm::vec2> texcoords0;
  std::vector<glm::vec2> texcoords1;
  std::vector<glm::vec4> colors0;      ///< COLOR_0 as RGBA (linear)
  std::vector<std::uint32_t> indices;  ///< 3 per triangle
  int material = -1;                   ///< -1: the glTF default material
  /// Whether the triangles close a volume (every edge shared by exactly two triangles):
  /// KHR_materials_volume needs it to bound a medium; an open mesh is rendered thin-walled.
  /// Computed (scene/mesh_closure.h) for meshes whose material has a volume with
  /// thicknessFactor > 0, by the loader and the built-in scenes; left true for the others.
  bool closed = true;
  /// KHR_materials_variants: empty when no mapping names the primitive; otherwise the file's
  /// own material first (variant -1), then one entry per variant that changes the material
  /// or the closure (a mapped variant, or one that changes the shell the primitive closes
  /// with its mesh's other primitives), by variant.
  std::vector<VariantMaterial> variant_materials;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// A mesh placed in the world.
struct Instance {
  int mesh = -1;
  glm::mat4 transform{1.0f};  ///< object to world (accumulated through the node tree)
  int node = -1;              ///< glTF node index, -1 for generated scenes
};

/// glTF camera with its world transform. The camera looks down its local -Z with +Y up.
struct Camera {
  enum class Type { kPerspective, kOrthographic };
  std::string name;
  Type type = Type::kPerspective;
  float yfov = 0.8f;                  ///< radians (perspective)
  std::optional<float> aspect_ratio;  ///< width / height the camera was authored for; renders
                                      ///< keep yfov and use the image's aspect (camera.h)
  float xmag = 1.0f, ymag = 1.0f;     ///< half extents (orthographic)
  float znear = 0.01f;
  std::optional<float> zfar;        ///< infinite when absent
  glm::mat4 camera_to_world{1.0f};  ///< rigid (scale removed)

  glm::vec3 position() const { return glm::vec3(camera_to_world[3]); }
  glm::vec3 forward() const { return -glm::normalize(glm::vec3(camera_to_world[2])); }
};

/// KHR_lights_punctual light in world space, in the spec's units: point and spot
/// intensity in candela (lm/sr), directional in lux (lm/m^2).
struct Light {
  enum class Type { kPoint, kSpot, kDirectional };
  std::string name;
  Type type = Type::kPoint;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  std::optional<float> range;  ///< none: infinite
  float inner_cone_angle = 0.0f;
  float outer_cone_angle = 0.7853981633974483f;  ///< pi / 4
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< the direction the light points (world)
};

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};
  bool empty() const { return min.x > max.x; }
  void extend(glm::vec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
};

struct Scene {
  std::string source;  ///< file path or "builtin:<name>"
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  std::vector<std::string> warnings;
  /// LoadOptions::progress stopped the load (util/progress.h): the scene holds the nodes
  /// set up until then only.
  bool interrupted = false;
  // What the source file declared (empty for built-in scenes), for `pbrkit info`.
  std::size_t node_count = 0;
  std::vector<std::string> extensions_used;
  std::vector<std::string> extensions_required;
  /// The hierarchy, skins, morph targets and animations that pose this scene
  /// (scene/pose.h); null for a scene that cannot move (no animations, no skins).
  std::shared_ptr<const SceneMotion> motion;
  /// KHR_materials_variants: the variants' names (the root's `variants`, in order) and the
  /// one whose materials the meshes hold (-1: none, each primitive's own material).
  std::vector<std::string> variants;
  int active_variant = -1;

  /// World-space bounding box of all instances.
  Bounds world_bounds() const;
  /// Material for a mesh (the glTF default material when the index is -1).
  const Material& material_of(const Mesh& mesh) const;
  std::size_t triangle_count() const;  ///< over all instances

  static const Material& default_material();
};

/// Whether a primitive's surface can be anything but opaque: its material's alphaMode is
/// MASK, or BLEND with an alpha below 1 somewhere (the baseColor factor, the baseColor
/// texture's alpha channel or COLOR_0's alpha). A BLEND material whose alpha is 1
/// everywhere (exporters often write BLEND for opaque surfaces) renders as OPAQUE in both
/// renderers: blending it would only cost order artifacts in the real-time renderer.
bool has_alpha(const Scene& scene, const Mesh& mesh);

}  // namespace pbrkit
