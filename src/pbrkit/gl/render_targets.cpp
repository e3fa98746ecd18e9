#include "pbrkit/gl/render_targets.h"

#include <algorithm>
#include <cstddef>

#include "pbrkit/util/error.h"

namespace pbrkit::gl {

void RenderTargets::release() {
  glDeleteFramebuffers(1, &msaa_fbo);
  glDeleteRenderbuffers(1, &msaa_color);
  glDeleteRenderbuffers(1, &msaa_depth);
  glDeleteFramebuffers(1, &resolve_fbo);
  glDeleteTextures(1, &resolve_color);
  glDeleteFramebuffers(1, &transmission_fbo);
  glDeleteTextures(1, &transmission_color);
  glDeleteTextures(1, &transmission_depth);
  glDeleteFramebuffers(1, &back_fbo);
  glDeleteTextures(1, &back_position);
  glDeleteTextures(1, &back_normal);
  glDeleteRenderbuffers(1, &back_depth);
  msaa_fbo = msaa_color = msaa_depth = resolve_fbo = resolve_color = 0;
  transmission_fbo = transmission_color = transmission_depth = 0;
  back_fbo = back_position = back_normal = back_depth = 0;
}

void RenderTargets::ensure(int w, int h, int s) {
  if (w == width && h == height && s == samples && msaa_fbo) return;
  release();
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

void RenderTargets::resolve() const {
  glBlitNamedFramebuffer(msaa_fbo, resolve_fbo, 0, 0, width, height, 0, 0, width, height,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

namespace {

// A single-level texture read at texel centres (no filtering between two surfaces' data).
GLuint nearest_texture(GLenum format, int w, int h) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

void RenderTargets::begin_back_faces(int x0, int y0, int x1, int y1) {
  if (!back_fbo) {
    back_position = nearest_texture(GL_RGBA32F, width, height);
    back_normal = nearest_texture(GL_RGBA32F, width, height);
    glCreateRenderbuffers(1, &back_depth);
    glNamedRenderbufferStorage(back_depth, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &back_fbo);
    glNamedFramebufferTexture(back_fbo, GL_COLOR_ATTACHMENT0, back_position, 0);
    glNamedFramebufferTexture(back_fbo, GL_COLOR_ATTACHMENT1, back_normal, 0);
    glNamedFramebufferRenderbuffer(back_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, back_depth);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(back_fbo, 2, buffers);
    if (glCheckNamedFramebufferStatus(back_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      fail("OpenGL: a {}x{} back-face position and normal target is not supported here", width,
           height);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, back_fbo);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, y0, x1 - x0, y1 - y0);
  const float zero[4] = {0, 0, 0, 0};
  const float far_depth = 1.0f;
  glClearNamedFramebufferfv(back_fbo, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(back_fbo, GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(back_fbo, GL_DEPTH, 0, &far_depth);
}

void RenderTargets::capture_frame(bool depth, bool mips) {
  int levels = 1;
  while ((std::max(width, height) >> levels) > 0) ++levels;
  if (!transmission_fbo) {
    glCreateTextures(GL_TEXTURE_2D, 1, &transmission_color);
    glTextureStorage2D(transmission_color, levels, GL_RGBA32F, width, height);
    glTextureParameteri(transmission_color, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(transmission_color, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(transmission_color, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(transmission_color, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &transmission_fbo);
    glNamedFramebufferTexture(transmission_fbo, GL_COLOR_ATTACHMENT0, transmission_color, 0);
    if (glCheckNamedFramebufferStatus(transmission_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      fail("OpenGL: a {}x{} mip-mapped float target is not supported here", width, height);
  }
  if (depth && !transmission_depth) {
    transmission_depth = nearest_texture(GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferTexture(transmission_fbo, GL_DEPTH_ATTACHMENT, transmission_depth, 0);
    if (glCheckNamedFramebufferStatus(transmission_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      fail("OpenGL: a {}x{} float depth texture is not supported here", width, height);
  }
  glBlitNamedFramebuffer(msaa_fbo, transmission_fbo, 0, 0, width, height, 0, 0, width, height,
                         GL_COLOR_BUFFER_BIT | (depth ? GL_DEPTH_BUFFER_BIT : 0u), GL_NEAREST);
  glTextureParameteri(transmission_color, GL_TEXTURE_MAX_LEVEL, mips ? levels - 1 : 0);
  if (mips) glGenerateTextureMipmap(transmission_color);
}

Image RenderTargets::read_back() const {
  Image flipped(width, height, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(resolve_color, 0, GL_RGBA, GL_FLOAT,
                    GLsizei(flipped.data.size() * sizeof(float)), flipped.data.data());
  // GL's row 0 is the bottom; Image's row 0 is the top.
  Image out(width, height, 4);
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(flipped.data.data() + std::size_t(height - 1 - y) * row, row,
                out.data.data() + std::size_t(y) * row);
  return out;
}

}  // namespace pbrkit::gl
