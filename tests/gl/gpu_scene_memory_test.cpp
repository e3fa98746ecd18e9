// What the OpenGL renderer allocates for a scene, known before it allocates it: a software
// rasteriser (llvmpipe) keeps buffers and textures in the process's own memory, so a scene
// that would not fit is refused with the figures instead of the process being killed.
#include <gtest/gtest.h>

#include <string>

#include "gl_test_context.h"
#include "pbrkit/gl/gpu_scene.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/error.h"

namespace pbrkit::gl {
namespace {

// One quad (4 vertices with positions, normals and one UV set; 2 triangles), an 8-bit RGBA
// 4 x 4 texture (mips 4x4, 2x2, 1x1: 21 texels) and a 16-bit grey 2 x 2 one (2x2, 1x1: 5
// texels, uploaded as RGBA16), two instances.
Scene quad_scene() {
  Scene scene;
  scene.source = "test:quad";
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals.assign(4, glm::vec3(0, 0, 1));
  mesh.texcoords0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = 0;
  scene.materials.push_back(Material{});
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0f), -1});
  scene.instances.push_back({0, glm::mat4(2.0f), -1});
  scene.textures.push_back(
      Texture::from_unorm8(4, 4, 4, std::vector<std::uint8_t>(4 * 4 * 4, 200), true));
  scene.textures.push_back(
      Texture::from_unorm16(2, 2, 1, std::vector<std::uint16_t>(2 * 2, 40000), false));
  return scene;
}

TEST(GlSceneMemory, BytesAreWhatTheUploadAllocates) {
  testing::context();
  const Scene scene = quad_scene();
  const GlSceneBytes b = gl_scene_bytes(scene);
  // By hand: 4 x (12 + 12 + 8) vertex bytes, 6 x 4 index bytes, 21 x 4 + 5 x 8 texture
  // bytes, two instances of two mat4s.
  EXPECT_EQ(b.vertices, 128u);
  EXPECT_EQ(b.indices, 24u);
  EXPECT_EQ(b.textures, 21u * 4u + 5u * 8u);
  EXPECT_EQ(b.instances, 2u * 2u * 64u);

  // And by GL's own account of what the upload made.
  GpuScene gpu;
  gpu.upload(scene);
  GLint64 buffer_bytes = 0;
  for (const GpuMesh& m : gpu.meshes)
    for (GLuint buffer : m.buffers) {
      GLint64 size = 0;
      if (glIsBuffer(buffer)) glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
      buffer_bytes += size;
    }
  EXPECT_EQ(std::size_t(buffer_bytes), b.vertices + b.indices);
  GLint64 instance_bytes = 0;
  glGetNamedBufferParameteri64v(gpu.instance_buffer, GL_BUFFER_SIZE, &instance_bytes);
  EXPECT_EQ(std::size_t(instance_bytes), b.instances);
  std::size_t texture_bytes = 0;
  for (GLuint tex : gpu.textures) {
    GLint levels = 0;
    glGetTextureParameteriv(tex, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    for (GLint level = 0; level < levels; ++level) {
      GLint w = 0, h = 0, r = 0, g = 0, bl = 0, a = 0;
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_WIDTH, &w);
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_HEIGHT, &h);
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_RED_SIZE, &r);
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_GREEN_SIZE, &g);
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_BLUE_SIZE, &bl);
      glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_ALPHA_SIZE, &a);
      texture_bytes += std::size_t(w) * std::size_t(h) * std::size_t(r + g + bl + a) / 8;
    }
  }
  EXPECT_EQ(texture_bytes, b.textures);
}

TEST(GlSceneMemory, SceneOverTheLimitIsRefusedWithTheFigures) {
  testing::context();
  const Scene scene = quad_scene();
  const std::size_t need = gl_scene_bytes(scene).total();
  GpuScene gpu;
  try {
    gpu.upload(scene, need - 1);
    FAIL() << "uploaded " << need << " bytes under a limit of " << need - 1;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test:quad"), std::string::npos) << what;
    EXPECT_NE(what.find("vertex buffers 0.0 MB"), std::string::npos) << what;
    EXPECT_NE(what.find("is available"), std::string::npos) << what;
  }
  EXPECT_TRUE(gpu.meshes.empty());  // nothing was allocated
  EXPECT_NO_THROW(gpu.upload(scene, need));
  EXPECT_EQ(gpu.meshes.size(), 1u);
  // A larger scene refused leaves the one uploaded before in place (the viewer keeps drawing
  // it when a dropped file does not fit).
  Scene larger = scene;
  larger.meshes.push_back(larger.meshes[0]);
  EXPECT_THROW(gpu.upload(larger, need), Error);
  EXPECT_EQ(gpu.meshes.size(), 1u);
  EXPECT_TRUE(glIsBuffer(gpu.meshes[0].buffers[0]));
}

}  // namespace
}  // namespace pbrkit::gl
