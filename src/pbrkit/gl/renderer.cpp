#include "pbrkit/gl/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "pbrkit/core/math.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/draw_queue.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/gpu_deformation.h"
#include "pbrkit/gl/gpu_scene.h"
#include "pbrkit/gl/gpu_timer.h"
#include "pbrkit/gl/light_clusters.h"
#include "pbrkit/gl/occluder_pass.h"
#include "pbrkit/gl/render_targets.h"
#include "pbrkit/gl/shader_permutations.h"
#include "pbrkit/gl/surface_bindings.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit::gl {

namespace {

// "name[i]" for a uniform array element.
std::string indexed(const char* name, int i) {
  return fmt::format("{}[{}]", name, i);
}

// (cos a, sin a) of a = -rotation_deg in radians: equirect.glsl's world_to_env argument,
// the inverse of the environment's rotation about +Y (core/equirect.h's convention).
glm::vec2 env_rotation_cs(float rotation_deg) {
  const float a = -glm::radians(rotation_deg);
  return {std::cos(a), std::sin(a)};
}

// The extensions' factors, each on its uniform factor_uniform() names, from the material
// schema (the READMEs' defaults when the material has none, which the permutation then
// does not read).
void set_extension_uniforms(const Program& p, const Material& m) {
  for (const MaterialExtension& e : material_extensions()) {
    const bool present = e.present(m);
    for (const MaterialFactor& f : e.factors) {
      glm::vec3 v(0.0f);
      for (int c = 0; c < f.components; ++c)
        v[c] = present ? f.read(m)[c] : factor_default(e, f, c);
      const std::string name = factor_uniform(f);
      if (f.components == 3)
        p.set(name.c_str(), v);
      else
        p.set(name.c_str(), v.x);
    }
  }
  // The shader's "none" is <= 0 (glTF requires a positive distance; absent is infinity).
  const float d = m.volume ? m.volume->attenuation_distance : 0.0f;
  p.set("uAttenuationDistance", std::isfinite(d) && d > 0.0f ? d : 0.0f);
  // A normalTextureInfo's scale, not a factor of the schema.
  p.set("uClearcoatNormalScale", m.clearcoat ? m.clearcoat->normal_scale : 1.0f);
}

// The most captures of the frame a transmission pass makes (the opaque frame, then one more
// each time a transmissive surface covers one drawn since the last capture): glass seen
// through glass, up to this depth.
constexpr int kMaxTransmissionCaptures = 4;

// A transmissive instance's place in the pass: drawn in increasing `nearest` (the view-space
// z of its bounding box's nearest corner: an object nested in another, the liquid in its
// glass, comes first), over its screen rectangle (NDC; the whole screen when a corner is
// behind the camera).
struct TransmissiveDraw {
  float nearest = 0.0f;
  glm::vec2 lo{-1.0f}, hi{1.0f};
  std::size_t index = 0;
  bool overlaps(const TransmissiveDraw& o) const {
    return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y;
  }
};

TransmissiveDraw transmissive_draw(std::size_t index, const glm::mat4& model, const glm::vec3& bmin,
                                   const glm::vec3& bmax, const glm::mat4& view,
                                   const glm::mat4& projection) {
  TransmissiveDraw d;
  d.index = index;
  d.nearest = -std::numeric_limits<float>::infinity();
  glm::vec2 lo(std::numeric_limits<float>::infinity()), hi(-lo);
  bool behind = false;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner((k & 1) ? bmax.x : bmin.x, (k & 2) ? bmax.y : bmin.y,
                           (k & 4) ? bmax.z : bmin.z);
    const glm::vec4 v = view * model * glm::vec4(corner, 1.0f);
    d.nearest = std::max(d.nearest, v.z);  // view space looks down -Z: largest is nearest
    const glm::vec4 clip = projection * v;
    if (clip.w <= 0.0f) {
      behind = true;
      continue;
    }
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    lo = glm::min(lo, ndc), hi = glm::max(hi, ndc);
  }
  if (!behind) d.lo = lo, d.hi = hi;
  return d;
}

// What the surfaces write (debug_channels.h): a permutation of its own, so the shaded
// frame compiles no debug code.
void set_debug_features(const RenderSettings& settings, SurfaceFeatures& f) {
  f.debug_channel = int(settings.debug_channel);
}

// Whether a transmissive surface of material `m` may read the captured frame above its level
// 0: its refraction blurs with the perceptual roughness (transmission.glsl's
// transmission_lod), which is the factor times the texture's G (glTF 2.0, 3.9.2), or the
// override; a factor of 0 is smooth everywhere and reads level 0 alone.
bool blurs_frame(const Material& m, const RenderSettings& settings) {
  if (settings.roughness_override >= 0.0f) return settings.roughness_override > 0.0f;
  return m.roughness_factor > 0.0f;
}

// Whether `m` on a mesh refracts through two interfaces (thick_refraction.glsl): a specular
// transmission through a volume of thickness > 0; only these pay for the back-face pass.
bool refracts_thick(const Material& m, bool closed) {
  SurfaceFeatures f;
  set_transmission_features(m, closed, f);
  return f.transmission && f.volume;
}

// The back-face pass of thick refraction (Wyman 2005; thick_refraction.glsl): instance
// `index`'s back faces alone (front faces culled, the nearest back face kept) into the
// back-face target over the object's screen rectangle `lo`..`hi` (NDC), cleared first;
// then the frame's target is bound again. Binds the target's textures for the surface
// shader and returns the rectangle in texture coordinates: the shader reads back faces only
// inside it (outside, the target holds other objects'). `program` is made on first use;
// the draw goes through `queue` (the software rasteriser's waits).
glm::vec4 draw_back_faces(std::array<Program, 3>& programs, RenderTargets& targets,
                          const GpuScene& scene, const GpuDeformation& deformation,
                          std::size_t index, glm::vec2 lo, glm::vec2 hi,
                          const glm::mat4& view_projection, DrawQueue& queue) {
  const glm::vec2 size(float(targets.width), float(targets.height));
  // Whole pixels covering the rectangle, one more each side for rounding (clamped as floats:
  // a corner just in front of the camera projects far outside any int).
  const glm::ivec2 p0(
      glm::clamp(glm::floor((lo * 0.5f + 0.5f) * size) - 1.0f, glm::vec2(0.0f), size));
  const glm::ivec2 p1(
      glm::clamp(glm::ceil((hi * 0.5f + 0.5f) * size) + 1.0f, glm::vec2(0.0f), size));
  const Instance& inst = scene.instances[index];
  const GpuMesh& mesh = scene.meshes[std::size_t(inst.mesh)];
  // By the mesh's DEFORM: a deforming mesh's back faces are its deformed ones.
  const GpuDeformingMesh* deforming = deformation.of_mesh(inst.mesh);
  Program& program = programs[std::size_t(deforming ? deforming->deform() : 0)];
  if (!program.id())
    program = Program::graphics(
        "pbr_vertex.glsl", "back_face_fragment.glsl",
        surface_prelude() + fmt::format("#define HAS_COLOR_0 0\n#define DEFORM {}\n",
                                        deforming ? deforming->deform() : 0));
  targets.begin_back_faces(p0.x, p0.y, p1.x, p1.y);
  program.use();
  program.set("uViewProjection", view_projection);
  program.set("uInstanceBase", GLint(scene.slot_of[index]));
  if (deforming) GpuDeformation::bind(program, *deforming);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glFrontFace(glm::determinant(glm::mat3(inst.transform)) < 0.0f ? GL_CW : GL_CCW);
  glBindVertexArray(mesh.vao);
  queue.draw_triangles(std::size_t(mesh.index_count / 3), 1);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, targets.msaa_fbo);
  glBindTextureUnit(kBackPositionUnit, targets.back_position);
  glBindTextureUnit(kBackNormalUnit, targets.back_normal);
  return glm::vec4(glm::vec2(p0) / size, glm::vec2(p1) / size);
}

// What render() knows of the frame it draws: the camera's matrices, the lights and their
// clusters, the features every surface permutation of the frame shares, and the state its
// passes hand on to each other.
struct Frame {
  const Camera* camera = nullptr;
  const RenderSettings* settings = nullptr;
  int width = 0, height = 0;
  glm::mat4 view{1.0f}, projection{1.0f}, view_projection{1.0f}, inverse_view_projection{1.0f};
  float rotation_delta = 0.0f;  // the environment's rotation minus the baked IBL's
  float ibl_scale = 1.0f;       // the environment's intensity over the baked IBL's
  std::vector<const Light*> lights;
  LightClusters clusters;
  bool clustered = false;  // some light binned into clusters (LIGHTS 2)
  // The view depth of a world point, dot(view_depth.xyz, p) + view_depth.w.
  glm::vec4 view_depth{0.0f};
  SurfaceFeatures features;        // the frame's: per draw, the material's are added
  std::vector<GLuint> prepared;    // the programs whose frame uniforms are set
  bool back_faces_drawn = false;   // the back-face target holds the instance drawn next
  glm::vec4 back_face_rect{0.0f};  // over this rectangle (texture coordinates)
};

// The draws the opaque pass leaves for later passes.
struct QueuedDraws {
  std::vector<TransmissiveDraw> transmissive;          // surfaces that read the opaque frame
  std::vector<std::pair<float, std::size_t>> blended;  // (view-space z, instance)
  bool frame_read = false;                             // a blended surface reads the frame too
  bool frame_blurred = false;  // a surface that reads the frame may read above its level 0
};

}  // namespace

// The parts a frame is made of, each in its own file; the members are made in this order
// (programs first: a driver that cannot compile them fails before anything is uploaded)
// and released in the reverse one, all while the context is current.
struct Renderer::State {
  ShaderPermutations programs;
  std::array<GLuint, 3> energy{};  // per GeometryModel
  GpuScene scene;
  // The deforming meshes' rest data, drawn deformed in the vertex shader once posed
  // (Renderer::set_pose).
  GpuDeformation deformation;
  // What set_pose poses: the scene's motion (null: none) and its file, for errors.
  std::shared_ptr<const SceneMotion> motion;
  std::string source;
  GpuEnvironment environment;
  GLuint white_texture = 0;
  GLuint sheen_lut = 0;  // core/sheen.h's SheenTable
  // ibl/anisotropic_albedo.h's and core/anisotropic_energy.h's tables, made for the first
  // frame with an anisotropic material.
  GLuint anisotropic_albedo = 0;
  GLuint anisotropic_energy = 0;
  GLuint empty_vao = 0;  // the background's full-screen triangle has no attributes
  RenderTargets targets;
  GpuTimer timer;
  GpuLightBuffers light_buffers;
  OccluderPass occluders;  // the environment light's shadows (occluder_pass.h)
  // Whether a frame has needed more than kMaxTransmissionCaptures captures (warned once per
  // renderer: the viewer draws the same scene every frame).
  bool capture_limit_warned = false;
  // The back-face pass's programs (pbr_vertex.glsl, back_face_fragment.glsl) by DEFORM, made
  // on the first frame with a thick transmissive object (of that kind).
  std::array<Program, 3> back_faces;
  // Every draw goes through it: on a software rasteriser it bounds the queue (draw_queue.h).
  DrawQueue queue;

  // render()'s steps, in the order it takes them.
  Frame begin_frame(const Camera& camera, int width, int height, const RenderSettings& settings);
  QueuedDraws draw_opaque(Frame& f);
  void draw_background(const Frame& f);
  void draw_transmissive(Frame& f, QueuedDraws& queued);
  void draw_blended(Frame& f, std::vector<std::pair<float, std::size_t>>& blended);
  // Sets the frame's uniforms on `p` the first time the frame uses it.
  void prepare(Frame& f, const Program& p);
  // Instance `index` and the `count` - 1 after it in slot order (one run: the same mesh and
  // winding), in one glDrawElementsInstanced (in chunks on a software rasteriser: DrawQueue).
  // `cull`: the faces to cull (GL_BACK, GL_FRONT), or 0 for the material's choice.
  void draw(Frame& f, std::size_t index, GLenum cull = 0, std::size_t count = 1);
};

Frame Renderer::State::begin_frame(const Camera& camera, int width, int height,
                                   const RenderSettings& settings) {
  Frame f;
  f.camera = &camera;
  f.settings = &settings;
  f.width = width;
  f.height = height;
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  targets.ensure(width, height, std::clamp(settings.msaa, 1, std::max(1, int(max_samples))));
  const float aspect = float(width) / float(height);
  f.view = view_matrix(camera);
  f.projection = projection_matrix(camera, aspect);
  f.view_projection = f.projection * f.view;

  timer.begin();
  queue.begin_frame(settings.software_queue_triangles);
  glBindFramebuffer(GL_FRAMEBUFFER, targets.msaa_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  f.rotation_delta = settings.env_rotation_deg - environment.ibl_params.rotation_deg;
  f.ibl_scale = settings.env_intensity / std::max(environment.ibl_params.intensity, 1e-30f);

  // The punctual lights of this frame, uploaded with their clusters (light_clusters.h).
  for (std::size_t i = 0; i < scene.lights.size() && settings.lights; ++i) {
    if (i < settings.light_enabled.size() && !settings.light_enabled[i]) continue;
    f.lights.push_back(&scene.lights[i]);
  }
  if (settings.clustered_lights && !f.lights.empty())
    f.clusters = bin_lights(f.lights,
                            ClusterView{f.view, f.projection, width, height, camera.znear,
                                        camera.type == Camera::Type::kOrthographic
                                            ? camera.zfar.value_or(camera.znear + 1e6f)
                                            : camera.zfar},
                            settings.light_clusters);
  // No light binned (every light global, or none reaching the view): the plain loop, without
  // the cluster lookup.
  f.clustered = settings.clustered_lights && !f.lights.empty() && !f.clusters.indices.empty();
  light_buffers.upload(f.lights, f.clustered ? &f.clusters : nullptr);
  occluders.begin_frame(scene, {settings.transmissive_shadows, settings.opaque_shadows}, programs,
                        f.features);
  // Minus the view matrix's third row (view space looks down -Z).
  f.view_depth = -glm::vec4(f.view[0][2], f.view[1][2], f.view[2][2], f.view[3][2]);
  const GeometryModel direct = direct_geometry(settings.brdf.model);
  const GeometryModel ibl = ibl_geometry(settings.brdf.model);
  f.features.ibl = settings.ibl && environment.has_ibl;
  // Per draw, only thick transmissive surfaces compile it in (draw).
  f.features.glass_reflections = f.features.ibl && settings.transmissive_reflections;
  f.features.irradiance_sh = settings.irradiance == IrradianceMode::kSH;
  f.features.multiscatter = settings.brdf.multiscatter;
  f.features.geometry = int(direct);
  f.features.fresnel = settings.fresnel == FresnelMode::kSchlick ? 0 : 1;
  const bool spots = std::any_of(f.lights.begin(), f.lights.end(),
                                 [](const Light* l) { return l->type == Light::Type::kSpot; });
  f.features.lights = f.lights.empty() ? 0 : f.clustered ? (spots ? 3 : 2) : 1;
  if (f.features.lights == 1 && int(f.lights.size()) <= kCompiledLightCount)
    f.features.light_count = int(f.lights.size());
  set_debug_features(settings, f.features);
  glBindTextureUnit(kEnergyDirectUnit, energy[std::size_t(direct)]);
  glBindTextureUnit(kEnergyIblUnit, energy[std::size_t(ibl)]);
  glBindTextureUnit(kSpecularCubeUnit, environment.specular_cube);
  glBindTextureUnit(kIrradianceCubeUnit, environment.irradiance_cube);
  glBindTextureUnit(kCoatEnergyUnit, energy[std::size_t(GeometryModel::kReference)]);
  glBindTextureUnit(kSheenCubeUnit, environment.sheen_cube);
  glBindTextureUnit(kSheenLutUnit, sheen_lut);
  if (!anisotropic_albedo &&
      std::any_of(scene.materials.begin(), scene.materials.end(),
                  [](const Material& m) { return m.anisotropy.has_value(); })) {
    anisotropic_albedo = create_anisotropic_albedo_texture();
    anisotropic_energy = create_anisotropic_energy_texture();
  }
  glBindTextureUnit(kAnisotropicAlbedoUnit, anisotropic_albedo);
  glBindTextureUnit(kAnisotropicEnergyUnit, anisotropic_energy);
  f.inverse_view_projection = glm::inverse(f.view_projection);
  return f;
}

void Renderer::State::prepare(Frame& f, const Program& p) {
  if (std::find(f.prepared.begin(), f.prepared.end(), p.id()) != f.prepared.end()) return;
  f.prepared.push_back(p.id());
  const RenderSettings& settings = *f.settings;
  p.set("uViewProjection", f.view_projection);
  p.set("uCameraPosition", f.camera->position());
  p.set("uMetallicOverride", settings.metallic_override);
  p.set("uRoughnessOverride", settings.roughness_override);
  glProgramUniform3fv(p.id(), p.location("uSH"), 9, &environment.ibl_params.sh[0].x);
  p.set("uSpecularLevels", environment.specular_levels);
  p.set("uSheenLevels", environment.sheen_levels);
  p.set("uIblRotation", env_rotation_cs(f.rotation_delta));
  p.set("uIblScale", f.ibl_scale);
  p.set("uTransmissionFrameSize", glm::vec2(float(f.width), float(f.height)));
  p.set("uLightCount", GLint(f.lights.size()));
  if (f.clustered) {
    const LightClusters& clusters = f.clusters;
    p.set("uViewDepth", f.view_depth);
    p.set("uGlobalLightCount", GLint(clusters.global.size()));
    p.set("uClusterGrid", clusters.grid);
    p.set("uClusterTile", float(clusters.tile_pixels));
    // slice = floor(log(depth / z_lo) * slices / log(z_hi / z_lo)) (light_clusters.h).
    p.set("uClusterDepth", glm::vec2(clusters.z_lo, float(clusters.grid.z) /
                                                        std::log(clusters.z_hi / clusters.z_lo)));
  }
}

void Renderer::State::draw(Frame& f, std::size_t index, GLenum cull, std::size_t count) {
  const Instance& inst = scene.instances[index];
  const GpuMesh& mesh = scene.meshes[std::size_t(inst.mesh)];
  const Material& m = scene.material_of(mesh);
  const auto refs = m.textures();
  SurfaceFeatures features = f.features;
  features.alpha_mode = mesh.alpha_mode;
  features.colors = mesh.has_colors;
  const GpuDeformingMesh* deforming = deformation.of_mesh(inst.mesh);
  features.deform = deforming ? deforming->deform() : 0;
  for (int t = 0; t < kTextureSlotCount; ++t) {
    const TextureRef& ref = *refs[std::size_t(t)];
    if (ref.valid() && std::size_t(ref.texture) < scene.textures.size())
      features.textures |= 1u << t;
  }
  features.unlit = m.unlit;
  features.specular = m.specular.has_value() || m.ior != 1.5f;
  features.anisotropy = m.anisotropy.has_value();
  features.iridescence = m.iridescence.has_value() && m.iridescence->factor > 0.0f;
  features.clearcoat = m.clearcoat.has_value() && m.clearcoat->factor > 0.0f;
  features.sheen = m.sheen.has_value() && max3(m.sheen->color_factor) > 0.0f;
  set_transmission_features(m, mesh.closed, features);
  features.glass_reflections =
      f.features.glass_reflections && features.transmission && features.volume;
  const Program& p = programs.surface(features);
  prepare(f, p);
  p.use();
  p.set("uInstanceBase", GLint(scene.slot_of[index]));
  if (deforming) GpuDeformation::bind(p, *deforming);
  p.set("uBaseColorFactor", m.base_color_factor);
  p.set("uMetallicFactor", m.metallic_factor);
  p.set("uRoughnessFactor", m.roughness_factor);
  p.set("uEmissive", m.emissive_factor * m.emissive_strength);
  p.set("uNormalScale", m.normal_scale);
  p.set("uOcclusionStrength", m.occlusion_strength);
  p.set("uAlphaCutoff", m.alpha_cutoff);
  set_extension_uniforms(p, m);
  if (features.transmission && features.volume) {
    p.set("uBackFaces", GLint(f.back_faces_drawn));
    p.set("uBackFaceRect", f.back_face_rect);
    p.set("uInverseViewProjection", f.inverse_view_projection);
  }
  if (features.transmission || features.diffuse_transmission)
    p.set("uModelScale", glm::vec3(glm::length(glm::vec3(inst.transform[0])),
                                   glm::length(glm::vec3(inst.transform[1])),
                                   glm::length(glm::vec3(inst.transform[2]))));
  for (int t = 0; t < kTextureSlotCount; ++t) {
    const TextureRef& ref = *refs[std::size_t(t)];
    const bool valid = (features.textures >> t) & 1u;
    if (t >= int(kFirstExtensionTextureSlot) && !valid)
      continue;  // an extension's unused slot is not sampled
    p.set(indexed("uTexcoordSet", t).c_str(), ref.texcoord);
    p.set(indexed("uTextureTransform", t).c_str(),
          ref.transform ? ref.transform->matrix() : glm::mat3(1.0f));
    glBindTextureUnit(texture_unit(TextureSlot(t)),
                      valid ? scene.textures[std::size_t(ref.texture)] : white_texture);
  }
  // glTF: single-sided materials cull back faces; a mirroring transform flips winding.
  if (cull == 0 && m.double_sided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(cull == 0 ? GL_BACK : cull);
  }
  glFrontFace(glm::determinant(glm::mat3(inst.transform)) < 0.0f ? GL_CW : GL_CCW);
  glBindVertexArray(mesh.vao);
  // One instanced draw; on a software rasteriser chunks of at most the queue's limit of
  // triangles (at least one instance each, a larger mesh in index ranges), the frame waiting
  // for the rasteriser's queue once that many have been drawn (draw_queue.h).
  const std::size_t limit = queue.limit();
  const std::size_t triangles = std::size_t(mesh.index_count / 3);
  const std::size_t chunk =
      limit > 0 ? std::max<std::size_t>(1, limit / std::max<std::size_t>(1, triangles)) : count;
  for (std::size_t k = 0; k < count; k += chunk) {
    const std::size_t n = std::min(chunk, count - k);
    if (k > 0) p.set("uInstanceBase", GLint(scene.slot_of[index] + k));
    queue.draw_triangles(triangles, n);
  }
}

// Opaque and masked instances a run at a time (GpuScene::runs: one mesh, one winding); the
// transmissive and blended ones are queued for their passes.
QueuedDraws Renderer::State::draw_opaque(Frame& f) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBufferBinding, scene.instance_buffer);
  deformation.bind_pose();
  QueuedDraws queued;
  for (const InstanceRun& run : scene.runs) {
    const GpuMesh& mesh =
        scene.meshes[std::size_t(scene.instances[scene.at_slot[run.first_slot]].mesh)];
    const Material& m = scene.material_of(mesh);
    // Surfaces with KHR_materials_transmission read the opaque frame: they wait for it.
    const bool transmits = m.transmission.has_value() && m.transmission->factor > 0.0f;
    if (mesh.alpha_mode != 2 && !transmits) {
      draw(f, scene.at_slot[run.first_slot], 0, run.count);
      continue;
    }
    queued.frame_blurred = queued.frame_blurred || (transmits && blurs_frame(m, *f.settings));
    for (std::size_t slot = run.first_slot; slot < run.first_slot + run.count; ++slot) {
      const std::size_t i = scene.at_slot[slot];
      const Instance& inst = scene.instances[i];
      const glm::vec4 c = f.view * inst.transform * glm::vec4(mesh.center, 1.0f);
      if (mesh.alpha_mode == 2) {
        queued.blended.emplace_back(c.z, i);  // view space looks down -Z: most negative is farthest
        queued.frame_read = queued.frame_read || transmits;
      } else {
        queued.transmissive.push_back(transmissive_draw(i, inst.transform, mesh.bounds_min,
                                                        mesh.bounds_max, f.view, f.projection));
      }
    }
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  return queued;
}

// Background: a full-screen triangle at the far plane, shaded only where no opaque surface
// is (depth still 1.0), without writing depth.
void Renderer::State::draw_background(const Frame& f) {
  const RenderSettings& settings = *f.settings;
  int mode = 2;
  glm::vec3 color = settings.background.color;
  if (settings.background.mode == Background::Mode::kEnvironment && environment.has_env) mode = 0;
  if (settings.background.mode == Background::Mode::kBlurred && environment.has_ibl) mode = 1;
  if (settings.background.mode != Background::Mode::kColor && mode == 2) color = glm::vec3(0.0f);
  const Program& p = programs.background(mode);
  p.use();
  p.set("uColor", color);
  p.set("uInverseProjection", glm::inverse(f.projection));
  p.set("uCameraToWorld", glm::mat3(f.camera->camera_to_world));
  p.set("uEnvRotation", env_rotation_cs(settings.env_rotation_deg));
  p.set("uEnvScale", settings.env_intensity / std::max(environment.env_intensity, 1e-30f));
  p.set("uIblRotation", env_rotation_cs(f.rotation_delta));
  p.set("uIblScale", f.ibl_scale);
  p.set("uBlurLod", settings.background.blur_lod);
  glBindTextureUnit(kBackgroundEnvironmentUnit,
                    environment.env_texture ? environment.env_texture : white_texture);
  glBindTextureUnit(kBackgroundSpecularCubeUnit, environment.specular_cube);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

// The transmission pass (the Sample Viewer's and Filament's screen-space refraction): the
// opaque frame and background, resolved into a mip-mapped colour target, then the
// transmissive surfaces, far to near, each reading it through transmission.glsl. The
// Sample Viewer reads only the opaque frame, so glass behind glass (a liquid in its
// glass) is invisible; here the frame is captured again before a surface that covers one
// drawn since the last capture (at most kMaxTransmissionCaptures in all). A frame
// without transmissive surfaces pays nothing: no copy, no mip chain.
void Renderer::State::draw_transmissive(Frame& f, QueuedDraws& queued) {
  std::vector<TransmissiveDraw>& transmissive = queued.transmissive;
  if (transmissive.empty() && !queued.frame_read) return;
  const bool thick = std::any_of(transmissive.begin(), transmissive.end(), [&](const auto& t) {
    const GpuMesh& mesh = scene.meshes[std::size_t(scene.instances[t.index].mesh)];
    return refracts_thick(scene.material_of(mesh), mesh.closed);
  });
  targets.capture_frame(thick, queued.frame_blurred);
  if (thick) glBindTextureUnit(kFrameDepthUnit, targets.transmission_depth);
  int captures = 1;
  glBindTextureUnit(kTransmissionFrameUnit, targets.transmission_color);
  std::sort(
      transmissive.begin(), transmissive.end(),
      [](const TransmissiveDraw& a, const TransmissiveDraw& b) { return a.nearest < b.nearest; });
  std::vector<const TransmissiveDraw*> since_capture;
  for (const TransmissiveDraw& t : transmissive) {
    const bool covers = std::any_of(since_capture.begin(), since_capture.end(),
                                    [&](const TransmissiveDraw* o) { return t.overlaps(*o); });
    if (covers && captures < kMaxTransmissionCaptures) {
      targets.capture_frame(thick, queued.frame_blurred);
      ++captures;
      since_capture.clear();
    } else if (covers && !capture_limit_warned) {
      // This surface reads a capture without the glass it covers (drawn since the last one).
      warn(
          "OpenGL renderer: glass seen through glass needs more than {} captures of the frame "
          "(the limit); a deeper layer shows what is behind it without the glass in between",
          kMaxTransmissionCaptures);
      capture_limit_warned = true;
    }
    since_capture.push_back(&t);
    const GpuMesh& mesh = scene.meshes[std::size_t(scene.instances[t.index].mesh)];
    f.back_faces_drawn = refracts_thick(scene.material_of(mesh), mesh.closed);
    if (f.back_faces_drawn)
      f.back_face_rect = draw_back_faces(back_faces, targets, scene, deformation, t.index, t.lo,
                                         t.hi, f.view_projection, queue);
    draw(f, t.index);
    f.back_faces_drawn = false;
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
}

// Blended surfaces back to front (sorted by view depth), without writing depth.
void Renderer::State::draw_blended(Frame& f, std::vector<std::pair<float, std::size_t>>& blended) {
  if (blended.empty()) return;
  std::sort(blended.begin(), blended.end());
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  // A double-sided blended mesh is drawn back faces first, then front faces: the far
  // side of a closed (convex) surface is composited before the near one whatever the
  // triangle order. Layers within one side are drawn in index order (no per-triangle
  // sorting): concave meshes can still show the wrong layer on top.
  for (const auto& b : blended) {
    const GpuMesh& mesh = scene.meshes[std::size_t(scene.instances[b.second].mesh)];
    if (scene.material_of(mesh).double_sided) {
      draw(f, b.second, GL_FRONT);
      draw(f, b.second, GL_BACK);
    } else {
      draw(f, b.second);
    }
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

Renderer::Renderer() : state_(std::make_unique<State>()) {
  State& s = *state_;
  for (int g = 0; g < 3; ++g) s.energy[std::size_t(g)] = create_energy_texture(GeometryModel(g));
  glCreateTextures(GL_TEXTURE_2D, 1, &s.white_texture);
  glTextureStorage2D(s.white_texture, 1, GL_RGBA32F, 1, 1);
  const float white[4] = {1, 1, 1, 1};
  glTextureSubImage2D(s.white_texture, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, white);
  s.sheen_lut = create_sheen_lut_texture();
  glCreateVertexArrays(1, &s.empty_vao);
  // pbr_fragment.glsl binds samplers up to unit kLastSurfaceUnit.
  GLint units = 0;
  glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
  if (units <= GLint(kLastSurfaceUnit))
    fail("OpenGL: {} fragment texture units, the surface shader needs {}", units,
         kLastSurfaceUnit + 1);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  s.queue = DrawQueue(is_software_renderer(current_renderer()));
}

Renderer::~Renderer() {
  State& s = *state_;
  glDeleteTextures(3, s.energy.data());
  glDeleteTextures(1, &s.white_texture);
  glDeleteTextures(1, &s.sheen_lut);
  glDeleteTextures(1, &s.anisotropic_albedo);
  glDeleteTextures(1, &s.anisotropic_energy);
  glDeleteVertexArrays(1, &s.empty_vao);
}

void Renderer::set_scene(const Scene& scene) {
  state_->scene.upload(scene);
  state_->deformation.set_scene(scene);
  state_->motion = scene.motion;
  state_->source = scene.source;
  state_->occluders.scene_changed(state_->scene);
}

void Renderer::set_pose(const PoseTime& pose) {
  State& s = *state_;
  const std::shared_ptr<const SceneMotion>& motion = s.motion;
  if (!motion) {
    if (pose.animation >= 0) fail("OpenGL: set_pose: the scene has no animations");
    return;
  }
  const std::vector<glm::mat4> world = checked_node_transforms(*motion, s.source, pose);
  std::vector<Instance> instances = s.scene.instances;
  std::vector<Light> lights = s.scene.lights;
  place_instances_and_lights(*motion, world, instances, lights);
  s.scene.update_instances(instances);
  s.scene.lights = std::move(lights);
  s.deformation.pose(world, posed_morph_weights(*motion, pose));
  // The proxies of the environment light's shadows follow their instances.
  s.occluders.scene_changed(s.scene);
}

void Renderer::set_materials(const std::vector<Material>& materials) {
  std::vector<Material>& current = state_->scene.materials;
  if (materials.size() != current.size())
    fail("OpenGL: set_materials with {} materials for a scene of {}", materials.size(),
         current.size());
  current = materials;
  state_->occluders.scene_changed(state_->scene);
}

void Renderer::set_environment(const Environment* env) {
  state_->environment.set_environment(env);
}

void Renderer::set_ibl(const IblMaps* maps) {
  state_->environment.set_ibl(maps);
}

bool Renderer::set_environment_light(const Environment* env, const std::optional<BakeOptions>& bake,
                                     const ProgressCallback& progress) {
  set_environment(env);
  if (!env || !bake) {
    set_ibl(nullptr);
    return true;
  }
  BakeResult baked = bake_environment(*env, *bake, progress);
  if (baked.interrupted) {
    set_ibl(nullptr);
    return false;
  }
  const IblMaps maps = ibl_maps_from_bake(std::move(baked), *env);
  set_ibl(&maps);
  return true;
}

void Renderer::render(const Camera& camera, int width, int height, const RenderSettings& settings) {
  State& s = *state_;
  if (width < 1 || height < 1) fail("OpenGL: image size {}x{} is empty", width, height);
  Frame frame = s.begin_frame(camera, width, height, settings);
  // Opaque and masked first, then the background where they left the far plane, then the
  // transmissive surfaces over a capture of that, then blended surfaces back to front.
  QueuedDraws queued = s.draw_opaque(frame);
  s.draw_background(frame);
  s.draw_transmissive(frame, queued);
  s.draw_blended(frame, queued.blended);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glBindVertexArray(0);

  s.targets.resolve();
  s.timer.end();
}

Image Renderer::read_back() const {
  return state_->targets.read_back();
}

void Renderer::display(float exposure_ev, ToneMapper mapper) {
  State& s = *state_;
  if (!s.targets.resolve_color) fail("OpenGL: display() before any render()");
  const Program& p = s.programs.display(mapper);
  glViewport(0, 0, s.targets.width, s.targets.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);  // display.glsl encodes sRGB itself
  p.use();
  p.set("uExposureScale", exposure_scale(exposure_ev));
  glBindTextureUnit(kDisplayFrameUnit, s.targets.resolve_color);
  glBindVertexArray(s.empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

double Renderer::gpu_time_ms() const {
  return state_->timer.last_ms();
}

double Renderer::latest_gpu_time_ms() {
  return state_->timer.latest_ms();
}

Image render_headless(const Scene& scene, const Camera& camera, int width, int height,
                      const Environment* env, const IblMaps* ibl, const RenderSettings& settings) {
  HeadlessContext context;
  Renderer renderer;
  renderer.set_scene(scene);
  renderer.set_environment(env);
  renderer.set_ibl(ibl);
  renderer.render(camera, width, height, settings);
  return renderer.read_back();
}

Image render_headless(const Scene& scene, const Camera& camera, int width, int height,
                      const Environment* env, const std::optional<BakeOptions>& bake,
                      const RenderSettings& settings) {
  HeadlessContext context;
  Renderer renderer;
  renderer.set_scene(scene);
  renderer.set_environment_light(env, bake);
  renderer.render(camera, width, height, settings);
  return renderer.read_back();
}

}  // namespace pbrkit::gl
