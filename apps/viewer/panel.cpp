#include "panel.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>

#include "pbrkit/core/color.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"

namespace pbrkit::viewer {

namespace {

// The extension controls, one checkbox per extension with factors and a slider (a colour
// picker for a colour) per factor, from the material schema; true when one changed.
bool draw_extension_controls(ViewerState& s) {
  bool changed = false;
  const auto schema = material_schema();
  for (std::size_t i = 0; i < schema.size(); ++i) {
    const MaterialExtension& x = schema[i];
    ExtensionOverride& o = s.ext[i];
    if (x.factors.empty()) continue;  // KHR_materials_unlit: a shading mode, not a value
    changed |= ImGui::Checkbox(fmt::format("override {}", x.summary).c_str(), &o.on);
    if (!o.on) continue;
    float* v = o.values.data();
    for (const MaterialFactor& f : x.factors) {
      const FactorControl& c = f.control;
      if (f.components == 3)
        changed |= ImGui::ColorEdit3(f.json_name, v);
      else
        changed |= ImGui::SliderFloat(f.json_name, v, c.min, c.max, "%.3g",
                                      c.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
      v += f.components;
    }
  }
  return changed;
}

// A combo over `names`; true when the choice changed.
bool name_combo(const char* label, int& choice, const std::vector<std::string>& names) {
  const auto getter = [](void* data, int i, const char** out) {
    *out = static_cast<const std::vector<std::string>*>(data)->at(std::size_t(i)).c_str();
    return true;
  };
  return ImGui::Combo(label, &choice, getter, const_cast<std::vector<std::string>*>(&names),
                      int(names.size()));
}

// The error view's colour bar: the viridis ramp from 0 to `scale` (and above).
void draw_colour_bar(float scale) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  const int steps = 32;
  for (int i = 0; i < steps; ++i) {
    const glm::vec3 c = viridis((float(i) + 0.5f) / float(steps));
    draw->AddRectFilled(ImVec2(p.x + w * float(i) / steps, p.y),
                        ImVec2(p.x + w * float(i + 1) / steps, p.y + h),
                        ImGui::GetColorU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::Text("0%%%*s%.0f%%+", int(w / ImGui::CalcTextSize(" ").x) - 8, "", 100.0f * scale);
}

// The truth modes' part of the panel: the mode, the path tracer's progress, the error.
// Returns true when the path-traced image must restart.
bool draw_truth_panel(ViewerState& s) {
  bool changed = false;
  int mode = int(s.mode);
  const char* modes[] = {"1 raster", "2 path", "3 split", "4 difference"};
  if (ImGui::Combo("view", &mode, modes, 4)) s.mode = ViewMode(mode);
  if (s.mode == ViewMode::kRaster) {
    static const std::vector<std::string> names = gl::debug_channel_names();
    int channel = int(s.channel);
    if (name_combo("channel (C)", channel, names)) s.channel = gl::DebugChannel(channel);
    if (s.channel != gl::DebugChannel::kNone)
      ImGui::TextUnformatted("raw values: no exposure, no tone map");
    return false;
  }
  if (s.snapshot) {
    const ProgressiveSnapshot& p = *s.snapshot;
    ImGui::Text("path: %.1f / %u spp, %.1f s, noise %.4f%s", p.spp, s.options.spp, p.seconds,
                p.noise,
                p.complete  ? " (done)"
                : p.preview ? " (preview)"
                            : "");
  } else {
    ImGui::TextUnformatted("path: starting");
  }
  if (const auto error = s.path.error()) ImGui::TextWrapped("path tracer: %s", error->c_str());
  if (s.mode == ViewMode::kPath) {
    static const std::vector<std::string> names = path_channel_names();
    int channel = int(s.path_channel);
    if (name_combo("channel (C)", channel, names)) {
      s.path_channel = PathChannel(channel);
      s.path_display_dirty = true;
    }
    if (s.path_channel == PathChannel::kColor) {
      if (ImGui::Checkbox("denoise (D)", &s.denoise)) s.path_display_dirty = true;
      if (s.denoise) {
        ImGui::SameLine();
        ImGui::TextUnformatted(denoiser_name(s.denoiser_choice.kind));
        const bool shown = s.snapshot && s.denoiser.result(s.snapshot->serial);
        ImGui::TextUnformatted(shown                                ? "showing the denoised image"
                               : s.denoiser.busy()                  ? "denoising..."
                               : s.snapshot && s.snapshot->complete ? "denoise failed"
                                                                    : "denoises at the target spp");
        if (const auto& error = s.denoiser.error()) ImGui::TextWrapped("%s", error->c_str());
      }
    }
  }
  if (s.mode == ViewMode::kSplit) ImGui::SliderFloat("split", &s.split, 0.0f, 1.0f);
  if (s.mode == ViewMode::kDifference) {
    ImGui::Text("relative luminance error: mean %.1f%%, 95th pct %.1f%%", 100.0 * s.error.mean,
                100.0 * s.error.p95);
    ImGui::Text("(against a path-traced image of noise %.4f)",
                s.snapshot ? s.snapshot->noise : 0.0);
    draw_colour_bar(0.5f);
  }
  int spp = int(s.options.spp);
  if (ImGui::InputInt("target spp", &spp, 64, 1024) && spp >= 1) {
    s.options.spp = std::uint32_t(spp);
    changed = true;
  }
  // Path guiding pays where light arrives after bounces (an interior lit through a window)
  // and costs elsewhere (BENCHMARKS.md, "Path guiding"); the render restarts to learn anew.
  bool guiding = s.options.guiding == Guiding::kOn;
  if (ImGui::Checkbox("path guiding", &guiding)) {
    s.options.guiding = guiding ? Guiding::kOn : Guiding::kOff;
    changed = true;
  }
  return changed;
}

// The animation section (a scene with glTF animations): which one ("rest pose" first),
// play / pause, the time, speed and loop. It poses and uploads the scene itself and
// restarts the path view on a new pose only while paused (apply_pose).
void draw_animation_panel(ViewerState& s, gl::Renderer& renderer) {
  if (!s.scene.motion || s.scene.motion->animations.empty()) return;
  if (!ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) return;
  std::vector<std::string> names = {"rest pose"};
  const std::vector<Animation>& animations = s.scene.motion->animations;
  for (std::size_t i = 0; i < animations.size(); ++i)
    names.push_back(fmt::format("{} {} ({:.3g} to {:.3g} s)", i, animations[i].name,
                                animations[i].start(), animations[i].end()));
  Playback& p = s.playback;
  int choice = p.animation + 1;
  if (name_combo("animation", choice, names)) set_animation(s, renderer, choice - 1);
  if (p.animation < 0) return;
  if (ImGui::Button(p.playing ? "pause (space)" : "play (space)"))
    set_playing(s, renderer, !p.playing);
  ImGui::SameLine();
  ImGui::Checkbox("loop", &p.loop);
  if (ImGui::SliderFloat("time", &p.time, p.start, p.end, "%.3f s")) {
    p.time = std::clamp(p.time, p.start, p.end);  // a typed value may lie outside
    apply_pose(s, renderer);
  }
  ImGui::SliderFloat("speed", &p.speed, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
  ImGui::Text("pose + upload %.1f ms a frame", s.pose_ms);
  if (p.playing && s.mode != ViewMode::kRaster)
    ImGui::TextWrapped(
        "path view: held while playing (a restart every frame would show only previews); "
        "it restarts on the pose shown when paused");
}

}  // namespace

bool draw_panel(ViewerState& s, gl::Renderer& renderer, double cpu_ms, double gpu_ms) {
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("pbrkit view");
  ImGui::Text("frame %.1f ms (GPU %.1f ms)", cpu_ms, gpu_ms);
  ImGui::Text("%s", s.scene.source.c_str());
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
  changed |= draw_truth_panel(s);
  ImGui::Separator();
  if (!s.options.no_env &&
      ImGui::BeginCombo("environment",
                        s.env_choices[std::size_t(s.env_choice)].empty()
                            ? "default"
                            : std::filesystem::path(s.env_choices[std::size_t(s.env_choice)])
                                  .filename()
                                  .c_str())) {
    for (std::size_t i = 0; i < s.env_choices.size(); ++i) {
      const std::string label = s.env_choices[i].empty()
                                    ? "default"
                                    : std::filesystem::path(s.env_choices[i]).filename().string();
      if (ImGui::Selectable(label.c_str(), int(i) == s.env_choice) && int(i) != s.env_choice) {
        s.env_choice = int(i);
        load_environment(s, renderer);
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  changed |=
      ImGui::SliderFloat("rotation", &s.settings.env_rotation_deg, -180.0f, 180.0f, "%.0f deg");
  changed |= ImGui::SliderFloat("intensity", &s.settings.env_intensity, 0.0f, 4.0f);
  ImGui::SliderFloat("exposure", &s.display.exposure_ev, -6.0f, 6.0f, "%.1f EV");
  int tm = int(s.display.tone_mapper);
  static const std::vector<std::string> names = tone_mapper_names();
  const auto getter = [](void* data, int i, const char** out) {
    *out = static_cast<const std::vector<std::string>*>(data)->at(std::size_t(i)).c_str();
    return true;
  };
  if (ImGui::Combo("tone mapper", &tm, getter, const_cast<std::vector<std::string>*>(&names),
                   int(names.size())))
    s.display.tone_mapper = ToneMapper(tm);
  int model = int(s.settings.brdf.model);
  static const std::vector<std::string> model_names = brdf_model_names();
  if (ImGui::Combo("model", &model, getter, const_cast<std::vector<std::string>*>(&model_names),
                   int(model_names.size()))) {
    s.settings.brdf.model = BrdfModel(model);
    changed = true;
  }
  changed |= ImGui::Checkbox("multiple scattering", &s.settings.brdf.multiscatter);
  // Choice k is 2^k samples, up to what the context supports (the renderer clamps to it).
  const char* msaa_modes[] = {"off", "2x", "4x", "8x"};
  int msaa = 0, msaa_choices = 1;
  while (msaa < 3 && (2 << msaa) <= s.settings.msaa) ++msaa;
  while (msaa_choices < 4 && (1 << msaa_choices) <= s.max_samples) ++msaa_choices;
  if (ImGui::Combo("MSAA", &msaa, msaa_modes, msaa_choices)) s.settings.msaa = 1 << msaa;
  ImGui::Checkbox("image-based lighting", &s.settings.ibl);
  ImGui::Checkbox("glass shadows", &s.settings.transmissive_shadows);
  ImGui::Checkbox("opaque shadows", &s.settings.opaque_shadows);
  ImGui::Checkbox("glass reflections", &s.settings.transmissive_reflections);
  int irradiance = int(s.settings.irradiance);
  const char* irradiance_modes[] = {"SH9", "cube"};
  if (ImGui::Combo("irradiance", &irradiance, irradiance_modes, 2))
    s.settings.irradiance = gl::IrradianceMode(irradiance);
  // Every punctual light (the renderer shades them all, clustered), folded away when many.
  const std::size_t lights = s.scene.lights.size();
  if (lights > 0 && (lights <= 8 || ImGui::TreeNode("lights", "lights (%zu)", lights))) {
    for (std::size_t i = 0; i < lights; ++i) {
      bool on = s.settings.light_enabled[i];
      const std::string label = "light " + std::to_string(i) + " " + s.scene.lights[i].name;
      if (ImGui::Checkbox(label.c_str(), &on)) {
        s.settings.light_enabled[i] = on;
        changed = true;
      }
    }
    if (lights > 8) ImGui::TreePop();
  }
  // KHR_materials_variants: "none" (each primitive's own material), then the file's.
  if (!s.scene.variants.empty()) {
    std::vector<std::string> variants = {"none"};
    variants.insert(variants.end(), s.scene.variants.begin(), s.scene.variants.end());
    int choice = s.scene.active_variant + 1;
    if (name_combo("variant", choice, variants)) {
      set_variant(s, renderer, choice - 1);
      changed = true;
    }
  }
  draw_animation_panel(s, renderer);
  ImGui::Separator();
  changed |= ImGui::Checkbox("override metallic", &s.override_metallic);
  if (s.override_metallic) changed |= ImGui::SliderFloat("metallic", &s.metallic, 0.0f, 1.0f);
  changed |= ImGui::Checkbox("override roughness", &s.override_roughness);
  if (s.override_roughness) changed |= ImGui::SliderFloat("roughness", &s.roughness, 0.0f, 1.0f);
  if (draw_extension_controls(s)) {
    renderer.set_materials(overridden_materials(s));
    changed = true;
  }
  ImGui::TextUnformatted("drag: orbit, right drag: pan, wheel: zoom");
  ImGui::TextUnformatted("1-4: raster, path, split, difference");
  ImGui::TextUnformatted("C: next channel, D: denoise (path), Space: play / pause");
  ImGui::TextUnformatted("F12/P: screenshot, R: reload, Esc: quit");
  ImGui::TextUnformatted("drop a .gltf/.glb or an .hdr/.exr on the window");
  ImGui::End();
  return changed;
}

}  // namespace pbrkit::viewer
