// Path guiding's SD-tree (guiding.h; Mueller, Gross & Novak 2017).
#include "pbrkit/pt/guiding.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

// The quadrant of `p` in its node's square, and `p` in that quadrant's own unit square.
inline int descend(glm::vec2& p) {
  const int qx = p.x >= 0.5f ? 1 : 0, qy = p.y >= 0.5f ? 1 : 0;
  p = glm::min(glm::vec2(p.x * 2.0f - float(qx), p.y * 2.0f - float(qy)),
               glm::vec2(kOneMinusEpsilon));
  return qx + 2 * qy;
}

// The learned distribution of a pass: the topology it recorded into with each leaf's
// fixed-point sum, summed up to the root in index order (children after their parent).
DirectionalQuadtree finalize(const DirectionalQuadtree& topology,
                             const std::vector<std::uint64_t>& flux) {
  DirectionalQuadtree d = topology;
  for (std::size_t n = d.nodes.size(); n-- > 0;) {
    DirectionalQuadtree::Node& node = d.nodes[n];
    for (int q = 0; q < 4; ++q) {
      if (const std::uint32_t c = node.child[q]) {
        const DirectionalQuadtree::Node& child = d.nodes[c];
        node.sum[q] = (child.sum[0] + child.sum[1]) + (child.sum[2] + child.sum[3]);
      } else {
        node.sum[q] = float(double(flux[4 * n + std::size_t(q)]) / PathGuide::kFixedScale);
      }
    }
  }
  return d;
}

void refine(DirectionalQuadtree& out, std::uint32_t out_node, const DirectionalQuadtree& src,
            int src_node, float energy, int depth, float limit, int max_depth) {
  for (int q = 0; q < 4; ++q) {
    float e = energy * 0.25f;  // inside one of src's leaves: uniform
    int sq = -1;
    if (src_node >= 0) {
      const DirectionalQuadtree::Node& s = src.nodes[std::size_t(src_node)];
      e = s.sum[q];
      if (s.child[q]) sq = int(s.child[q]);
    }
    if (e > limit && depth < max_depth) {
      const auto c = std::uint32_t(out.nodes.size());
      out.nodes.emplace_back();
      out.nodes[out_node].child[q] = c;
      refine(out, c, src, sq, e, depth + 1, limit, max_depth);
    }
  }
}

}  // namespace

Guiding parse_guiding(std::string_view name) {
  if (name == "off") return Guiding::kOff;
  if (name == "on") return Guiding::kOn;
  fail("unknown guiding '{}' (expected 'off' or 'on')", name);
}

std::string_view guiding_name(Guiding guiding) {
  return guiding == Guiding::kOn ? "on" : "off";
}

glm::vec2 direction_to_square(glm::vec3 w) {
  const float x = 0.5f * (std::clamp(w.z, -1.0f, 1.0f) + 1.0f);
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return glm::min(glm::vec2(x, phi * kInv2Pi), glm::vec2(kOneMinusEpsilon));
}

glm::vec3 square_to_direction(glm::vec2 p) {
  const float cos_theta = 2.0f * p.x - 1.0f;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * p.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

glm::vec3 DirectionalQuadtree::sample(glm::vec2 u, float& pdf) const {
  // Each level chooses a column by its energy with u.x, then a quadrant within the column
  // with u.y, and rescales the number used to [0, 1) for the next level (one 2D number
  // descends the whole tree); the pdf over the square is the product of 4 x each choice's
  // share of its node's energy.
  float density = 1.0f;
  glm::vec2 origin(0.0f);
  float size = 1.0f;
  std::uint32_t n = 0;
  for (;;) {
    const Node& node = nodes[n];
    const float total = (node.sum[0] + node.sum[1]) + (node.sum[2] + node.sum[3]);
    const float left = node.sum[0] + node.sum[2];
    const float p_left = left / total;
    int qx;
    if (u.x < p_left) {
      qx = 0;
      u.x = u.x / p_left;
    } else {
      qx = 1;
      u.x = (u.x - p_left) / (1.0f - p_left);
    }
    const float column = qx ? node.sum[1] + node.sum[3] : left;
    const float p_low = node.sum[qx] / column;
    int qy;
    if (u.y < p_low) {
      qy = 0;
      u.y = u.y / p_low;
    } else {
      qy = 1;
      u.y = (u.y - p_low) / (1.0f - p_low);
    }
    u = glm::clamp(u, glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon));
    const int q = qx + 2 * qy;
    density *= 4.0f * node.sum[q] / total;
    size *= 0.5f;
    origin += glm::vec2(float(qx), float(qy)) * size;
    if (!node.child[q]) break;
    n = node.child[q];
  }
  pdf = density * kInv4Pi;
  return square_to_direction(origin + u * size);
}

float DirectionalQuadtree::pdf(glm::vec3 w) const {
  glm::vec2 p = direction_to_square(w);
  float density = 1.0f;
  std::uint32_t n = 0;
  for (;;) {
    const Node& node = nodes[n];
    const float total = (node.sum[0] + node.sum[1]) + (node.sum[2] + node.sum[3]);
    if (!(total > 0.0f)) return 0.0f;
    const int q = descend(p);
    density *= 4.0f * node.sum[q] / total;
    if (!node.child[q]) break;
    n = node.child[q];
  }
  return density * kInv4Pi;
}

DirectionalQuadtree refine_topology(const DirectionalQuadtree& source, float rho, int max_depth) {
  DirectionalQuadtree out;
  const float total = source.total();
  if (total > 0.0f) refine(out, 0, source, 0, total, 1, rho * total, max_depth);
  return out;
}

PathGuide::PathGuide(const Bounds& bounds, const GuideOptions& options) : options_(options) {
  // A share of 0 would leave directions the guide has not learned unsampled: biased.
  if (!(options.fixed_bsdf_fraction <= 1.0f) || options.fixed_bsdf_fraction == 0.0f)
    throw Error("path guiding: the BSDF share " + std::to_string(options.fixed_bsdf_fraction) +
                " is not in (0, 1] (0 would leave what the guide has not learned unsampled; "
                "negative: learned per region)");
  Region root;
  if (bounds.empty()) {
    root.lo = glm::vec3(-1.0f);
    root.hi = glm::vec3(1.0f);
  } else {
    // A little larger than the scene, so that points on its faces are inside.
    const glm::vec3 pad = 1e-3f * glm::max(bounds.extent(), glm::vec3(1e-3f));
    root.lo = bounds.min - pad;
    root.hi = bounds.max + pad;
  }
  if (options_.fixed_bsdf_fraction >= 0.0f) root.bsdf_fraction = options_.fixed_bsdf_fraction;
  regions_.push_back(std::move(root));
  nodes_.emplace_back();
  rebuild_topologies();
}

std::uint32_t PathGuide::region_at(glm::vec3 p) const {
  std::uint32_t n = 0;
  while (nodes_[n].axis >= 0) {
    const SpatialNode& node = nodes_[n];
    n = node.child[p[node.axis] >= node.split ? 1 : 0];
  }
  return nodes_[n].region;
}

void PathGuide::record(std::uint32_t region, glm::vec3 w, float value) {
  if (!(value >= 0.0f)) return;  // NaN: the path's own bug, counted by the render
  Region& r = regions_[region];
  std::atomic_ref<std::uint64_t>(r.records).fetch_add(1, std::memory_order_relaxed);
  const auto fixed = std::uint64_t(double(std::min(value, kMaxRecord)) * kFixedScale + 0.5);
  if (fixed == 0) return;
  glm::vec2 p = direction_to_square(w);
  std::uint32_t n = 0;
  for (;;) {
    const int q = descend(p);
    const std::uint32_t c = r.training.nodes[n].child[q];
    if (!c) {
      std::atomic_ref<std::uint64_t>(r.flux[4 * std::size_t(n) + std::size_t(q)])
          .fetch_add(fixed, std::memory_order_relaxed);
      return;
    }
    n = c;
  }
}

void PathGuide::record_fraction(std::uint32_t region, float F, float p_bsdf, float p_guide,
                                float p_drawn) {
  if (!(F >= 0.0f) || !(p_drawn > 0.0f)) return;
  Region& r = regions_[region];
  std::atomic_ref<std::uint64_t>(r.fraction_samples).fetch_add(1, std::memory_order_relaxed);
  if (F == 0.0f) return;  // adds 0 to every candidate's moment
  for (int k = 0; k < kFractionCount; ++k) {
    const float a = kBsdfFractions[k];
    const float p = a * p_bsdf + (1.0f - a) * p_guide;
    // A candidate that could not have drawn a direction the integrand needs has an
    // infinite second moment: the largest term.
    const float term = p > 0.0f ? std::min(F / p * (F / p_drawn), kMaxMoment) : kMaxMoment;
    const auto fixed = std::uint64_t(double(term) * kMomentScale + 0.5);
    if (fixed)
      std::atomic_ref<std::uint64_t>(r.moments[k]).fetch_add(fixed, std::memory_order_relaxed);
  }
}

void PathGuide::end_pass() {
  const int k = passes_++;
  std::vector<double> records(regions_.size());
  for (std::size_t i = 0; i < regions_.size(); ++i) {
    Region& r = regions_[i];
    records[i] = double(r.records);
    // The share of the least estimated second moment (of equal ones the smaller); a region
    // with too few samples, or whose samples found no light, keeps its share.
    if (options_.fixed_bsdf_fraction < 0.0f && r.fraction_samples >= kMinFractionSamples) {
      int best = 0;
      for (int c = 1; c < kFractionCount; ++c)
        if (r.moments[c] < r.moments[best]) best = c;
      if (r.moments[best] > 0) r.bsdf_fraction = kBsdfFractions[best];
    }
    // A region that recorded nothing this pass keeps what it learned before.
    DirectionalQuadtree learned = finalize(r.training, r.flux);
    if (learned.total() > 0.0f) r.sampling = std::move(learned);
  }
  // The spatial tree: a region that saw more than c sqrt(2^k) records is split, its
  // records assumed halved by each split (the children inherit the parent's distribution).
  const double threshold = options_.c * std::sqrt(std::ldexp(1.0, k));
  const std::size_t node_count = nodes_.size();
  for (std::size_t n = 0; n < node_count; ++n)
    if (nodes_[n].axis < 0) split(std::uint32_t(n), records[nodes_[n].region], threshold);
  rebuild_topologies();
  guided_regions_ =
      std::size_t(std::count_if(regions_.begin(), regions_.end(), [](const Region& r) {
        return r.bsdf_fraction < 1.0f && r.sampling.total() > 0.0f;
      }));
}

void PathGuide::split(std::uint32_t node, double records, double threshold) {
  if (records <= threshold || regions_.size() >= options_.max_regions) return;
  const std::uint32_t region = nodes_[node].region;
  // Halve the region's box across its longest side.
  const glm::vec3 lo = regions_[region].lo, hi = regions_[region].hi, e = hi - lo;
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const float mid = 0.5f * (lo[axis] + hi[axis]);
  Region upper;
  upper.sampling = regions_[region].sampling;
  upper.bsdf_fraction = regions_[region].bsdf_fraction;
  upper.lo = lo;
  upper.hi = hi;
  upper.lo[axis] = mid;
  regions_[region].hi[axis] = mid;
  const auto upper_region = std::uint32_t(regions_.size());
  regions_.push_back(std::move(upper));
  const auto c0 = std::uint32_t(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  nodes_[c0].region = region;
  nodes_[c0 + 1].region = upper_region;
  SpatialNode& parent = nodes_[node];
  parent.axis = axis;
  parent.split = mid;
  parent.child[0] = c0;
  parent.child[1] = c0 + 1;
  split(c0, records * 0.5, threshold);
  split(c0 + 1, records * 0.5, threshold);
}

void PathGuide::rebuild_topologies() {
  // rho doubled until the quadtrees fit their bound (the same choice on every run: it
  // depends on the learned distributions only).
  for (float rho = options_.rho;; rho *= 2.0f) {
    std::size_t total = 0;
    for (Region& r : regions_) {
      r.training = refine_topology(r.sampling, rho, options_.max_depth);
      total += r.training.nodes.size();
    }
    if (total <= options_.max_directional_nodes || rho >= 1.0f) break;
  }
  for (Region& r : regions_) {
    r.flux.assign(4 * r.training.nodes.size(), 0);
    r.records = 0;
    std::fill(std::begin(r.moments), std::end(r.moments), std::uint64_t(0));
    r.fraction_samples = 0;
  }
}

std::size_t PathGuide::directional_nodes() const {
  std::size_t n = 0;
  for (const Region& r : regions_) n += r.sampling.nodes.size();
  return n;
}

std::size_t PathGuide::bytes() const {
  std::size_t b = nodes_.capacity() * sizeof(SpatialNode) + regions_.capacity() * sizeof(Region);
  for (const Region& r : regions_)
    b += (r.sampling.nodes.capacity() + r.training.nodes.capacity()) *
             sizeof(DirectionalQuadtree::Node) +
         r.flux.capacity() * sizeof(std::uint64_t);
  return b;
}

}  // namespace pbrkit
