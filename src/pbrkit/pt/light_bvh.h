#pragma once
// A bounding-volume hierarchy over the lights that have a position (emissive triangles,
// point and spot lights), for choosing one light per shading point in proportion to an
// estimate of its contribution there (Conty Estevez & Kulla 2018, "Importance Sampling of
// Many Lights with Adaptive Tree Splitting"; pbrt-v4's BVHLightSampler).
//
// Each node bounds its lights' power (phi), their positions (a box) and their emission
// directions (an orientation cone: axis w, normal spread theta_o, emission spread theta_e
// beyond it). The tree is built binary (the split of least cost, as pbrt-v4's), then each
// node takes its grandchildren as its own children: up to four per node, whose importances
// one SSE vector evaluates together, so a choice among N lights passes about log4(N) nodes
// instead of log2(N) (the traversal's time is the latency of one level after the other). A
// light is chosen by one traversal from the root, going to a child with probability
// proportional to the child's importance at the shading point and rescaling the single
// random number at each step (Conty Estevez & Kulla 2018, sec. 5, with k-ary nodes in place
// of binary ones: each child's probability is its share of its siblings' importance). Each
// light keeps the path from the root to its leaf (two bits per level), so the probability of
// choosing it from a point, which multiple importance sampling needs when a BSDF-sampled
// ray hits it, retraces the same decisions.
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

  bool empty() const { return nodes_.empty() && single_ < 0; }
  /// The summed power of the lights in the tree.
  double total_power() const { return total_power_; }
  /// Chooses a light from (p, n) with u in [0, 1); returns its index and sets `pmf`, or
  /// returns -1 (no light) when the traversal reaches a node none of whose children's
  /// lights can reach p (as pbrt-v4's): the pmf over the lights then sums to less than 1,
  /// the rest being the probability of no light, which costs no shadow ray.
  std::int64_t sample(glm::vec3 p, glm::vec3 n, float u, float& pmf) const;
  /// The probability with which sample(p, n, .) returns `light` (bit-identical to the
  /// `pmf` sample() reports for it).
  float pmf(glm::vec3 p, glm::vec3 n, std::uint32_t light) const;
  /// Nodes in the tree (each of up to four children; none when it holds a single light)
  /// and the depth of its deepest light (a light that is a child of the root has depth 1).
  std::size_t node_count() const { return nodes_.size(); }
  int depth() const { return depth_; }

  /// The bounds of one light or node as importance() reads them: the bounding sphere of
  /// the box, the cone with its sine, the power.
  struct Node {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
    glm::vec3 w{0.0f, 0.0f, 1.0f};
    float phi = 0.0f;
    float cos_theta_o = 1.0f, sin_theta_o = 0.0f, cos_theta_e = 0.0f;
    bool two_sided = false;
    static Node of(const LightBounds& b);
  };
  /// light_importance() of a node.
  static float importance(const Node& node, glm::vec3 p, glm::vec3 n);

  /// A node of the tree as the traversal reads it: its (up to) four children's Nodes, one
  /// SSE lane each (structure of arrays, four cache lines). A child is a light (leaf) or
  /// another node; an unused lane has phi 0 and so importance 0.
  struct alignas(64) WideNode {
    float cx[4], cy[4], cz[4], radius[4];
    float wx[4], wy[4], wz[4], phi[4];
    float cos_theta_o[4], sin_theta_o[4], cos_theta_e[4];
    std::int32_t two_sided[4];   ///< 0 or -1 (an SSE lane mask)
    std::uint32_t child[4];      ///< the light's index (leaf) or the node's
    std::uint8_t leaf_mask = 0;  ///< bit k: child k is a light
    std::uint8_t count = 0;      ///< children in use (lanes 0..count-1)
    /// Sets lane k to `b`.
    void set(int k, const Node& b);
  };
  /// light_importance() of the children of `node`, lane k in out[k]; each lane is
  /// bit-identical to importance() of that child's Node (tested).
  static void importance4(const WideNode& node, glm::vec3 p, glm::vec3 n, float out[4]);

 private:
  struct Item {
    LightBounds bounds;
    glm::vec3 centroid;
    std::uint32_t light;
  };
  /// The binary tree of the build: node i's children are `first` and `second`, or it is a
  /// leaf holding `light`.
  struct BuildNode {
    LightBounds bounds;
    std::uint32_t first = 0, second = 0, light = 0;
    bool leaf = false;
  };
  std::uint32_t build(std::vector<BuildNode>& tree, std::vector<Item>& items, std::size_t begin,
                      std::size_t end, int depth) const;
  /// Makes the WideNode of binary interior node `b` (children: its grandchildren, or its
  /// children where those are leaves) and those below it; returns its index.
  std::uint32_t collapse(const std::vector<BuildNode>& tree, std::uint32_t b, int depth,
                         std::uint64_t trail);

  std::vector<WideNode> nodes_;  ///< nodes_[0] is the root
  /// Per light: bits 2k and 2k+1 are the child taken at depth k; lights not in the tree
  /// hold kNotInTree.
  std::vector<std::uint64_t> trails_;
  static constexpr std::uint64_t kNotInTree = ~std::uint64_t(0);
  std::int64_t single_ = -1;  ///< the light, when the tree holds exactly one (no nodes)
  double total_power_ = 0.0;
  int depth_ = 0;
};

}  // namespace pbrkit
