// Animations (glTF 2.0 section 3.11): every sampler's keyframes read and checked (times
// finite and strictly increasing, values finite and as many as the keys ask), every
// channel's target checked (the node exists, is not a matrix node, and has morph targets
// when its weights are animated; a KHR_animation_pointer resolved, animation_pointer.cpp),
// before a pose trusts any of it.
#include <cmath>

#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/util/log.h"

namespace pbrkit::gltf {

namespace {

// How many morph targets a node's mesh has (0 without a mesh); primitives must agree
// (glTF 2.0 section 3.7.2.2: "All primitives MUST have the same number of morph targets").
std::size_t morph_target_count(const tinygltf::Model& model, int node) {
  const int mesh = model.nodes[std::size_t(node)].mesh;
  if (mesh < 0 || std::size_t(mesh) >= model.meshes.size()) return 0;
  const auto& prims = model.meshes[std::size_t(mesh)].primitives;
  return prims.empty() ? 0 : prims[0].targets.size();
}

}  // namespace

void Loader::read_animations() {
  weights_animated_.assign(model_.nodes.size(), 0);
  for (std::size_t ai = 0; ai < model_.animations.size(); ++ai) {
    const auto& ga = model_.animations[ai];
    const std::string apath = fmt::format("animations[{}]", ai);
    Animation anim;
    anim.name = ga.name.empty() ? fmt::format("animation{}", ai) : ga.name;
    anim.samplers.resize(ga.samplers.size());
    std::vector<AnimatedProperty> sampler_use(ga.samplers.size());
    std::vector<char> used(ga.samplers.size(), 0);
    for (std::size_t ci = 0; ci < ga.channels.size(); ++ci) {
      const auto& gc = ga.channels[ci];
      const std::string cpath = fmt::format("{}.channels[{}]", apath, ci);
      if (gc.sampler < 0 || std::size_t(gc.sampler) >= ga.samplers.size())
        error(cpath + ".sampler", fmt::format("sampler {} does not exist ({} samplers)", gc.sampler,
                                              ga.samplers.size()));
      AnimationChannel ch;
      ch.sampler = gc.sampler;
      int pointer_width = 0;
      if (const auto pointer = animation_pointers_.find({int(ai), int(ci)});
          pointer != animation_pointers_.end()) {
        // KHR_animation_pointer (animation_pointer.cpp): a node's property, or another one.
        if (!resolve_pointer(pointer->second,
                             cpath + ".target.extensions.KHR_animation_pointer.pointer", ch,
                             pointer_width))
          continue;
      } else {
        if (gc.target_node < 0) {
          // A channel without a node "SHOULD be ignored" (section 3.11, "target.node").
          warning(fmt::format("{}.target: no node; ignored", cpath));
          continue;
        }
        if (std::size_t(gc.target_node) >= model_.nodes.size())
          error(cpath + ".target.node", fmt::format("node {} does not exist ({} nodes)",
                                                    gc.target_node, model_.nodes.size()));
        ch.node = gc.target_node;
        if (gc.target_path == "translation")
          ch.property = AnimatedProperty::kTranslation;
        else if (gc.target_path == "rotation")
          ch.property = AnimatedProperty::kRotation;
        else if (gc.target_path == "scale")
          ch.property = AnimatedProperty::kScale;
        else if (gc.target_path == "weights")
          ch.property = AnimatedProperty::kWeights;
        else
          error(cpath + ".target.path", fmt::format("'{}' is not translation, rotation, scale, "
                                                    "weights or pointer",
                                                    gc.target_path));
      }
      const bool on_node = ch.property != AnimatedProperty::kPointer;
      if (on_node && model_.nodes[std::size_t(ch.node)].matrix.size() == 16 &&
          ch.property != AnimatedProperty::kWeights)
        error(cpath + ".target.node",
              fmt::format("nodes[{}] has a matrix, which animations cannot target (section "
                          "3.5.2: it MUST be given as TRS)",
                          ch.node));
      int width = 3;
      if (ch.property == AnimatedProperty::kPointer) width = pointer_width;
      if (ch.property == AnimatedProperty::kRotation) width = 4;
      if (ch.property == AnimatedProperty::kWeights) {
        width = int(morph_target_count(model_, ch.node));
        if (width == 0)
          error(cpath + ".target.node",
                fmt::format("nodes[{}]'s weights are animated, but it has no mesh with morph "
                            "targets",
                            ch.node));
        weights_animated_[std::size_t(ch.node)] = 1;
      }
      const std::size_t s = std::size_t(ch.sampler);
      if (used[s] && (anim.samplers[s].width != width || sampler_use[s] != ch.property))
        error(cpath + ".sampler",
              fmt::format("sampler {} also drives a property of another kind", ch.sampler));
      if (!used[s]) {
        used[s] = 1;
        sampler_use[s] = ch.property;
        anim.samplers[s].width = width;
      }
      anim.channels.push_back(ch);
    }
    for (std::size_t si = 0; si < ga.samplers.size(); ++si) {
      if (!used[si]) continue;  // no channel reads it
      const auto& gs = ga.samplers[si];
      const std::string spath = fmt::format("{}.samplers[{}]", apath, si);
      AnimationSampler& s = anim.samplers[si];
      if (gs.interpolation.empty() || gs.interpolation == "LINEAR")
        s.interpolation = Interpolation::kLinear;
      else if (gs.interpolation == "STEP")
        s.interpolation = Interpolation::kStep;
      else if (gs.interpolation == "CUBICSPLINE")
        s.interpolation = Interpolation::kCubicSpline;
      else
        error(spath + ".interpolation",
              fmt::format("'{}' is not LINEAR, STEP or CUBICSPLINE", gs.interpolation));
      if (gs.input < 0 || std::size_t(gs.input) >= model_.accessors.size())
        error(spath + ".input", fmt::format("accessor {} does not exist", gs.input));
      if (gs.output < 0 || std::size_t(gs.output) >= model_.accessors.size())
        error(spath + ".output", fmt::format("accessor {} does not exist", gs.output));
      // Times are FLOAT (section 3.11: "input ... MUST be float").
      s.times = read_floats(gs.input, spath + ".input", 1, false);
      if (s.times.empty()) error(spath + ".input", "has no keyframes");
      for (std::size_t k = 0; k < s.times.size(); ++k) {
        if (!std::isfinite(s.times[k]))
          error(spath + ".input",
                fmt::format("accessors[{}][{}] is not a finite time", gs.input, k));
        if (k > 0 && !(s.times[k] > s.times[k - 1]))
          error(spath + ".input",
                fmt::format("times must increase strictly (section 3.11): accessors[{}][{}] = {} "
                            "follows {}",
                            gs.input, k, s.times[k], s.times[k - 1]));
      }
      // Weights are scalars, one per target and key; the others one vector per key.
      const bool weights = sampler_use[si] == AnimatedProperty::kWeights;
      s.values = read_floats(gs.output, spath + ".output", weights ? 1 : s.width, true);
      const std::size_t per_key =
          std::size_t(s.width) * (s.interpolation == Interpolation::kCubicSpline ? 3 : 1);
      if (s.values.size() != per_key * s.times.size())
        error(spath + ".output",
              fmt::format("accessors[{}] has {} values; {} keyframes of {} need {}", gs.output,
                          s.values.size(), s.times.size(), per_key, per_key * s.times.size()));
      for (std::size_t k = 0; k < s.values.size(); ++k)
        if (!std::isfinite(s.values[k]))
          error(spath + ".output",
                fmt::format("accessors[{}] value {} is not finite", gs.output, k));
    }
    motion_.animations.push_back(std::move(anim));
  }
}

}  // namespace pbrkit::gltf
