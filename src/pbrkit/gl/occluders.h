#pragma once
// Private to the OpenGL renderer (renderer.cpp): the proxies of the scene's transmissive
// objects that shadow the environment's light on other surfaces (occluders.glsl).
#include <span>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "pbrkit/gl/gpu_scene.h"

namespace pbrkit::gl {

/// The most occluders of each kind (spheres, parallelepipeds) a frame compiles in: their
/// numbers are part of the shader's permutation (5 bits each in SurfaceFeatures::key).
inline constexpr int kMaxOccluders = 16;

/// A parallelepiped's three pairs of faces as box_form_factor takes them
/// (occluder_form_factors.glsl).
struct ParallelepipedFaces {
  glm::vec4 normals[3]{};  ///< pair k: the unit normal (xyz) and the half-extent along it (w)
  glm::vec3 areas{0.0f};   ///< pair k: the area of one of its faces
};

/// The pairs of faces of the parallelepiped of half-axes a_k: across a_k, spanned by
/// a_{k+1} and a_{k+2}. A flat body (a half-axis 0) is given a thickness of 1e-4 of its
/// largest half-axis, so that its extents still bound it.
ParallelepipedFaces parallelepiped_faces(const glm::vec3 axes[3]);

/// One proxy of a transmissive or opaque instance (occluders.glsl).
struct Occluder {
  bool sphere = false;
  glm::vec3 center{0.0f};
  float radius = 0.0f;        ///< a sphere's
  ParallelepipedFaces faces;  ///< a parallelepiped's
  glm::vec3 transmittance{1.0f};
  int slot = 0;  ///< the instance's slot (gpu_scene.h): a surface is not shadowed by its own
  /// An opaque object's proxy (RenderSettings::opaque_shadows): it lets nothing through and
  /// reflects `albedo` of the environment light that reaches its sides, diffusely: a side
  /// of outward normal N sends albedo E(N) / pi, E the environment's irradiance there
  /// (occluders.glsl's side_radiance; the light other objects hide from it is not taken
  /// off).
  bool opaque = false;
  glm::vec3 albedo{0.0f};
  /// An opaque proxy's own radiance from every side, added to what it reflects: its
  /// material's emission (opaque_emission), or for an unlit material (KHR_materials_unlit)
  /// its base colour, with albedo 0, as the path tracer takes an unlit surface: an emitter
  /// of its colour that reflects nothing. (A single-sided emitter's proxy glows from its
  /// back too.)
  glm::vec3 emission{0.0f};
};

/// Which instances stand in as proxies.
struct OccluderKinds {
  bool transmissive = true;  ///< RenderSettings::transmissive_shadows
  bool opaque = false;       ///< RenderSettings::opaque_shadows
  bool operator==(const OccluderKinds&) const = default;
};

/// The share of a uniform environment's light a transmissive material lets through an
/// object, per channel: its transmitting share (transmission times the base colour, and
/// diffuse transmission's colour where the rest transmits diffusely) times 1 - F_avg at
/// each interface it crosses (F_avg the cosine-weighted hemispherical average of the
/// dielectric Fresnel reflectance: one interface thin-walled, two through a `volume`), and
/// through a volume Beer-Lambert's attenuation over `chord` (world units).
glm::vec3 occluder_transmittance(const Material& m, bool volume, float chord);

/// One proxy per instance of `scene` whose material transmits light (KHR_materials_
/// transmission or _diffuse_transmission) where `kinds.transmissive`, and per other instance
/// where `kinds.opaque`: a sphere where the mesh is one (GpuMesh::sphere_radius) and the
/// instance scales it uniformly, else its bounding box as a parallelepiped. A transmissive
/// one's transmittance is occluder_transmittance's over the body's mean chord, 4 V / S
/// (Cauchy's formula for a convex body); an opaque one's is 0, and its albedo
/// opaque_albedo's.
std::vector<Occluder> ibl_occluders(const GpuScene& scene, OccluderKinds kinds = {});

/// The share of the light reaching an opaque surface of material `m` that it sends back,
/// for its proxy: the base colour (its factor times its texture's mean, `texture_means`:
/// GpuScene's), which a rough dielectric's diffuse lobe and specular lobe reflect together
/// to within its F_avg, and a metal's specular lobe reflects.
glm::vec3 opaque_albedo(const Material& m, std::span<const glm::vec3> texture_means);
/// The radiance an opaque surface of material `m` emits, for its proxy: the emissive factor
/// times KHR_materials_emissive_strength times the emissive texture's mean.
glm::vec3 opaque_emission(const Material& m, std::span<const glm::vec3> texture_means);

/// What a frame compiles in: at most kMaxOccluders of each kind, the largest (a sphere's
/// radius, a parallelepiped's surface), spheres first, and of each kind the transmissive
/// ones before the opaque ones; `counts` the spheres' and the parallelepipeds' numbers.
std::vector<Occluder> select_occluders(std::span<const Occluder> all, glm::ivec2& counts);

/// The selection's geometry as occluders.glsl's OCCLUDER_GEOMETRY define, five vec4 per
/// occluder (centre and slot; the three pairs of faces; the faces' areas and the radius),
/// and the indices of each kind's transmissive and opaque ones as lists of
/// OCCLUDER_TERM(i) (OCCLUDER_TRANSMISSIVE_SPHERES, _OPAQUE_SPHERES, _TRANSMISSIVE_BOXES,
/// _OPAQUE_BOXES), compiled into the surface program: a software rasteriser (llvmpipe) reads
/// a uniform buffer lane by lane and does not unroll a loop over many proxies, and the
/// geometry changes only with the scene (docs/benchmarks_archive.md, "Shadows of transmissive
/// objects" and "The proxies' terms written out").
std::string occluder_geometry_define(std::span<const Occluder> selected);

/// The selected occluders' transmittances on the GPU (occluders.glsl's Occluders block, one
/// vec4 each; the opaque ones' albedos and emissions after them), which change with the
/// materials without a new program. Needs the current GL context for its whole life.
class GpuOccluderBuffer {
 public:
  GpuOccluderBuffer();
  ~GpuOccluderBuffer();
  GpuOccluderBuffer(const GpuOccluderBuffer&) = delete;
  GpuOccluderBuffer& operator=(const GpuOccluderBuffer&) = delete;
  /// Uploads the transmittances and the opaque ones' albedos and emissions of `selected`
  /// (select_occluders's) and binds the buffer.
  void upload(std::span<const Occluder> selected);
  /// Binds the buffer (GL_UNIFORM_BUFFER at surface_bindings.h's kOccluderBufferBinding).
  void bind() const;
  GLuint id() const { return buffer_; }

 private:
  GLuint buffer_ = 0;
};

}  // namespace pbrkit::gl
