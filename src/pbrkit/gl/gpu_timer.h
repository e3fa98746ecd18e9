#pragma once
// Private to the OpenGL renderer (renderer.cpp): the GPU time of a frame, between two
// GL_TIMESTAMP queries (llvmpipe's GL_TIME_ELAPSED reports nonsense). Two pairs of queries
// are used in turn, so that a viewer can read the previous frame's time without waiting
// for the current one.
#include <array>

#include <epoxy/gl.h>

namespace pbrkit::gl {

class GpuTimer {
 public:
  /// Creates the queries; needs a current GL context for the timer's whole life.
  GpuTimer();
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  /// The frame's first timestamp, in the pair the frame before did not use.
  void begin();
  /// The frame's last timestamp.
  void end();
  /// The last frame's time in milliseconds (0 before any); waits for it.
  double last_ms() const;
  /// The newest finished frame's time: the last frame's if it is done, else the one
  /// before's.
  double latest_ms();

 private:
  std::array<GLuint, 4> timer_{};  // (begin, end) of pair 0, then of pair 1
  std::array<bool, 2> pending_{};
  int pair_ = 0;  // the pair of the last frame
  double latest_ms_ = 0.0;
};

}  // namespace pbrkit::gl
