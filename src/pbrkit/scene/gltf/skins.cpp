// Skins (glTF 2.0 section 3.7.3) and the per-vertex data of a mesh that deforms: morph
// target displacements (section 3.7.2.2) and joint influences (JOINTS_n / WEIGHTS_n),
// every index and weight checked before a pose uses it.
#include <cmath>

#include "pbrkit/scene/gltf/loader.h"

namespace pbrkit::gltf {

void Loader::read_skins() {
  for (std::size_t si = 0; si < model_.skins.size(); ++si) {
    const auto& gs = model_.skins[si];
    const std::string path = fmt::format("skins[{}]", si);
    Skin skin;
    skin.name = gs.name.empty() ? path : gs.name;
    if (gs.joints.empty()) error(path + ".joints", "is empty (section 3.7.3: at least one)");
    if (gs.joints.size() > 65535)
      error(path + ".joints", fmt::format("{} joints; at most 65535", gs.joints.size()));
    std::vector<char> seen(model_.nodes.size(), 0);
    for (std::size_t j = 0; j < gs.joints.size(); ++j) {
      const int node = gs.joints[j];
      if (node < 0 || std::size_t(node) >= model_.nodes.size())
        error(fmt::format("{}.joints[{}]", path, j),
              fmt::format("node {} does not exist ({} nodes)", node, model_.nodes.size()));
      if (seen[std::size_t(node)])
        error(fmt::format("{}.joints[{}]", path, j), fmt::format("node {} is listed twice", node));
      seen[std::size_t(node)] = 1;
      skin.joints.push_back(node);
    }
    if (gs.inverseBindMatrices >= 0) {
      const std::vector<float> m =
          read_floats(gs.inverseBindMatrices, path + ".inverseBindMatrices", 16, false);
      if (m.size() / 16 < gs.joints.size())
        error(path + ".inverseBindMatrices",
              fmt::format("accessors[{}] has {} matrices for {} joints", gs.inverseBindMatrices,
                          m.size() / 16, gs.joints.size()));
      for (std::size_t j = 0; j < gs.joints.size(); ++j) {
        glm::mat4 ibm;
        for (int e = 0; e < 16; ++e) {
          const float v = m[j * 16 + std::size_t(e)];
          if (!std::isfinite(v))
            error(path + ".inverseBindMatrices", fmt::format("matrix {} is not finite", j));
          ibm[e / 4][e % 4] = v;  // column-major, as glTF stores matrices
        }
        skin.inverse_bind.push_back(ibm);
      }
    } else {
      // "When undefined, each matrix is a 4x4 identity matrix" (section 5.28).
      skin.inverse_bind.assign(gs.joints.size(), glm::mat4(1.0f));
    }
    motion_.skins.push_back(std::move(skin));
  }
}

void Loader::read_deformation(const tinygltf::Primitive& prim,
                              const std::map<std::string, int>& attributes,
                              const std::string& where, std::size_t vertices, int skin,
                              DeformingMesh& d) {
  d.targets.resize(prim.targets.size());
  for (std::size_t t = 0; t < prim.targets.size(); ++t)
    for (const auto& target : prim.targets[t]) {
      const std::string& name = target.first;
      const std::string tw = fmt::format("{}.targets[{}].{}", where, t, name);
      std::vector<glm::vec3>* dst = name == "POSITION"  ? &d.targets[t].positions
                                    : name == "NORMAL"  ? &d.targets[t].normals
                                    : name == "TANGENT" ? &d.targets[t].tangents
                                                        : nullptr;
      if (!dst) continue;  // TEXCOORD_n / COLOR_n targets: not morphed
      const std::vector<float> f = read_floats(target.second, tw, 3, true);
      if (f.size() / 3 != vertices)
        error(tw, fmt::format("has {} elements, expected {}", f.size() / 3, vertices));
      dst->resize(vertices);
      for (std::size_t i = 0; i < vertices; ++i) {
        (*dst)[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
        if (!std::isfinite(f[3 * i] + f[3 * i + 1] + f[3 * i + 2]))
          error(tw, fmt::format("element {} is not finite", i));
      }
    }
  if (skin < 0) return;
  const std::size_t joint_count = motion_.skins[std::size_t(skin)].joints.size();
  int sets = 0;
  while (attributes.count(fmt::format("JOINTS_{}", sets))) ++sets;
  if (sets == 0)
    error(where + ".attributes",
          "the node has a skin but the primitive has no JOINTS_0 (section 3.7.3.1)");
  d.influences = 4 * sets;
  const std::size_t k = std::size_t(d.influences);
  d.joints.assign(vertices * k, 0);
  d.weights.assign(vertices * k, 0.0f);
  for (int s = 0; s < sets; ++s) {
    const std::string jn = fmt::format("JOINTS_{}", s), wn = fmt::format("WEIGHTS_{}", s);
    const std::string jw = fmt::format("{}.attributes.{}", where, jn);
    const std::string ww = fmt::format("{}.attributes.{}", where, wn);
    const auto wit = attributes.find(wn);
    if (wit == attributes.end()) error(ww, fmt::format("is missing beside {}", jn));
    const auto& ja = model_.accessors[std::size_t(attributes.at(jn))];
    if (ja.normalized || (ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                          ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
      error(jw, "must be unsigned byte or unsigned short, not normalized (section 3.7.3.1)");
    const std::vector<float> j = read_floats(attributes.at(jn), jw, 4, true);
    const std::vector<float> w = read_floats(wit->second, ww, 4, true);
    if (j.size() / 4 != vertices)
      error(jw, fmt::format("has {} elements, expected {}", j.size() / 4, vertices));
    if (w.size() / 4 != vertices)
      error(ww, fmt::format("has {} elements, expected {}", w.size() / 4, vertices));
    for (std::size_t i = 0; i < vertices; ++i)
      for (std::size_t c = 0; c < 4; ++c) {
        const float joint = j[4 * i + c], weight = w[4 * i + c];
        if (!(weight >= 0.0f) || !std::isfinite(weight))
          error(ww,
                fmt::format("vertex {} has weight {}; weights must be finite and >= 0", i, weight));
        if (!(joint >= 0.0f && joint < float(joint_count)))
          error(jw, fmt::format("vertex {} names joint {}, but the skin has {} joints", i, joint,
                                joint_count));
        d.joints[i * k + std::size_t(4 * s) + c] = std::uint16_t(joint);
        d.weights[i * k + std::size_t(4 * s) + c] = weight;
      }
  }
  // Weights are renormalised: exporters quantise them, and "the sum ... SHOULD be 1"
  // (section 3.7.3.1) leaves files whose sums are off.
  std::size_t unweighted = 0;
  for (std::size_t i = 0; i < vertices; ++i) {
    float sum = 0.0f;
    for (std::size_t c = 0; c < k; ++c) sum += d.weights[i * k + c];
    if (sum > 0.0f) {
      for (std::size_t c = 0; c < k; ++c) d.weights[i * k + c] /= sum;
    } else {
      ++unweighted;
      d.weights[i * k] = 1.0f;  // bound to its first listed joint
    }
  }
  if (unweighted > 0)
    warning(
        fmt::format("{}: {} vertices have all joint weights 0; each follows its first "
                    "listed joint",
                    where, unweighted));
}

}  // namespace pbrkit::gltf
