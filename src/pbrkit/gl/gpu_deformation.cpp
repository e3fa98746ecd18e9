#include "pbrkit/gl/gpu_deformation.h"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "pbrkit/gl/surface_bindings.h"

namespace pbrkit::gl {

namespace {

using Word = glm::uvec4;  // deformation.glsl's uvec4, floats by their bits

Word word(glm::vec4 v) {
  return {std::bit_cast<std::uint32_t>(v.x), std::bit_cast<std::uint32_t>(v.y),
          std::bit_cast<std::uint32_t>(v.z), std::bit_cast<std::uint32_t>(v.w)};
}

// Where each part of a mesh's buffer starts, in words (deformation.glsl's layout).
struct Layout {
  std::size_t vertices = 0, influences = 0;
  std::size_t influence_offset = 0, corner_offset = 0, target_offset = 0, words = 0;
};

Layout layout(const DeformingMesh& d) {
  Layout l;
  l.vertices = d.positions.size();
  l.influences = d.skin >= 0 ? std::size_t(std::max(d.influences, 0)) : 0;
  l.influence_offset = 3 * l.vertices;
  l.corner_offset = l.influence_offset + l.vertices * ((l.influences + 1) / 2);
  l.target_offset = l.corner_offset + (d.flat_normals ? l.vertices : 0);
  l.words = std::max<std::size_t>(1, l.target_offset + 3 * l.vertices * d.targets.size());
  return l;
}

// The mesh's buffer: rest attributes, influences, corners, targets (deformation.glsl).
std::vector<Word> mesh_words(const DeformingMesh& d, const Layout& l,
                             const std::vector<std::uint32_t>& indices) {
  std::vector<Word> w(l.words, Word(0u));
  const std::size_t n = l.vertices;
  for (std::size_t v = 0; v < n; ++v) {
    w[3 * v] = word(glm::vec4(d.positions[v], 1.0f));
    if (v < d.normals.size()) w[3 * v + 1] = word(glm::vec4(d.normals[v], 0.0f));
    w[3 * v + 2] = word(v < d.tangents.size() ? d.tangents[v] : glm::vec4(0, 0, 0, 1));
  }
  const std::size_t per_vertex = (l.influences + 1) / 2;
  for (std::size_t v = 0; v < n && l.influences > 0; ++v)
    for (std::size_t c = 0; c < l.influences; ++c) {
      Word& x = w[l.influence_offset + v * per_vertex + c / 2];
      const std::size_t at = v * l.influences + c;
      x[int(2 * (c % 2))] = d.joints[at];
      x[int(2 * (c % 2) + 1)] = std::bit_cast<std::uint32_t>(d.weights[at]);
    }
  if (d.flat_normals)
    // A later triangle's corners replace an earlier one's, as deform()'s face normals do.
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
      for (int k = 0; k < 3; ++k)
        if (indices[t + std::size_t(k)] < n)
          w[l.corner_offset + indices[t + std::size_t(k)]] =
              Word(indices[t], indices[t + 1], indices[t + 2], 1u);
  for (std::size_t t = 0; t < d.targets.size(); ++t) {
    const MorphTarget& target = d.targets[t];
    const std::size_t base = l.target_offset + 3 * t * n;
    for (std::size_t v = 0; v < target.positions.size() && v < n; ++v)
      w[base + 3 * v] = word(glm::vec4(target.positions[v], 0.0f));
    for (std::size_t v = 0; v < target.normals.size() && v < n; ++v)
      w[base + 3 * v + 1] = word(glm::vec4(target.normals[v], 0.0f));
    for (std::size_t v = 0; v < target.tangents.size() && v < n; ++v)
      w[base + 3 * v + 2] = word(glm::vec4(target.tangents[v], 0.0f));
  }
  return w;
}

std::size_t joint_count(const SceneMotion& motion) {
  std::size_t count = 0;
  for (const Skin& s : motion.skins) count += s.joints.size();
  return std::max<std::size_t>(1, count);
}

std::size_t weight_count(const SceneMotion& motion) {
  std::size_t count = 0;
  for (const DeformingMesh& d : motion.deforming) count += d.targets.size();
  return std::max<std::size_t>(1, count);
}

}  // namespace

std::size_t gl_deformation_bytes(const Scene& scene) {
  if (!scene.motion || scene.motion->deforming.empty()) return 0;
  std::size_t bytes =
      sizeof(glm::mat4) * joint_count(*scene.motion) + sizeof(float) * weight_count(*scene.motion);
  for (const DeformingMesh& d : scene.motion->deforming) bytes += sizeof(Word) * layout(d).words;
  return bytes;
}

void GpuDeformation::set_scene(const Scene& scene) {
  release();
  if (!scene.motion || scene.motion->deforming.empty()) return;
  motion_ = scene.motion;
  mesh_count_ = scene.meshes.size();
  for (const DeformingMesh& d : motion_->deforming)
    flat_indices_.push_back(d.flat_normals && d.mesh >= 0 && std::size_t(d.mesh) < mesh_count_
                                ? scene.meshes[std::size_t(d.mesh)].indices
                                : std::vector<std::uint32_t>{});
}

void GpuDeformation::upload_rest() {
  const SceneMotion& motion = *motion_;
  GLint base = 0;
  for (const Skin& s : motion.skins) {
    skin_base_.push_back(base);
    base += GLint(s.joints.size());
  }
  by_mesh_.assign(mesh_count_, -1);
  GLint weight_base = 0;
  for (std::size_t i = 0; i < motion.deforming.size(); ++i) {
    const DeformingMesh& d = motion.deforming[i];
    if (d.mesh < 0 || std::size_t(d.mesh) >= mesh_count_) continue;
    const Layout l = layout(d);
    GpuDeformingMesh g;
    g.mesh = d.mesh;
    g.vertex_count = GLint(l.vertices);
    g.influences = GLint(l.influences);
    g.targets = GLint(d.targets.size());
    g.joint_base = d.skin >= 0 ? skin_base_[std::size_t(d.skin)] : -1;
    g.weight_base = weight_base;
    weight_base += g.targets;
    g.influence_offset = GLint(l.influence_offset);
    g.corner_offset = GLint(l.corner_offset);
    g.target_offset = GLint(l.target_offset);
    g.attributes = (d.normals.empty() ? 0 : 1) | (d.tangents.empty() ? 0 : 2);
    g.flat_normals = d.flat_normals;
    const std::vector<Word> words = mesh_words(d, l, flat_indices_[i]);
    glCreateBuffers(1, &g.buffer);
    glNamedBufferStorage(g.buffer, GLsizeiptr(words.size() * sizeof(Word)), words.data(), 0);
    by_mesh_[std::size_t(d.mesh)] = int(meshes_.size());
    meshes_.push_back(g);
  }
  joint_count_ = joint_count(motion);
  weight_count_ = weight_count(motion);
  glCreateBuffers(1, &joint_buffer_);
  glNamedBufferStorage(joint_buffer_, GLsizeiptr(joint_count_ * sizeof(glm::mat4)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  glCreateBuffers(1, &weight_buffer_);
  glNamedBufferStorage(weight_buffer_, GLsizeiptr(weight_count_ * sizeof(float)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
}

void GpuDeformation::pose(const std::vector<glm::mat4>& world,
                          const std::vector<std::vector<float>>& weights) {
  if (!motion_) return;
  if (!joint_buffer_) upload_rest();
  const SceneMotion& motion = *motion_;
  std::vector<glm::mat4> joints;
  joints.reserve(joint_count_);
  for (const Skin& s : motion.skins) {
    const std::vector<glm::mat4> m = joint_matrices(s, world);
    joints.insert(joints.end(), m.begin(), m.end());
  }
  joints.resize(joint_count_, glm::mat4(1.0f));
  // Each mesh's weights, one per target: deform() reads the node's first ones and takes a
  // target without a weight as weighted 0.
  std::vector<float> w(weight_count_, 0.0f);
  for (const DeformingMesh& d : motion.deforming) {
    if (d.mesh < 0 || std::size_t(d.mesh) >= by_mesh_.size() || by_mesh_[std::size_t(d.mesh)] < 0)
      continue;
    const GpuDeformingMesh& g = meshes_[std::size_t(by_mesh_[std::size_t(d.mesh)])];
    const std::vector<float>& node = weights[std::size_t(d.node)];
    for (std::size_t t = 0; t < std::size_t(g.targets) && t < node.size(); ++t)
      w[std::size_t(g.weight_base) + t] = node[t];
  }
  glNamedBufferSubData(joint_buffer_, 0, GLsizeiptr(joints.size() * sizeof(glm::mat4)),
                       joints.data());
  glNamedBufferSubData(weight_buffer_, 0, GLsizeiptr(w.size() * sizeof(float)), w.data());
  posed_ = true;
}

void GpuDeformation::release() {
  for (GpuDeformingMesh& g : meshes_) glDeleteBuffers(1, &g.buffer);
  meshes_.clear();
  by_mesh_.clear();
  skin_base_.clear();
  if (joint_buffer_) glDeleteBuffers(1, &joint_buffer_);
  if (weight_buffer_) glDeleteBuffers(1, &weight_buffer_);
  joint_buffer_ = weight_buffer_ = 0;
  joint_count_ = weight_count_ = 0;
  motion_.reset();
  mesh_count_ = 0;
  flat_indices_.clear();
  posed_ = false;
}

const GpuDeformingMesh* GpuDeformation::of_mesh(int mesh) const {
  if (!posed_ || mesh < 0 || std::size_t(mesh) >= by_mesh_.size()) return nullptr;
  const int i = by_mesh_[std::size_t(mesh)];
  return i < 0 ? nullptr : &meshes_[std::size_t(i)];
}

void GpuDeformation::bind_pose() const {
  if (!posed_) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kJointMatrixBufferBinding, joint_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMorphWeightBufferBinding, weight_buffer_);
}

void GpuDeformation::bind(const Program& p, const GpuDeformingMesh& d) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDeformVertexBufferBinding, d.buffer);
  p.set("uDeformVertexCount", d.vertex_count);
  p.set("uInfluences", d.influences);
  p.set("uMorphTargets", d.targets);
  p.set("uJointBase", d.joint_base);
  p.set("uMorphWeightBase", d.weight_base);
  p.set("uInfluenceOffset", d.influence_offset);
  p.set("uCornerOffset", d.corner_offset);
  p.set("uTargetOffset", d.target_offset);
  p.set("uDeformAttributes", d.attributes);
}

}  // namespace pbrkit::gl
