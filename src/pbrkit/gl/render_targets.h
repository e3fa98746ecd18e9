#pragma once
// Private to the OpenGL renderer (renderer.cpp): the frame's framebuffers. A frame is drawn
// into a float colour + depth target with `samples` samples per pixel (one: no MSAA) and
// resolved into a single-sample float texture, which read_back() and Renderer::display()
// read. Both are remade only when the size or the sample count changes. Frames with
// transmissive surfaces also capture the opaque frame into a mip-mapped colour texture
// (made on the first such frame) that those surfaces read (shaders/transmission.glsl);
// frames with thick ones (a volume thickness > 0) also capture its depth and draw each such
// object's back faces into a position + normal target first (shaders/thick_refraction.glsl,
// Wyman 2005).
#include <epoxy/gl.h>

#include "pbrkit/image/image.h"

namespace pbrkit::gl {

struct RenderTargets {
  // Framebuffers: multisampled (or not) render target, and the resolved one.
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth = 0;
  GLuint resolve_fbo = 0, resolve_color = 0;
  // The opaque frame for the transmission pass: single-sample, every mip level down to 1x1.
  GLuint transmission_fbo = 0, transmission_color = 0;
  // Its depth (where thick objects' exit rays meet the frame), made on first use.
  GLuint transmission_depth = 0;
  // One thick object's back faces: world position (w = 1 where covered) and outward normal.
  GLuint back_fbo = 0, back_position = 0, back_normal = 0, back_depth = 0;
  int width = 0, height = 0, samples = 0;

  RenderTargets() = default;
  ~RenderTargets() { release(); }
  RenderTargets(const RenderTargets&) = delete;
  RenderTargets& operator=(const RenderTargets&) = delete;

  /// Targets of `w` x `h` with `s` samples (Error if the driver cannot make them).
  void ensure(int w, int h, int s);
  void release();
  /// Resolves the samples into the single-sample float target.
  void resolve() const;
  /// Resolves what the multisampled target holds now into transmission_color's level 0
  /// and, with `mips`, builds its mip chain (a box-filter chain: glGenerateMipmap; without,
  /// the texture's levels are limited to 0, so no stale level can be read); with `depth`,
  /// also its depth into transmission_depth.
  void capture_frame(bool depth = false, bool mips = true);
  /// Binds the back-face target (made on first use) and clears the pixels [x0, x1) x [y0, y1)
  /// (GL's rows): no back face there. Leaves the scissor test on over that rectangle.
  void begin_back_faces(int x0, int y0, int x1, int y1);
  /// The resolved frame, linear RGBA float, row 0 at the top (as Image everywhere).
  Image read_back() const;
};

}  // namespace pbrkit::gl
