#pragma once
// Path guiding (PathTracerSettings::guiding): the SD-tree of Mueller, Gross & Novak 2017,
// "Practical Path Guiding for Efficient Light-Transport Simulation" (EGSR 2017). The
// incident radiance is learned while rendering, per region of space (a binary tree over the
// scene's box) and direction (in each region a quadtree over the cylindrical map
// (cos theta, phi) of the sphere): the paper's SD-tree, its section 3. The integrator samples
// directions from it, mixed with BSDF sampling by one-sample MIS, the BSDF chosen with a
// probability learned per region (below). Training is in passes of doubling sample counts (the
// paper's "binary doubling"): pass k samples with the distribution learned in pass k - 1
// and records into a copy of it whose spatial tree is refined where a region saw more than
// c sqrt(2^k) records and whose quadtrees are refined where a node holds more than rho of
// the energy.
//
// The BSDF's share of the mixture per region (Mueller 2019, "Practical Path Guiding in
// Production", section "Learning the BSDF sampling fraction", which optimises it by
// gradient descent): here each pass estimates, for every candidate share a in
// kBsdfFractions, the second moment of the one-sample estimator at the region's guided
// vertices, sum of F^2 / (p_a p_drawn) over their samples (F = f cos L, the integrand;
// p_a = a p_bsdf + (1 - a) p_guide; an unbiased estimate of the integral of F^2 / p_a
// wherever p_drawn > 0), and the next pass uses the candidate of the least. A share of 1
// turns the region's guide off: where the guide misses what BSDF sampling finds (a small
// lamp, a narrow highlight), the fixed half share gave those rare directions twice their
// BSDF weight.
//
// Determinism: the records of a pass are summed in 64-bit fixed point with integer atomics
// (the order of integer additions does not change their sum), so the guide after a pass,
// and with it the render, is the same whatever the thread count; the learned distribution
// is built from those sums in index order between passes.
//
// Private to the path tracer (tests include it through pbrkit_internal).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

/// The cylindrical map of the sphere (the paper's directional parametrisation): x = (cos theta + 1)
/// / 2, y = phi / 2 pi, with theta measured from world +Z. It preserves area: a region of the unit
/// square covers 4 pi times its area in solid angle.
glm::vec2 direction_to_square(glm::vec3 w);
glm::vec3 square_to_direction(glm::vec2 p);

/// A distribution over directions as a quadtree over the unit square: each node splits
/// its square into four quadrants (q = x + 2 y, x and y the halves, 0 low) and holds each
/// quadrant's energy; a quadrant either has a child node or is a leaf, uniform inside.
class DirectionalQuadtree {
 public:
  struct Node {
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    std::uint32_t child[4] = {0, 0, 0, 0};  ///< 0: the quadrant is a leaf (node 0 is the root)
  };

  /// One root with four empty leaves.
  DirectionalQuadtree() : nodes(1) {}

  /// The energy of the whole sphere (0: nothing learned, not to be sampled).
  float total() const {
    const Node& r = nodes[0];
    return (r.sum[0] + r.sum[1]) + (r.sum[2] + r.sum[3]);
  }
  /// A direction drawn in proportion to the energy (descend by the quadrants' energies,
  /// uniform within the leaf reached), and its pdf over solid angle. Needs total() > 0.
  glm::vec3 sample(glm::vec2 u, float& pdf) const;
  /// The pdf of sample() for `w` over solid angle (0 where the energy is 0).
  float pdf(glm::vec3 w) const;

  /// Nodes in depth-first order: a node's children come after it.
  std::vector<Node> nodes;
};

struct GuideOptions {
  /// The spatial tree splits a region that received more than c sqrt(2^k) records in pass k
  /// (the paper's c = 12000).
  double c = 12000.0;
  /// A quadrant holding more than rho of its region's energy is subdivided (the paper's rho =
  /// 0.01).
  float rho = 0.01f;
  /// The quadtrees' depth limit (the paper's 20).
  int max_depth = 20;
  /// Memory bounds: the spatial tree stops splitting at this many regions, and rho is
  /// doubled until the quadtrees of all regions together fit this many nodes.
  std::size_t max_regions = 1u << 14;
  std::size_t max_directional_nodes = 1u << 19;
  /// In (0, 1]: every region's BSDF share, fixed; negative: learned per region.
  float fixed_bsdf_fraction = -1.0f;
};

/// The SD-tree: what the integrator samples from (the distribution learned in the previous
/// pass) and what it records into (the current pass's). `record` may be called from many
/// threads at once; everything else between passes.
class PathGuide {
 public:
  PathGuide(const Bounds& bounds, const GuideOptions& options = {});

  /// The region holding `p` (points outside the box go to the nearest region).
  std::uint32_t region_at(glm::vec3 p) const;
  /// The distribution learned for `region` (total() 0 until something was learned there).
  const DirectionalQuadtree& distribution(std::uint32_t region) const {
    return regions_[region].sampling;
  }
  /// The candidate BSDF shares of the mixture; a region starts at kInitialBsdfFraction.
  static constexpr int kFractionCount = 6;
  static constexpr float kBsdfFractions[kFractionCount] = {0.2f, 0.35f, 0.5f, 0.65f, 0.8f, 1.0f};
  static constexpr float kInitialBsdfFraction = 1.0f;
  /// Guided samples a region needs in a pass before its share is chosen again.
  static constexpr std::uint64_t kMinFractionSamples = 64;
  /// The BSDF's share of the mixture at `region`'s guided vertices (1: not guided).
  float bsdf_fraction(std::uint32_t region) const { return regions_[region].bsdf_fraction; }
  /// One sample of a guided vertex of `region` for the choice of its share: the integrand
  /// `F` = f cos L (L the radiance the path found along the direction), the BSDF's and the
  /// guide's pdfs of the direction and the pdf it was drawn with. Thread-safe.
  void record_fraction(std::uint32_t region, float F, float p_bsdf, float p_guide, float p_drawn);

  /// One radiance record of this pass: the incident radiance `value` along `w` at a point
  /// of `region`, divided by the pdf with which `w` was sampled (a Monte Carlo estimate of the flux
  /// through the leaf holding `w`). Thread-safe.
  void record(std::uint32_t region, glm::vec3 w, float value);

  /// The end of a pass: what it recorded becomes the distribution to sample (a region that
  /// recorded nothing keeps its previous one), then the trees are refined for the next pass.
  void end_pass();

  /// Passes ended so far.
  int passes() const { return passes_; }
  /// The regions whose guided vertices sample from their guide in the next pass (a learned
  /// distribution and a BSDF share below 1), as of the last end_pass.
  std::size_t guided_regions() const { return guided_regions_; }
  std::size_t region_count() const { return regions_.size(); }
  /// Directional nodes of the learned distributions.
  std::size_t directional_nodes() const;
  /// Bytes held (both trees and the accumulators).
  std::size_t bytes() const;

  /// Records are summed as value * kFixedScale in 64-bit integers; a value above
  /// kMaxRecord (a firefly) is clamped to it, so that a pass of 2^24 such records in one
  /// quadrant still cannot overflow. Values below 1 / kFixedScale are lost, which changes
  /// the guide only (every sample stays unbiased).
  static constexpr double kFixedScale = 1048576.0;  // 2^20
  static constexpr float kMaxRecord = 1e6f;
  /// The second moments of the share's choice likewise: scale 2^12, each sample's term
  /// clamped to 1e8 (2^24 samples of a region in a pass stay below 2^64).
  static constexpr double kMomentScale = 4096.0;
  static constexpr float kMaxMoment = 1e8f;

 private:
  struct SpatialNode {
    int axis = -1;  ///< -1: a leaf
    float split = 0.0f;
    std::uint32_t child[2] = {0, 0};
    std::uint32_t region = 0;  ///< for a leaf
  };
  struct Region {
    DirectionalQuadtree sampling;  ///< learned in the previous pass
    /// The current pass's topology (its sums unused) and its fixed-point sums, four per node.
    DirectionalQuadtree training;
    std::vector<std::uint64_t> flux;
    std::uint64_t records = 0;
    glm::vec3 lo{0.0f}, hi{0.0f};                ///< the region's box
    float bsdf_fraction = kInitialBsdfFraction;  ///< chosen from the previous pass
    std::uint64_t moments[kFractionCount] = {};  ///< this pass's, fixed point
    std::uint64_t fraction_samples = 0;
  };
  void split(std::uint32_t node, double records, double threshold);
  void rebuild_topologies();

  GuideOptions options_;
  std::vector<SpatialNode> nodes_;
  std::vector<Region> regions_;
  int passes_ = 0;
  std::size_t guided_regions_ = 0;
};

/// A quadtree over the same square whose quadrants are subdivided while they hold more than
/// `rho` of `source`'s energy (uniform within `source`'s leaves), to `max_depth` levels: the
/// topology the next pass records into. Public for the tests.
DirectionalQuadtree refine_topology(const DirectionalQuadtree& source, float rho, int max_depth);

}  // namespace pbrkit
