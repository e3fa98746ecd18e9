#include "pbrkit/gl/gpu_timer.h"

#include <cstddef>

namespace pbrkit::gl {

namespace {

double timer_pair_ms(const std::array<GLuint, 4>& timer, int pair) {
  GLuint64 begin = 0, end = 0;
  glGetQueryObjectui64v(timer[std::size_t(2 * pair)], GL_QUERY_RESULT, &begin);
  glGetQueryObjectui64v(timer[std::size_t(2 * pair + 1)], GL_QUERY_RESULT, &end);
  return end > begin ? double(end - begin) * 1e-6 : 0.0;
}

}  // namespace

GpuTimer::GpuTimer() {
  glCreateQueries(GL_TIMESTAMP, 4, timer_.data());
}

GpuTimer::~GpuTimer() {
  glDeleteQueries(4, timer_.data());
}

void GpuTimer::begin() {
  pair_ = 1 - pair_;
  glQueryCounter(timer_[std::size_t(2 * pair_)], GL_TIMESTAMP);
}

void GpuTimer::end() {
  glQueryCounter(timer_[std::size_t(2 * pair_ + 1)], GL_TIMESTAMP);
  pending_[std::size_t(pair_)] = true;
}

double GpuTimer::last_ms() const {
  if (!pending_[std::size_t(pair_)]) return 0.0;
  return timer_pair_ms(timer_, pair_);
}

double GpuTimer::latest_ms() {
  // The last frame's pair if it is done, else the frame before's (done long ago on any
  // GPU; reading it may wait only when it is not).
  for (int pair : {pair_, 1 - pair_}) {
    if (!pending_[std::size_t(pair)]) continue;
    GLint available = 0;
    glGetQueryObjectiv(timer_[std::size_t(2 * pair + 1)], GL_QUERY_RESULT_AVAILABLE, &available);
    if (available || pair != pair_) {
      latest_ms_ = timer_pair_ms(timer_, pair);
      break;
    }
  }
  return latest_ms_;
}

}  // namespace pbrkit::gl
