#include "playback.h"

#include <algorithm>
#include <cmath>

namespace pbrkit::viewer {

void choose_animation(Playback& p, int animation, float start, float end) {
  p.animation = animation;
  p.start = start;
  p.end = std::max(start, end);
  p.time = std::clamp(p.time, p.start, p.end);
  if (animation < 0) p.playing = false;
}

void play(Playback& p) {
  if (p.animation < 0) return;
  if (!p.loop && p.speed > 0.0f && p.time >= p.end) p.time = p.start;
  if (!p.loop && p.speed < 0.0f && p.time <= p.start) p.time = p.end;
  p.playing = true;
}

bool advance(Playback& p, double seconds) {
  if (!p.playing || p.animation < 0) return false;
  const double duration = double(p.end) - double(p.start);
  double t = double(p.time) + seconds * double(p.speed);
  if (p.loop) {
    if (duration <= 0.0) {
      t = p.start;
    } else {
      t = std::fmod(t - p.start, duration);
      if (t < 0.0) t += duration;
      t += p.start;
    }
  } else {
    // Stopped at the end it ran into; a speed of 0 stays playing in place.
    if ((p.speed > 0.0f && t >= p.end) || (p.speed < 0.0f && t <= p.start)) p.playing = false;
    t = std::clamp(t, double(p.start), double(p.end));
  }
  const float next = float(t);
  const bool changed = next != p.time;
  p.time = next;
  return changed;
}

}  // namespace pbrkit::viewer
