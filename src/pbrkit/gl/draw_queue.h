#pragma once
// Private to the OpenGL renderer (renderer.cpp): the draw queue of a software rasteriser.
// llvmpipe keeps every triangle drawn since the frame's last wait in its queue, so a frame of
// millions of instanced triangles would hold them all at once; on a software rasteriser the
// renderer draws in chunks and waits for the queue (glFinish) every
// RenderSettings::software_queue_triangles triangles, which bounds that memory. Each triangle
// is rasterised from the same vertices and in the same order as in one draw, so the image is
// the same (the invariance rules, OpenGL 4.5 core profile, appendix A). A GPU's driver needs
// no such wait, and there every draw is one call.
#include <cstddef>

namespace pbrkit::gl {

class DrawQueue {
 public:
  /// `software`: the context is a software rasteriser's (context.h's is_software_renderer).
  explicit DrawQueue(bool software = false) : software_(software) {}

  /// At the start of a frame: at most `queue_triangles` triangles between waits
  /// (RenderSettings::software_queue_triangles; 0: never wait), none queued yet.
  void begin_frame(std::size_t queue_triangles);
  /// The most triangles a draw may hold and be followed by no wait (0: no limit, as on a
  /// GPU).
  std::size_t limit() const { return limit_; }
  /// `instances` instances of the bound vertex array's first `triangles` triangles, from the
  /// instance slot its program's uInstanceBase names: with a limit, a mesh of more triangles
  /// in index ranges of at most limit(), and a wait once that many have been queued.
  void draw_triangles(std::size_t triangles, std::size_t instances);

 private:
  bool software_ = false;
  std::size_t limit_ = 0;
  std::size_t queued_ = 0;  // triangles drawn since the frame began or last waited
};

}  // namespace pbrkit::gl
