#include "viewer_state.h"

#include <algorithm>
#include <filesystem>
#include <thread>

#include <epoxy/gl.h>

#include "pbrkit/gl/context.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/variants.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/log.h"

namespace pbrkit::viewer {

namespace {

// The scene the path tracer renders: the panel's material overrides applied to the
// materials (metallic and roughness replace the factor and the texture's value, as the
// raster shader's overrides do) and the lights the panel turned off left out.
std::shared_ptr<const Scene> make_path_scene(const ViewerState& s) {
  auto scene = std::make_shared<Scene>(s.scene);
  scene->materials = overridden_materials(s);
  for (Material& m : scene->materials) {
    if (s.override_metallic || s.override_roughness) m.metallic_roughness_texture = {};
    if (s.override_metallic) m.metallic_factor = s.metallic;
    if (s.override_roughness) m.roughness_factor = s.roughness;
  }
  scene->lights.clear();
  for (std::size_t i = 0; i < s.scene.lights.size(); ++i)
    if (i >= s.settings.light_enabled.size() || s.settings.light_enabled[i])
      scene->lights.push_back(s.scene.lights[i]);
  return scene;
}

// The channel the path texture shows: the panel's in the path view; the split and the
// error compare colours.
PathChannel shown_path_channel(const ViewerState& s) {
  if (s.mode != ViewMode::kPath || s.snapshot->preview) return PathChannel::kColor;
  return s.path_channel;
}

}  // namespace

std::vector<ExtensionOverride> extension_overrides() {
  std::vector<ExtensionOverride> out;
  for (const MaterialExtension& x : material_schema()) {
    ExtensionOverride& o = out.emplace_back();
    for (const MaterialFactor& f : x.factors)
      o.values.insert(o.values.end(), f.components, f.control.start);
  }
  return out;
}

void init_state(ViewerState& s, const ViewerOptions& options) {
  s.options = options;
  s.settings.brdf = options.brdf;
  s.settings.background = options.background;
  s.settings.msaa = options.msaa;
  glGetIntegerv(GL_MAX_SAMPLES, &s.max_samples);
  if (s.settings.msaa <= 0) {
    const std::string gpu = gl::current_renderer();
    s.settings.msaa = gl::interactive_msaa(gpu);
    if (s.settings.msaa == 1)
      note("view: MSAA off on {}, a software rasteriser (--msaa 4 or the panel turns it on)", gpu);
  }
  s.display = options.display;
  s.env_choices.push_back(options.env);
  // The environments pbrkit ships (data/env/), offered in the panel by name order.
  std::vector<std::string> shipped;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir() / "env"))
    if (entry.path().extension() == ".exr") shipped.push_back(entry.path().string());
  std::sort(shipped.begin(), shipped.end());
  s.env_choices.insert(s.env_choices.end(), shipped.begin(), shipped.end());
  s.mode = options.mode;
  s.channel = options.channel;
  s.path_channel = options.path_channel;
  s.denoise = options.denoise;
  s.denoiser_choice = options.denoiser.choice;
  if (options.denoiser.learned) s.denoiser.use(options.denoiser);
  s.split = std::clamp(options.split, 0.0f, 1.0f);
}

std::vector<Material> overridden_materials(const ViewerState& s) {
  std::vector<Material> materials = s.scene.materials;
  const auto schema = material_schema();
  for (Material& m : materials)
    for (std::size_t i = 0; i < schema.size(); ++i) {
      const MaterialExtension& x = schema[i];
      if (!s.ext[i].on) continue;
      if (!x.present(m)) x.add(m);
      const float* v = s.ext[i].values.data();
      for (const MaterialFactor& f : x.factors) {
        std::copy(v, v + f.components, f.values(m));
        v += f.components;
      }
    }
  return materials;
}

void load_environment(ViewerState& s, gl::Renderer& renderer) {
  s.env.reset();
  if (!s.options.no_env)
    s.env = load_environment_or_default(s.env_choices[std::size_t(s.env_choice)], 0.0f, 1.0f);
  renderer.set_environment_light(
      s.env ? &*s.env : nullptr,
      gl::realtime_bake_options(s.options.bake_size, s.options.bake_samples));
}

void load_scene_into(ViewerState& s, gl::Renderer& renderer) {
  Scene scene = load_scene(s.options.scene);
  if (!s.options.variant.empty()) apply_variant(scene, find_variant(scene, s.options.variant));
  // The animation and time the options name (the command line's, or the panel's choice
  // kept for a reload), the scene posed before its first upload.
  Playback playback = s.playback;
  playback.time = s.options.animation_time;
  if (s.options.animation.empty()) {
    choose_animation(playback, -1, 0.0f, 0.0f);
  } else {
    const int index = find_animation(scene, s.options.animation);
    const Animation& a = scene.motion->animations[std::size_t(index)];
    choose_animation(playback, index, a.start(), a.end());
    pose_scene(scene, {playback.animation, playback.time});
  }
  renderer.set_scene(scene);  // a scene too large is refused here, the previous one kept
  s.scene = std::move(scene);
  s.playback = playback;
  renderer.set_materials(overridden_materials(s));  // the panel's overrides survive a reload
  s.settings.light_enabled.assign(s.scene.lights.size(), true);
  s.path_scene_dirty = true;
}

void set_variant(ViewerState& s, gl::Renderer& renderer, int variant) {
  apply_variant(s.scene, variant);
  // The meshes' material indices are in the uploaded draw runs (opaque, masked, blended):
  // the scene is uploaded again, then the panel's overrides.
  renderer.set_scene(s.scene);
  renderer.set_materials(overridden_materials(s));
  s.options.variant = variant < 0 ? "" : s.scene.variants[std::size_t(variant)];
  s.path_scene_dirty = true;
}

void apply_pose(ViewerState& s, gl::Renderer& renderer) {
  const Clock::time_point t0 = Clock::now();
  const Playback& p = s.playback;
  pose_scene(s.scene, {p.animation, p.time});
  // The GL renderer has no update of vertices or instance transforms alone: the whole
  // scene is uploaded again, textures included, each posed frame while playing. That costs
  // time in proportion to the scene's bytes (the panel shows it, pose_ms); fine for the
  // animated samples this is for (a skinned character is a few MB), not for a large
  // textured scene with one moving node.
  renderer.set_scene(s.scene);
  renderer.set_materials(overridden_materials(s));
  s.options.animation.clear();
  if (p.animation >= 0) {
    // By name when the name finds this animation again (a reload), else by index.
    const std::string& name = s.scene.motion->animations[std::size_t(p.animation)].name;
    s.options.animation = !name.empty() && find_animation(s.scene, name) == p.animation
                              ? name
                              : std::to_string(p.animation);
  }
  s.options.animation_time = p.time;
  s.path_scene_dirty = true;
  if (!p.playing) s.path_dirty = true;
  s.pose_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void set_animation(ViewerState& s, gl::Renderer& renderer, int animation) {
  if (animation < 0 || !s.scene.motion) {
    choose_animation(s.playback, -1, 0.0f, 0.0f);
  } else {
    const Animation& a = s.scene.motion->animations[std::size_t(animation)];
    s.playback.time = a.start();
    choose_animation(s.playback, animation, a.start(), a.end());
  }
  apply_pose(s, renderer);
}

void set_playing(ViewerState& s, gl::Renderer& renderer, bool playing) {
  const float time = s.playback.time;
  if (playing)
    play(s.playback);
  else
    s.playback.playing = false;
  if (s.playback.time != time) apply_pose(s, renderer);
  if (!s.playback.playing) s.path_dirty = s.path_scene_dirty = true;
}

void reset_orbit(ViewerState& s, float aspect) {
  s.orbit =
      Orbit::from_camera(select_camera(s.scene, s.options.camera, aspect), s.scene.world_bounds());
}

Camera current_camera(const ViewerState& s, int width, int height) {
  if (!s.orbit_moved) return select_view(s.scene, s.options.camera, width, height).camera;
  return s.orbit.camera();
}

void start_path(ViewerState& s, int width, int height) {
  ProgressiveJob job;
  if (!s.path_scene || s.path_scene_dirty) {
    s.path_scene = make_path_scene(s);
    s.path_scene_dirty = false;
  }
  job.scene = s.path_scene;
  if (s.env) {
    auto env = std::make_shared<Environment>(*s.env);
    env->rotation_deg = s.settings.env_rotation_deg;
    env->intensity = s.settings.env_intensity;
    job.env = std::move(env);
  }
  job.camera = current_camera(s, width, height);
  PathTracerSettings& p = job.settings;
  p.width = width;
  p.height = height;
  p.spp = s.options.spp;
  p.min_spp = 1;
  p.noise_threshold = 0.0f;
  p.seed = s.options.seed;
  p.guiding = s.options.guiding;
  p.brdf = s.settings.brdf;
  p.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
  p.checkpoint_interval = 0.1;
  s.path_job = s.path.start(std::move(job));
  s.snapshot.reset();
  s.path_dirty = false;
}

Image path_linear(const ViewerState& s) {
  const ProgressiveSnapshot& snap = *s.snapshot;
  if (s.denoise && s.mode == ViewMode::kPath && s.path_channel == PathChannel::kColor)
    if (const Image* denoised = s.denoiser.result(snap.serial)) return *denoised;
  return path_channel_image(snap, shown_path_channel(s));
}

Image path_display(const ViewerState& s) {
  return path_channel_display(path_linear(s), shown_path_channel(s), s.display);
}

DisplaySettings raster_display(const ViewerState& s) {
  if (s.channel != gl::DebugChannel::kNone) return {0.0f, ToneMapper::kNone};
  return s.display;
}

bool denoise_shown(const ViewerState& s) {
  return s.denoise && s.path_channel == PathChannel::kColor;
}

}  // namespace pbrkit::viewer
