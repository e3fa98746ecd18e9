#include "pbrkit/gl/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/energy_texture.h"
#include "pbrkit/gl/program.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {

IblMaps ibl_maps_from_bake(BakeResult bake, const Environment& env) {
  IblMaps maps;
  maps.specular = std::move(bake.specular);
  maps.irradiance = std::move(bake.irradiance);
  maps.sh = bake.sh;
  maps.rotation_deg = env.rotation_deg;
  maps.intensity = env.intensity;
  return maps;
}

BakeOptions realtime_bake_options(int face_size, int samples) {
  BakeOptions bake;
  bake.face_size = face_size;
  bake.min_face_size = std::min(8, face_size);
  bake.samples = samples;
  bake.irradiance_size = 16;
  bake.lut_size = 32;
  bake.quadrature_budget = 0x1p30;
  return bake;
}

namespace {

// "name[i]" for a uniform array element.
std::string indexed(const char* name, int i) {
  return fmt::format("{}[{}]", name, i);
}

GLenum pixel_format(int channels) {
  switch (channels) {
    case 1:
      return GL_RED;
    case 2:
      return GL_RG;
    case 3:
      return GL_RGB;
    default:
      return GL_RGBA;
  }
}

GLint wrap_mode(WrapMode w) {
  switch (w) {
    case WrapMode::kClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case WrapMode::kMirroredRepeat:
      return GL_MIRRORED_REPEAT;
    case WrapMode::kRepeat:
      break;
  }
  return GL_REPEAT;
}

struct GpuMesh {
  GLuint vao = 0;
  std::array<GLuint, 7> buffers{};  // 6 attributes + indices
  GLsizei index_count = 0;
  bool has_colors = false;
  int material = -1;
  /// The material's alphaMode as drawn: 0 opaque, 1 mask, 2 blend; BLEND without any
  /// alpha below 1 is drawn opaque (scene.h has_alpha).
  int alpha_mode = 0;
  glm::vec3 center{0.0f};
};

// One cube texture with every level of `cube` (RGB float), or a 1x1 black one.
GLuint upload_cube(const Cubemap* cube) {
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &tex);
  if (!cube || cube->mips.empty()) {
    glTextureStorage2D(tex, 1, GL_RGBA32F, 1, 1);
    const float black[4] = {0, 0, 0, 1};
    for (int face = 0; face < 6; ++face)
      glTextureSubImage3D(tex, 0, 0, 0, face, 1, 1, 1, GL_RGBA, GL_FLOAT, black);
  } else {
    const int levels = cube->levels();
    glTextureStorage2D(tex, levels, GL_RGBA32F, cube->size(0), cube->size(0));
    for (int level = 0; level < levels; ++level)
      for (int face = 0; face < 6; ++face) {
        // The baker's faces are in the GL convention: mips[level][face] uploads as-is to
        // GL_TEXTURE_CUBE_MAP_POSITIVE_X + face (layer `face` with DSA).
        const Image& img = cube->mips[std::size_t(level)][std::size_t(face)];
        glTextureSubImage3D(tex, level, 0, 0, face, img.width, img.height, 1,
                            pixel_format(img.channels), GL_FLOAT, img.data.data());
      }
  }
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return tex;
}

// (cos a, sin a) of a = -rotation_deg in radians: equirect.glsl's world_to_env argument,
// the inverse of the environment's rotation about +Y (core/equirect.h's convention).
glm::vec2 env_rotation_cs(float rotation_deg) {
  const float a = -glm::radians(rotation_deg);
  return {std::cos(a), std::sin(a)};
}

// Compile-time features of the surface program (pbr_fragment.glsl says why they are not
// uniforms: on llvmpipe an unused branch still costs its texture fetches). Every
// combination is its own program, compiled on first use, as real-time engines do with
// their shader permutations.
struct SurfaceFeatures {
  unsigned textures = 0;  ///< bit t: texture t bound (baseColor, MR, normal, occlusion, emissive)
  bool colors = false;    ///< the mesh has COLOR_0
  int alpha_mode = 0;     ///< 0 opaque, 1 mask, 2 blend
  bool ibl = false;
  bool irradiance_sh = true;
  bool multiscatter = false;
  int geometry = 0;  ///< GeometryModel for punctual lights
  int fresnel = 0;   ///< 0 Schlick, 1 spherical Gaussian
  int light_count = 0;

  std::uint32_t key() const {
    return textures | unsigned(alpha_mode) << 5 | unsigned(ibl) << 7 |
           unsigned(irradiance_sh) << 8 | unsigned(multiscatter) << 9 | unsigned(geometry) << 10 |
           unsigned(fresnel) << 12 | unsigned(light_count) << 13 | unsigned(colors) << 18;
  }
  std::string defines() const {
    std::string d;
    for (int t = 0; t < 5; ++t)
      d += fmt::format("#define HAS_TEXTURE_{} {}\n", t, (textures >> t) & 1u);
    d += fmt::format("#define HAS_COLOR_0 {}\n", int(colors));
    d += fmt::format(
        "#define ALPHA_MODE {}\n#define IBL {}\n#define IRRADIANCE_SH {}\n"
        "#define MULTISCATTER {}\n#define GEOMETRY {}\n#define FRESNEL {}\n"
        "#define LIGHT_COUNT {}\n",
        alpha_mode, int(ibl), int(irradiance_sh), int(multiscatter), geometry, fresnel,
        light_count);
    return d;
  }
};

}  // namespace

struct Renderer::State {
  std::unordered_map<std::uint32_t, Program> surface_programs;  // by SurfaceFeatures::key
  std::array<Program, 3> background;                            // by background MODE
  std::array<Program, 4> display;  // by ToneMapper, compiled on first use
  std::array<GLuint, 3> energy{};  // per GeometryModel
  std::vector<GpuMesh> meshes;
  std::vector<GLuint> textures;
  std::vector<Material> materials;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  GLuint env_texture = 0;
  float env_rotation = 0.0f, env_intensity = 1.0f;
  bool has_env = false;
  GLuint specular_cube = 0, irradiance_cube = 0;
  int specular_levels = 1;
  bool has_ibl = false;
  IblMaps ibl_params;  // rotation, intensity and SH (cubes are on the GPU)
  GLuint white_texture = 0;
  GLuint empty_vao = 0;  // the background's full-screen triangle has no attributes
  // Framebuffers: multisampled (or not) render target, and the resolved one.
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth = 0;
  GLuint resolve_fbo = 0, resolve_color = 0;
  int width = 0, height = 0, samples = 0;
  // GL_TIMESTAMP pairs (begin, end) for two frames in turn, so that a viewer can read the
  // previous frame's time without waiting for the current one.
  std::array<GLuint, 4> timer{};
  std::array<bool, 2> timer_pending{};
  int timer_pair = 0;  // the pair of the last render()
  double latest_gpu_ms = 0.0;

  const Program& surface_program(const SurfaceFeatures& f) {
    auto it = surface_programs.find(f.key());
    if (it == surface_programs.end())
      it = surface_programs
               .emplace(f.key(),
                        Program::graphics("pbr_vertex.glsl", "pbr_fragment.glsl", f.defines()))
               .first;
    return it->second;
  }

  void release_scene() {
    for (GpuMesh& m : meshes) {
      glDeleteVertexArrays(1, &m.vao);
      glDeleteBuffers(GLsizei(m.buffers.size()), m.buffers.data());
    }
    meshes.clear();
    if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
    textures.clear();
  }

  void release_targets() {
    glDeleteFramebuffers(1, &msaa_fbo);
    glDeleteRenderbuffers(1, &msaa_color);
    glDeleteRenderbuffers(1, &msaa_depth);
    glDeleteFramebuffers(1, &resolve_fbo);
    glDeleteTextures(1, &resolve_color);
    msaa_fbo = msaa_color = msaa_depth = resolve_fbo = resolve_color = 0;
  }

  void ensure_targets(int w, int h, int s) {
    if (w == width && h == height && s == samples && msaa_fbo) return;
    release_targets();
    width = w, height = h, samples = s;
    glCreateRenderbuffers(1, &msaa_color);
    glCreateRenderbuffers(1, &msaa_depth);
    glNamedRenderbufferStorageMultisample(msaa_color, s > 1 ? s : 0, GL_RGBA32F, w, h);
    glNamedRenderbufferStorageMultisample(msaa_depth, s > 1 ? s : 0, GL_DEPTH_COMPONENT32F, w, h);
    glCreateFramebuffers(1, &msaa_fbo);
    glNamedFramebufferRenderbuffer(msaa_fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color);
    glNamedFramebufferRenderbuffer(msaa_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth);
    glCreateTextures(GL_TEXTURE_2D, 1, &resolve_color);
    glTextureStorage2D(resolve_color, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &resolve_fbo);
    glNamedFramebufferTexture(resolve_fbo, GL_COLOR_ATTACHMENT0, resolve_color, 0);
    if (glCheckNamedFramebufferStatus(msaa_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(resolve_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      fail("OpenGL: a {}x{} float framebuffer with {} samples is not supported here", w, h, s);
  }
};

Renderer::Renderer() : state_(std::make_unique<State>()) {
  State& s = *state_;
  // The default surface program is compiled up front, so that a driver without GL 4.5
  // features fails here with the compile log rather than at the first frame.
  s.surface_program(SurfaceFeatures{});
  for (int mode = 0; mode < 3; ++mode)
    s.background[std::size_t(mode)] =
        Program::graphics("background_vertex.glsl", "background_fragment.glsl",
                          fmt::format("#define MODE {}\n", mode));
  for (int g = 0; g < 3; ++g) s.energy[std::size_t(g)] = create_energy_texture(GeometryModel(g));
  glCreateTextures(GL_TEXTURE_2D, 1, &s.white_texture);
  glTextureStorage2D(s.white_texture, 1, GL_RGBA32F, 1, 1);
  const float white[4] = {1, 1, 1, 1};
  glTextureSubImage2D(s.white_texture, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, white);
  s.specular_cube = upload_cube(nullptr);
  s.irradiance_cube = upload_cube(nullptr);
  glCreateQueries(GL_TIMESTAMP, 4, s.timer.data());
  glCreateVertexArrays(1, &s.empty_vao);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
}

Renderer::~Renderer() {
  State& s = *state_;
  s.release_scene();
  s.release_targets();
  glDeleteTextures(3, s.energy.data());
  glDeleteTextures(1, &s.white_texture);
  glDeleteTextures(1, &s.specular_cube);
  glDeleteTextures(1, &s.irradiance_cube);
  if (s.env_texture) glDeleteTextures(1, &s.env_texture);
  glDeleteQueries(4, s.timer.data());
  glDeleteVertexArrays(1, &s.empty_vao);
}

void Renderer::set_scene(const Scene& scene) {
  State& s = *state_;
  s.release_scene();
  for (const Mesh& mesh : scene.meshes) {
    GpuMesh g;
    glCreateVertexArrays(1, &g.vao);
    glCreateBuffers(GLsizei(g.buffers.size()), g.buffers.data());
    auto attribute = [&](GLuint index, const void* data, std::size_t count, int components) {
      if (count == 0) return;
      glNamedBufferStorage(g.buffers[index], GLsizeiptr(count * components * sizeof(float)), data,
                           0);
      glVertexArrayVertexBuffer(g.vao, index, g.buffers[index], 0,
                                GLsizei(components * sizeof(float)));
      glVertexArrayAttribFormat(g.vao, index, components, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(g.vao, index, index);
      glEnableVertexArrayAttrib(g.vao, index);
    };
    attribute(0, mesh.positions.data(), mesh.positions.size(), 3);
    attribute(1, mesh.normals.data(), mesh.normals.size(), 3);
    attribute(2, mesh.tangents.data(), mesh.tangents.size(), 4);
    attribute(3, mesh.texcoords0.data(), mesh.texcoords0.size(), 2);
    attribute(4, mesh.texcoords1.data(), mesh.texcoords1.size(), 2);
    attribute(5, mesh.colors0.data(), mesh.colors0.size(), 4);
    g.has_colors = !mesh.colors0.empty();
    g.material = mesh.material;
    const AlphaMode mode = scene.material_of(mesh).alpha_mode;
    g.alpha_mode = !has_alpha(scene, mesh) ? 0 : mode == AlphaMode::kMask ? 1 : 2;
    glNamedBufferStorage(g.buffers[6], GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.empty() ? nullptr : mesh.indices.data(), 0);
    glVertexArrayElementBuffer(g.vao, g.buffers[6]);
    g.index_count = GLsizei(mesh.indices.size());
    Bounds b;
    for (const glm::vec3& p : mesh.positions) b.extend(p);
    g.center = b.empty() ? glm::vec3(0.0f) : b.center();
    s.meshes.push_back(g);
  }
  for (const Texture& t : scene.textures) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    if (t.mips.empty()) {
      glTextureStorage2D(tex, 1, GL_RGBA32F, 1, 1);
      const float white[4] = {1, 1, 1, 1};
      glTextureSubImage2D(tex, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, white);
    } else {
      glTextureStorage2D(tex, GLsizei(t.mips.size()), GL_RGBA32F, t.width(), t.height());
      for (std::size_t level = 0; level < t.mips.size(); ++level) {
        const Image& img = t.mips[level];
        glTextureSubImage2D(tex, GLint(level), 0, 0, img.width, img.height,
                            pixel_format(img.channels), GL_FLOAT, img.data.data());
      }
    }
    const bool mip = t.sampler.min_mipmap && t.mips.size() > 1;
    const bool lin = t.sampler.min == FilterMode::kLinear;
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        mip ? (lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR)
                            : (lin ? GL_LINEAR : GL_NEAREST));
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER,
                        t.sampler.mag == FilterMode::kLinear ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, wrap_mode(t.sampler.wrap_s));
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, wrap_mode(t.sampler.wrap_t));
    s.textures.push_back(tex);
  }
  s.materials = scene.materials;
  s.instances = scene.instances;
  s.lights = scene.lights;
}

void Renderer::set_environment(const Environment* env) {
  State& s = *state_;
  if (s.env_texture) glDeleteTextures(1, &s.env_texture);
  s.env_texture = 0;
  s.has_env = env && !env->map.empty();
  if (!s.has_env) return;
  glCreateTextures(GL_TEXTURE_2D, 1, &s.env_texture);
  glTextureStorage2D(s.env_texture, 1, GL_RGBA32F, env->map.width, env->map.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(s.env_texture, 0, 0, 0, env->map.width, env->map.height,
                      pixel_format(env->map.channels), GL_FLOAT, env->map.data.data());
  // Bilinear, u wraps (the seam at u = 0 / 1), v clamps at the poles: Environment::eval.
  glTextureParameteri(s.env_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(s.env_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(s.env_texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(s.env_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  s.env_rotation = env->rotation_deg;
  s.env_intensity = env->intensity;
}

void Renderer::set_ibl(const IblMaps* maps) {
  State& s = *state_;
  glDeleteTextures(1, &s.specular_cube);
  glDeleteTextures(1, &s.irradiance_cube);
  s.has_ibl = maps != nullptr && !maps->specular.mips.empty();
  s.specular_cube = upload_cube(s.has_ibl ? &maps->specular : nullptr);
  s.irradiance_cube = upload_cube(s.has_ibl ? &maps->irradiance : nullptr);
  s.specular_levels = s.has_ibl ? maps->specular.levels() : 1;
  if (s.has_ibl) {
    s.ibl_params.sh = maps->sh;
    s.ibl_params.rotation_deg = maps->rotation_deg;
    s.ibl_params.intensity = maps->intensity;
  }
}

void Renderer::render(const Camera& camera, int width, int height, const RenderSettings& settings) {
  State& s = *state_;
  if (width < 1 || height < 1) fail("OpenGL: image size {}x{} is empty", width, height);
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  s.ensure_targets(width, height, std::clamp(settings.msaa, 1, std::max(1, int(max_samples))));
  const float aspect = float(width) / float(height);
  const glm::mat4 view = view_matrix(camera);
  const glm::mat4 projection = projection_matrix(camera, aspect);
  const glm::mat4 view_projection = projection * view;

  // GPU time between two timestamps (llvmpipe's GL_TIME_ELAPSED reports nonsense).
  s.timer_pair = 1 - s.timer_pair;
  glQueryCounter(s.timer[std::size_t(2 * s.timer_pair)], GL_TIMESTAMP);
  glBindFramebuffer(GL_FRAMEBUFFER, s.msaa_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  const float rotation_delta = settings.env_rotation_deg - s.ibl_params.rotation_deg;
  const float ibl_scale = settings.env_intensity / std::max(s.ibl_params.intensity, 1e-30f);

  // The punctual lights of this frame (their number is compiled into the program).
  constexpr int kMaxLights = 16;
  std::vector<const Light*> lights;
  for (std::size_t i = 0; i < s.lights.size() && settings.lights; ++i) {
    if (i < settings.light_enabled.size() && !settings.light_enabled[i]) continue;
    if (int(lights.size()) < kMaxLights) lights.push_back(&s.lights[i]);
  }
  SurfaceFeatures frame;
  const GeometryModel direct = direct_geometry(settings.brdf.model);
  const GeometryModel ibl = ibl_geometry(settings.brdf.model);
  frame.ibl = settings.ibl && s.has_ibl;
  frame.irradiance_sh = settings.irradiance == IrradianceMode::kSH;
  frame.multiscatter = settings.brdf.multiscatter;
  frame.geometry = int(direct);
  frame.fresnel = settings.fresnel == FresnelMode::kSchlick ? 0 : 1;
  frame.light_count = int(lights.size());
  glBindTextureUnit(5, s.energy[std::size_t(direct)]);
  glBindTextureUnit(6, s.energy[std::size_t(ibl)]);
  glBindTextureUnit(7, s.specular_cube);
  glBindTextureUnit(8, s.irradiance_cube);

  // The frame's uniforms, set once per frame on each program the frame uses.
  std::vector<GLuint> prepared;
  auto prepare = [&](const Program& p) {
    if (std::find(prepared.begin(), prepared.end(), p.id()) != prepared.end()) return;
    prepared.push_back(p.id());
    p.set("uViewProjection", view_projection);
    p.set("uCameraPosition", camera.position());
    p.set("uMetallicOverride", settings.metallic_override);
    p.set("uRoughnessOverride", settings.roughness_override);
    glProgramUniform3fv(p.id(), p.location("uSH"), 9, &s.ibl_params.sh[0].x);
    p.set("uSpecularLevels", s.specular_levels);
    p.set("uIblRotation", env_rotation_cs(rotation_delta));
    p.set("uIblScale", ibl_scale);
    for (int k = 0; k < int(lights.size()); ++k) {
      const Light& l = *lights[std::size_t(k)];
      p.set(indexed("uLightType", k).c_str(), l.type == Light::Type::kPoint  ? 0
                                              : l.type == Light::Type::kSpot ? 1
                                                                             : 2);
      p.set(indexed("uLightPosition", k).c_str(), l.position);
      p.set(indexed("uLightDirection", k).c_str(), glm::normalize(l.direction));
      p.set(indexed("uLightRadiance", k).c_str(), l.color * l.intensity);
      p.set(indexed("uLightRange", k).c_str(), l.range.value_or(0.0f));
      // KHR_lights_punctual's spot falloff: scale = 1 / max(0.001, cos(inner) - cos(outer)).
      const float scale =
          1.0f / std::max(0.001f, std::cos(l.inner_cone_angle) - std::cos(l.outer_cone_angle));
      p.set(indexed("uLightCone", k).c_str(),
            glm::vec2(scale, -std::cos(l.outer_cone_angle) * scale));
    }
  };

  // Opaque and masked first, then the background where they left the far plane, then
  // blended surfaces back to front (sorted by view depth).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  std::vector<std::pair<float, std::size_t>> blended;
  auto material_of = [&](const GpuMesh& mesh) -> const Material& {
    return mesh.material >= 0 && std::size_t(mesh.material) < s.materials.size()
               ? s.materials[std::size_t(mesh.material)]
               : Scene::default_material();
  };
  // `cull`: the faces to cull (GL_BACK, GL_FRONT), or 0 for the material's choice.
  auto draw = [&](std::size_t index, GLenum cull = 0) {
    const Instance& inst = s.instances[index];
    const GpuMesh& mesh = s.meshes[std::size_t(inst.mesh)];
    const Material& m = material_of(mesh);
    const std::array<const TextureRef*, 5> refs = m.textures();
    SurfaceFeatures features = frame;
    features.alpha_mode = mesh.alpha_mode;
    features.colors = mesh.has_colors;
    for (int t = 0; t < 5; ++t) {
      const TextureRef& ref = *refs[std::size_t(t)];
      if (ref.valid() && std::size_t(ref.texture) < s.textures.size()) features.textures |= 1u << t;
    }
    const Program& p = s.surface_program(features);
    prepare(p);
    p.use();
    p.set("uModel", inst.transform);
    p.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(inst.transform)));
    p.set("uBaseColorFactor", m.base_color_factor);
    p.set("uMetallicFactor", m.metallic_factor);
    p.set("uRoughnessFactor", m.roughness_factor);
    p.set("uEmissive", m.emissive_factor * m.emissive_strength);
    p.set("uNormalScale", m.normal_scale);
    p.set("uOcclusionStrength", m.occlusion_strength);
    p.set("uAlphaCutoff", m.alpha_cutoff);
    for (int t = 0; t < 5; ++t) {
      const TextureRef& ref = *refs[std::size_t(t)];
      const bool valid = (features.textures >> t) & 1u;
      const int k = t;
      p.set(indexed("uTexcoordSet", k).c_str(), ref.texcoord);
      p.set(indexed("uTextureTransform", k).c_str(),
            ref.transform ? ref.transform->matrix() : glm::mat3(1.0f));
      glBindTextureUnit(GLuint(t), valid ? s.textures[std::size_t(ref.texture)] : s.white_texture);
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
    glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
  };
  for (std::size_t i = 0; i < s.instances.size(); ++i) {
    const Instance& inst = s.instances[i];
    if (inst.mesh < 0 || std::size_t(inst.mesh) >= s.meshes.size()) continue;
    const GpuMesh& mesh = s.meshes[std::size_t(inst.mesh)];
    if (mesh.alpha_mode == 2) {
      const glm::vec4 c = view * inst.transform * glm::vec4(mesh.center, 1.0f);
      blended.emplace_back(c.z, i);  // view space looks down -Z: most negative is farthest
    } else {
      draw(i);
    }
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);

  // Background: a full-screen triangle at the far plane, shaded only where no opaque
  // surface is (depth still 1.0), without writing depth.
  {
    int mode = 2;
    glm::vec3 color = settings.background.color;
    if (settings.background.mode == Background::Mode::kEnvironment && s.has_env) mode = 0;
    if (settings.background.mode == Background::Mode::kBlurred && s.has_ibl) mode = 1;
    if (settings.background.mode != Background::Mode::kColor && mode == 2) color = glm::vec3(0.0f);
    const Program& p = s.background[std::size_t(mode)];
    p.use();
    p.set("uColor", color);
    p.set("uInverseProjection", glm::inverse(projection));
    p.set("uCameraToWorld", glm::mat3(camera.camera_to_world));
    p.set("uEnvRotation", env_rotation_cs(settings.env_rotation_deg));
    p.set("uEnvScale", settings.env_intensity / std::max(s.env_intensity, 1e-30f));
    p.set("uIblRotation", env_rotation_cs(rotation_delta));
    p.set("uIblScale", ibl_scale);
    p.set("uBlurLod", settings.background.blur_lod);
    glBindTextureUnit(0, s.env_texture ? s.env_texture : s.white_texture);
    glBindTextureUnit(1, s.specular_cube);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glBindVertexArray(s.empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }

  if (!blended.empty()) {
    std::sort(blended.begin(), blended.end());
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    // A double-sided blended mesh is drawn back faces first, then front faces: the far
    // side of a closed (convex) surface is composited before the near one whatever the
    // triangle order. Layers within one side are drawn in index order (no per-triangle
    // sorting): concave meshes can still show the wrong layer on top.
    for (const auto& b : blended) {
      if (material_of(s.meshes[std::size_t(s.instances[b.second].mesh)]).double_sided) {
        draw(b.second, GL_FRONT);
        draw(b.second, GL_BACK);
      } else {
        draw(b.second);
      }
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glBindVertexArray(0);

  // Resolve the samples into the single-sample float target.
  glBlitNamedFramebuffer(s.msaa_fbo, s.resolve_fbo, 0, 0, width, height, 0, 0, width, height,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glQueryCounter(s.timer[std::size_t(2 * s.timer_pair + 1)], GL_TIMESTAMP);
  s.timer_pending[std::size_t(s.timer_pair)] = true;
}

Image Renderer::read_back() const {
  const State& s = *state_;
  Image flipped(s.width, s.height, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(s.resolve_color, 0, GL_RGBA, GL_FLOAT,
                    GLsizei(flipped.data.size() * sizeof(float)), flipped.data.data());
  // GL's row 0 is the bottom; Image's row 0 is the top.
  Image out(s.width, s.height, 4);
  const std::size_t row = std::size_t(s.width) * 4;
  for (int y = 0; y < s.height; ++y)
    std::copy_n(flipped.data.data() + std::size_t(s.height - 1 - y) * row, row,
                out.data.data() + std::size_t(y) * row);
  return out;
}

void Renderer::display(float exposure_ev, ToneMapper mapper) {
  State& s = *state_;
  if (!s.resolve_color) fail("OpenGL: display() before any render()");
  Program& p = s.display[std::size_t(mapper)];
  if (!p.id())
    p = Program::graphics("display_vertex.glsl", "display_fragment.glsl",
                          fmt::format("#define TONE_MAPPER {}\n", int(mapper)));
  glViewport(0, 0, s.width, s.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);  // display.glsl encodes sRGB itself
  p.use();
  p.set("uExposureScale", exposure_scale(exposure_ev));
  glBindTextureUnit(0, s.resolve_color);
  glBindVertexArray(s.empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

namespace {

double timer_pair_ms(const std::array<GLuint, 4>& timer, int pair) {
  GLuint64 begin = 0, end = 0;
  glGetQueryObjectui64v(timer[std::size_t(2 * pair)], GL_QUERY_RESULT, &begin);
  glGetQueryObjectui64v(timer[std::size_t(2 * pair + 1)], GL_QUERY_RESULT, &end);
  return end > begin ? double(end - begin) * 1e-6 : 0.0;
}

}  // namespace

double Renderer::gpu_time_ms() const {
  const State& s = *state_;
  if (!s.timer_pending[std::size_t(s.timer_pair)]) return 0.0;
  return timer_pair_ms(s.timer, s.timer_pair);
}

double Renderer::latest_gpu_time_ms() {
  State& s = *state_;
  // The last frame's pair if it is done, else the frame before's (done long ago on any
  // GPU; reading it may wait only when it is not).
  for (int pair : {s.timer_pair, 1 - s.timer_pair}) {
    if (!s.timer_pending[std::size_t(pair)]) continue;
    GLint available = 0;
    glGetQueryObjectiv(s.timer[std::size_t(2 * pair + 1)], GL_QUERY_RESULT_AVAILABLE, &available);
    if (available || pair != s.timer_pair) {
      s.latest_gpu_ms = timer_pair_ms(s.timer, pair);
      break;
    }
  }
  return s.latest_gpu_ms;
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

}  // namespace pbrkit::gl
