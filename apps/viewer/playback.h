#pragma once
// The viewer's animation playback, private to the viewer: which glTF animation is shown,
// at which time, and how the time moves from one frame to the next (speed, loop). Only the
// clock: posing the scene at its time is viewer_state.h's apply_pose.
namespace pbrkit::viewer {

struct Playback {
  int animation = -1;              ///< SceneMotion::animations index; -1: the rest pose
  float start = 0.0f, end = 0.0f;  ///< the animation's first and last keyframe (seconds)
  float time = 0.0f;               ///< seconds, in [start, end]
  float speed = 1.0f;              ///< animation seconds per wall-clock second
  bool playing = false;
  bool loop = true;
};

/// Chooses `animation` (-1: the rest pose, which stops playing) spanning [start, end];
/// the time kept, clamped into the new range.
void choose_animation(Playback& p, int animation, float start, float end);

/// Starts playing; from the start again when playback had stopped at the end (or, for a
/// negative speed, at the start) without looping. The rest pose does not play.
void play(Playback& p);

/// The time `seconds` of wall clock later at `p.speed`, while playing: looping, it wraps
/// into [start, end) (an animation of no length stays at its start); not looping, it
/// stops at the end it runs into and playing turns off. True when the time changed.
bool advance(Playback& p, double seconds);

}  // namespace pbrkit::viewer
