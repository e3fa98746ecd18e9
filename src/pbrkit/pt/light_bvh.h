#pragma once
// A bounding-volume hierarchy over the lights that have a position (emissive triangles,
// point and spot lights), for choosing one light per shading point in proportion to an
// estimate of its contribution there (Conty Estevez & Kulla 2018, "Importance Sampling of
// Many Lights with Adaptive Tree Splitting"; pbrt-v4's BVHLightSampler).
//
// Each node bounds its lights' power (phi), their positions (a box) and their emission
// directions (an orientation cone: axis w, normal spread theta_o, emission spread theta_e
// beyond it). A light is chosen by one traversal from the root, going to either child with
// probability proportional to the child's importance at the shading point and rescaling the
// single random number at each step. Each light keeps the path from the root to its leaf (a
// bit trail), so the probability of choosing it from a point, which multiple importance
// sampling needs when a BSDF-sampled ray hits it, retraces the same decisions.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit {

/// What a light (or a node, for all its lights) is bounded by.
struct LightBounds {
  glm::vec3 lo{0.0f}, hi{0.0f};   ///< box of the emitting points
  glm::vec3 w{0.0f, 0.0f, 1.0f};  ///< orientation cone axis (unit)
  float phi = 0.0f;               ///< emitted power (any consistent unit); 0: never chosen
  float cos_theta_o = 1.0f;       ///< normals lie within theta_o of w
  float cos_theta_e = 0.0f;       ///< emission reaches theta_e beyond a normal
  bool two_sided = false;         ///< emits along -normal too

  /// The box, cone and power of both (the cone union of pbrt-v4's DirectionCone).
  static LightBounds merge(const LightBounds& a, const LightBounds& b);
};

/// An upper-bound estimate of the contribution of the lights bounded by `b` at point `p`
/// whose surface normal is `n` (zero for a point without a surface: the cosine at the
/// receiver is then left out): phi cos(theta') cos(theta_i') / d^2, where theta' and
/// theta_i' are the smallest angles the box allows at the emitter and at the receiver
/// (Conty Estevez & Kulla 2018, eq. 3; pbrt-v4 LightBounds::Importance). Zero only where
/// no light in `b` can reach `p`. Both sides of the receiver count (|n.wi|), so that a
/// transmissive surface's far side is covered.
float light_importance(const LightBounds& b, glm::vec3 p, glm::vec3 n);

class LightBvh {
 public:
  LightBvh() = default;
  /// `lights[i]` is light i's bounds; lights with phi <= 0 (or not finite) are left out
  /// and have probability 0.
  explicit LightBvh(const std::vector<LightBounds>& lights);

  bool empty() const { return nodes_.empty(); }
  /// The summed power of the lights in the tree.
  double total_power() const { return total_power_; }
  /// Chooses a light from (p, n) with u in [0, 1); returns its index and sets `pmf`, or
  /// returns -1 (no light) when the traversal reaches a node neither of whose children's
  /// lights can reach p (as pbrt-v4's): the pmf over the lights then sums to less than 1,
  /// the rest being the probability of no light, which costs no shadow ray.
  std::int64_t sample(glm::vec3 p, glm::vec3 n, float u, float& pmf) const;
  /// The probability with which sample(p, n, .) returns `light` (bit-identical to the
  /// `pmf` sample() reports for it).
  float pmf(glm::vec3 p, glm::vec3 n, std::uint32_t light) const;
  /// Nodes in the tree and the depth of its deepest leaf (the root has depth 0).
  std::size_t node_count() const { return nodes_.size(); }
  int depth() const { return depth_; }

  /// A node as traversal reads it (one cache line): the bounding sphere of the box, the
  /// cone with its sine, the power. Interior nodes have their first child right after them
  /// and the second at `index`; leaves hold their light's index.
  struct alignas(64) Node {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
    glm::vec3 w{0.0f, 0.0f, 1.0f};
    float phi = 0.0f;
    float cos_theta_o = 1.0f, sin_theta_o = 0.0f, cos_theta_e = 0.0f;
    std::uint32_t index = 0;
    bool two_sided = false;
    bool leaf = false;
    static Node of(const LightBounds& b);
  };
  /// light_importance() of a node.
  static float importance(const Node& node, glm::vec3 p, glm::vec3 n);

 private:
  struct Item {
    LightBounds bounds;
    glm::vec3 centroid;
    std::uint32_t light;
  };
  void build(std::vector<Item>& items, std::size_t begin, std::size_t end, int depth,
             std::uint64_t trail);

  std::vector<Node> nodes_;
  /// Per light: bit k is the branch taken at depth k (0 first child, 1 second); lights
  /// not in the tree hold kNotInTree.
  std::vector<std::uint64_t> trails_;
  static constexpr std::uint64_t kNotInTree = ~std::uint64_t(0);
  double total_power_ = 0.0;
  int depth_ = 0;
};

}  // namespace pbrkit
