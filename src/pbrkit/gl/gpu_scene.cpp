#include "pbrkit/gl/gpu_scene.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/gpu_deformation.h"
#include "pbrkit/util/available_memory.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {

namespace {

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

// Uploads one level of integer samples as RGBA: RGB and RGBA as they are (GL sets a
// missing alpha to 1); grey and grey-alpha expanded to (g, g, g, a) as Texture's lookups
// expand them (GL's own RED/RG would leave green and blue 0).
template <class T>
void upload_level(GLuint tex, const Texture& t, int level, const T* src, GLenum type) {
  const TextureLevel& l = t.levels[std::size_t(level)];
  if (t.channels >= 3) {
    glTextureSubImage2D(tex, level, 0, 0, l.width, l.height, pixel_format(t.channels), type, src);
    return;
  }
  const std::size_t n = std::size_t(l.width) * std::size_t(l.height);
  std::vector<T> rgba(n * 4);
  for (std::size_t i = 0; i < n; ++i) {
    const T g = src[i * std::size_t(t.channels)];
    rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = g;
    rgba[4 * i + 3] = t.channels == 2 ? src[i * 2 + 1] : std::numeric_limits<T>::max();
  }
  glTextureSubImage2D(tex, level, 0, 0, l.width, l.height, GL_RGBA, type, rgba.data());
}

// The mean linear RGB of `t`: its mip chain's last level, 1x1 (scene.h: a Texture always
// has the whole chain, box-filtered in linear space).
glm::vec3 texture_mean(const Texture& t) {
  return t.empty() ? glm::vec3(1.0f) : glm::vec3(t.texel(int(t.levels.size()) - 1, 0, 0));
}

// The format a texture's own mip chain is uploaded in, at its precision: 8-bit as
// GL_SRGB8_ALPHA8 (colour) or GL_RGBA8, which GL decodes to linear before filtering as
// Texture::sample does (OpenGL 4.6 section 8.24); 16-bit data as GL_RGBA16; 16-bit colour
// (GL has no 16-bit sRGB format) and float as GL_RGBA32F, decoded here.
GLenum upload_format(const Texture& t) {
  if (t.format == TexelFormat::kUnorm8) return t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
  if (t.format == TexelFormat::kUnorm16 && !t.srgb) return GL_RGBA16;
  return GL_RGBA32F;
}

std::size_t texel_bytes(GLenum format) {
  return format == GL_RGBA32F ? 16 : format == GL_RGBA16 ? 8 : 4;
}

void upload_texture(GLuint tex, const Texture& t) {
  const GLsizei levels = GLsizei(t.levels.size());
  const GLenum format = upload_format(t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureStorage2D(tex, levels, format, t.width(), t.height());
  if (format == GL_RGBA8 || format == GL_SRGB8_ALPHA8) {
    for (GLsizei level = 0; level < levels; ++level)
      upload_level(tex, t, level, t.texels8.data() + t.levels[std::size_t(level)].offset,
                   GL_UNSIGNED_BYTE);
  } else if (format == GL_RGBA16) {
    for (GLsizei level = 0; level < levels; ++level)
      upload_level(tex, t, level, t.texels16.data() + t.levels[std::size_t(level)].offset,
                   GL_UNSIGNED_SHORT);
  } else {
    for (GLsizei level = 0; level < levels; ++level) {
      const Image img = t.level_image(level);
      glTextureSubImage2D(tex, level, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT,
                          img.data.data());
    }
  }
}

// A mesh's vertex arrays at their attribute locations 0-5 (pbr_vertex.glsl): the data, the
// number of vertices it has (0: absent) and the floats per vertex.
struct VertexArray {
  const void* data;
  std::size_t count;
  int components;
};
std::array<VertexArray, 6> vertex_arrays(const Mesh& m) {
  return {{{m.positions.data(), m.positions.size(), 3},
           {m.normals.data(), m.normals.size(), 3},
           {m.tangents.data(), m.tangents.size(), 4},
           {m.texcoords0.data(), m.texcoords0.size(), 2},
           {m.texcoords1.data(), m.texcoords1.size(), 2},
           {m.colors0.data(), m.colors0.size(), 4}}};
}

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

}  // namespace

GlSceneBytes gl_scene_bytes(const Scene& scene) {
  GlSceneBytes b;
  for (const Mesh& mesh : scene.meshes) {
    for (const VertexArray& a : vertex_arrays(mesh))
      b.vertices += sizeof(float) * a.count * std::size_t(a.components);
    b.indices += sizeof(std::uint32_t) * mesh.indices.size();
  }
  for (const Texture& t : scene.textures) {
    // An empty texture is uploaded as one float texel.
    std::size_t texels = t.empty() ? 1 : 0;
    for (const TextureLevel& l : t.levels) texels += std::size_t(l.width) * std::size_t(l.height);
    b.textures += texel_bytes(t.empty() ? GL_RGBA32F : upload_format(t)) * texels;
  }
  b.instances = 2 * sizeof(glm::mat4) * scene.instances.size();
  b.deforming = gl_deformation_bytes(scene);
  return b;
}

namespace {

std::string megabytes(std::size_t bytes) {
  return fmt::format("{:.1f} MB", double(bytes) * 1e-6);
}

}  // namespace

void GpuScene::upload(const Scene& scene, std::size_t memory_limit) {
  const GlSceneBytes need = gl_scene_bytes(scene);
  const bool software = is_software_renderer(current_renderer());
  std::size_t frame_reserve = 0;
  if (memory_limit == 0 && software) {
    // What the frame needs besides the scene, kept free: llvmpipe's queue of binned
    // triangles (bounded by RenderSettings::software_queue_triangles; about 100 MB on an
    // 8 M-triangle mesh) and the render targets (about 115 MB more at 1280x720 than at
    // 128x128); docs/benchmarks_archive.md, "The OpenGL renderer's memory check".
    constexpr std::size_t kFrameBytes = std::size_t(224) << 20;
    const std::size_t available = available_memory();
    frame_reserve = std::min(available, kFrameBytes);
    memory_limit = std::max<std::size_t>(1, available - frame_reserve);
  }
  if (memory_limit > 0 && need.total() > memory_limit)
    fail(
        "{}: the OpenGL renderer's copy of the scene needs {} (vertex buffers {}, indices {}, "
        "textures {}, instances {}, deforming meshes {}) but {} is available{}{}",
        scene.source, megabytes(need.total()), megabytes(need.vertices), megabytes(need.indices),
        megabytes(need.textures), megabytes(need.instances), megabytes(need.deforming),
        megabytes(memory_limit),
        frame_reserve > 0 ? fmt::format(" ({} more kept for the frame)", megabytes(frame_reserve))
                          : "",
        software ? "; a software rasteriser keeps them in this process's memory" : "");
  release();  // only now: a scene refused leaves the one drawn before in place
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
    const std::array<VertexArray, 6> arrays = vertex_arrays(mesh);
    for (GLuint i = 0; i < GLuint(arrays.size()); ++i)
      attribute(i, arrays[i].data, arrays[i].count, arrays[i].components);
    g.has_colors = !mesh.colors0.empty();
    g.closed = mesh.closed;
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
    if (!b.empty()) g.bounds_min = b.min, g.bounds_max = b.max;
    if (!b.empty() && mesh.normals.size() == mesh.positions.size()) {
      // A sphere: every vertex at one distance from the centre, and its normal radial (a
      // box's corners, too, lie on a sphere; their normals are its faces').
      float lo = std::numeric_limits<float>::infinity(), hi = 0.0f, radial = 1.0f;
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 d = mesh.positions[i] - g.center;
        const float r = glm::length(d);
        lo = std::min(lo, r), hi = std::max(hi, r);
        if (r > 0.0f) radial = std::min(radial, glm::dot(d / r, glm::normalize(mesh.normals[i])));
      }
      if (hi > 0.0f && lo >= 0.97f * hi && radial >= 0.97f) g.sphere_radius = hi;
    }
    double area = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const std::uint32_t a = mesh.indices[t], b1 = mesh.indices[t + 1], c = mesh.indices[t + 2];
      if (std::max({a, b1, c}) >= mesh.positions.size()) continue;
      area += 0.5 * double(glm::length(glm::cross(mesh.positions[b1] - mesh.positions[a],
                                                  mesh.positions[c] - mesh.positions[a])));
    }
    g.surface_area = float(area);
    meshes.push_back(g);
  }
  for (const Texture& t : scene.textures) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    if (t.empty()) {
      glTextureStorage2D(tex, 1, GL_RGBA32F, 1, 1);
      const float white[4] = {1, 1, 1, 1};
      glTextureSubImage2D(tex, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, white);
    } else {
      upload_texture(tex, t);
    }
    const bool mip = t.sampler.min_mipmap && t.levels.size() > 1;
    const bool lin = t.sampler.min == FilterMode::kLinear;
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        mip ? (lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR)
                            : (lin ? GL_LINEAR : GL_NEAREST));
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER,
                        t.sampler.mag == FilterMode::kLinear ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, wrap_mode(t.sampler.wrap_s));
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, wrap_mode(t.sampler.wrap_t));
    textures.push_back(tex);
    texture_means.push_back(texture_mean(t));
  }
  materials = scene.materials;
  instances = scene.instances;
  lights = scene.lights;
  upload_instances();
  if (glGetError() == GL_OUT_OF_MEMORY) {
    release();  // not a scene drawn in part
    fail(
        "{}: the GPU ran out of memory for the scene's {} (vertex buffers {}, indices {}, "
        "textures {})",
        scene.source, megabytes(need.total()), megabytes(need.vertices), megabytes(need.indices),
        megabytes(need.textures));
  }
}

void GpuScene::upload_instances() {
  // Slots ordered by (mesh, mirrored), instances of one key in scene order: each key's
  // instances are one run. A mirrored instance (negative determinant) flips its triangles'
  // winding, so it cannot share a draw (one glFrontFace) with unmirrored ones.
  const auto mirrored = [&](std::size_t i) {
    return glm::determinant(glm::mat3(instances[i].transform)) < 0.0f;
  };
  const auto valid = [&](std::size_t i) {
    return instances[i].mesh >= 0 && std::size_t(instances[i].mesh) < meshes.size();
  };
  at_slot.resize(instances.size());
  std::iota(at_slot.begin(), at_slot.end(), std::size_t(0));
  std::stable_sort(at_slot.begin(), at_slot.end(), [&](std::size_t a, std::size_t b) {
    const int ma = valid(a) ? instances[a].mesh : -1, mb = valid(b) ? instances[b].mesh : -1;
    return ma != mb ? ma < mb : mirrored(a) < mirrored(b);
  });
  slot_of.assign(instances.size(), 0);
  std::vector<glm::mat4> matrices(2 * std::max<std::size_t>(instances.size(), 1), glm::mat4(1.0f));
  runs.clear();
  for (std::size_t slot = 0; slot < at_slot.size(); ++slot) {
    const std::size_t i = at_slot[slot];
    slot_of[i] = slot;
    matrices[2 * slot] = instances[i].transform;
    matrices[2 * slot + 1] = glm::mat4(glm::inverseTranspose(glm::mat3(instances[i].transform)));
    if (!valid(i)) continue;
    const bool joins = !runs.empty() && slot > 0 && valid(at_slot[slot - 1]) &&
                       instances[at_slot[slot - 1]].mesh == instances[i].mesh &&
                       mirrored(at_slot[slot - 1]) == mirrored(i);
    if (joins)
      ++runs.back().count;
    else
      runs.push_back({slot, 1});
  }
  if (instance_buffer) glDeleteBuffers(1, &instance_buffer);
  glCreateBuffers(1, &instance_buffer);
  // Dynamic: a pose rewrites the transforms (update_instances).
  glNamedBufferStorage(instance_buffer, GLsizeiptr(matrices.size() * sizeof(glm::mat4)),
                       matrices.data(), GL_DYNAMIC_STORAGE_BIT);
}

void GpuScene::update_instances(const std::vector<Instance>& posed) {
  bool flipped = false;
  for (std::size_t i = 0; i < instances.size() && i < posed.size(); ++i) {
    flipped = flipped || (glm::determinant(glm::mat3(instances[i].transform)) < 0.0f) !=
                             (glm::determinant(glm::mat3(posed[i].transform)) < 0.0f);
    instances[i].transform = posed[i].transform;
  }
  if (flipped) {
    upload_instances();
    return;
  }
  std::vector<glm::mat4> matrices(2 * std::max<std::size_t>(instances.size(), 1), glm::mat4(1.0f));
  for (std::size_t slot = 0; slot < at_slot.size(); ++slot) {
    const glm::mat4& m = instances[at_slot[slot]].transform;
    matrices[2 * slot] = m;
    matrices[2 * slot + 1] = glm::mat4(glm::inverseTranspose(glm::mat3(m)));
  }
  glNamedBufferSubData(instance_buffer, 0, GLsizeiptr(matrices.size() * sizeof(glm::mat4)),
                       matrices.data());
}

void GpuScene::release() {
  for (GpuMesh& m : meshes) {
    glDeleteVertexArrays(1, &m.vao);
    glDeleteBuffers(GLsizei(m.buffers.size()), m.buffers.data());
  }
  meshes.clear();
  if (instance_buffer) glDeleteBuffers(1, &instance_buffer);
  instance_buffer = 0;
  if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
  textures.clear();
  texture_means.clear();
  // Nothing may index the meshes released.
  materials.clear();
  instances.clear();
  lights.clear();
  slot_of.clear();
  at_slot.clear();
  runs.clear();
}

const Material& GpuScene::material_of(const GpuMesh& mesh) const {
  return mesh.material >= 0 && std::size_t(mesh.material) < materials.size()
             ? materials[std::size_t(mesh.material)]
             : Scene::default_material();
}

GpuEnvironment::GpuEnvironment() {
  specular_cube = upload_cube(nullptr);
  irradiance_cube = upload_cube(nullptr);
  sheen_cube = upload_cube(nullptr);
}

GpuEnvironment::~GpuEnvironment() {
  glDeleteTextures(1, &specular_cube);
  glDeleteTextures(1, &irradiance_cube);
  glDeleteTextures(1, &sheen_cube);
  if (env_texture) glDeleteTextures(1, &env_texture);
}

void GpuEnvironment::set_environment(const Environment* env) {
  if (env_texture) glDeleteTextures(1, &env_texture);
  env_texture = 0;
  has_env = env && !env->map.empty();
  if (!has_env) return;
  glCreateTextures(GL_TEXTURE_2D, 1, &env_texture);
  glTextureStorage2D(env_texture, 1, GL_RGBA32F, env->map.width, env->map.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(env_texture, 0, 0, 0, env->map.width, env->map.height,
                      pixel_format(env->map.channels), GL_FLOAT, env->map.data.data());
  // Bilinear, u wraps (the seam at u = 0 / 1), v clamps at the poles: Environment::eval.
  glTextureParameteri(env_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(env_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(env_texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(env_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  env_rotation = env->rotation_deg;
  env_intensity = env->intensity;
}

void GpuEnvironment::set_ibl(const IblMaps* maps) {
  glDeleteTextures(1, &specular_cube);
  glDeleteTextures(1, &irradiance_cube);
  glDeleteTextures(1, &sheen_cube);
  has_ibl = maps != nullptr && !maps->specular.mips.empty();
  specular_cube = upload_cube(has_ibl ? &maps->specular : nullptr);
  irradiance_cube = upload_cube(has_ibl ? &maps->irradiance : nullptr);
  specular_levels = has_ibl ? maps->specular.levels() : 1;
  // Maps without the sheen chain (made before it existed) light sheen with the GGX cube.
  const bool sheen = has_ibl && !maps->sheen.mips.empty();
  sheen_cube = upload_cube(sheen ? &maps->sheen : has_ibl ? &maps->specular : nullptr);
  sheen_levels = sheen ? maps->sheen.levels() : specular_levels;
  if (has_ibl) {
    ibl_params.sh = maps->sh;
    ibl_params.rotation_deg = maps->rotation_deg;
    ibl_params.intensity = maps->intensity;
  }
}

}  // namespace pbrkit::gl
