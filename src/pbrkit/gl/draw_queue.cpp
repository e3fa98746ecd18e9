#include "pbrkit/gl/draw_queue.h"

#include <algorithm>
#include <cstdint>

#include <epoxy/gl.h>

namespace pbrkit::gl {

void DrawQueue::begin_frame(std::size_t queue_triangles) {
  limit_ = software_ ? queue_triangles : 0;
  queued_ = 0;
}

void DrawQueue::draw_triangles(std::size_t triangles, std::size_t instances) {
  const std::size_t range = limit_ > 0 ? limit_ : triangles;
  for (std::size_t first = 0; first < triangles; first += range) {
    const std::size_t n = std::min(range, triangles - first);
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(3 * n), GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(3 * first * sizeof(std::uint32_t)),
                            GLsizei(instances));
    if (limit_ > 0 && (queued_ += n * instances) >= limit_) {
      glFinish();
      queued_ = 0;
    }
  }
}

}  // namespace pbrkit::gl
