#include "pbrkit/pt/light_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pbrkit/core/math.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

namespace {

// Importance is clamped to this, so that the sum of two children stays finite (a point
// light at the shading point itself, a huge power).
constexpr float kMaxImportance = 1e30f;
// The squared distance is at least this (a point light at the shading point).
constexpr float kMinDistance2 = 1e-12f;

// The angle between unit vectors, accurate near 0 and pi (pbrt-v4 AngleBetween).
float angle_between(glm::vec3 a, glm::vec3 b) {
  if (glm::dot(a, b) < 0.0f) return kPi - 2.0f * std::asin(std::min(glm::length(a + b) / 2, 1.0f));
  return 2.0f * std::asin(std::min(glm::length(b - a) / 2, 1.0f));
}

float safe_acos(float x) {
  return std::acos(std::clamp(x, -1.0f, 1.0f));
}

// The orientation measure of a cone (Conty Estevez & Kulla 2018, eq. 1; pbrt-v4
// BVHLightSampler::EvaluateCost): the solid angle of the normals' cone plus the cosine-
// weighted spread of the emission beyond it.
double orientation_measure(const LightBounds& b) {
  const double theta_o = safe_acos(b.cos_theta_o), theta_e = safe_acos(b.cos_theta_e);
  const double theta_w = std::min(theta_o + theta_e, double(kPi));
  const double sin_o = std::sqrt(std::max(0.0, 1.0 - double(b.cos_theta_o) * b.cos_theta_o));
  return 2.0 * kPi * (1.0 - b.cos_theta_o) +
         kPi / 2.0 *
             (2.0 * theta_w * sin_o - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * sin_o +
              b.cos_theta_o);
}

double surface_area(const LightBounds& b) {
  const glm::dvec3 d = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The cost of a node holding `b` split along `axis` of a parent box whose extent is
// `extent` (Conty Estevez & Kulla 2018, eq. 2: power x orientation measure x surface
// area, with the regularisation K_r = longest extent / extent along the axis, which keeps
// thin boxes from being cut across).
double split_cost(const LightBounds& b, glm::vec3 extent, int axis) {
  const double kr = double(std::max(extent.x, std::max(extent.y, extent.z))) / extent[axis];
  return double(b.phi) * orientation_measure(b) * kr * surface_area(b);
}

}  // namespace

LightBounds LightBounds::merge(const LightBounds& a, const LightBounds& b) {
  if (!(a.phi > 0.0f)) return b;
  if (!(b.phi > 0.0f)) return a;
  LightBounds r;
  r.lo = glm::min(a.lo, b.lo);
  r.hi = glm::max(a.hi, b.hi);
  r.phi = a.phi + b.phi;
  r.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  r.two_sided = a.two_sided || b.two_sided;
  // The smallest cone holding both normal cones (pbrt-v4 Union(DirectionCone, ...)).
  const float theta_a = safe_acos(a.cos_theta_o), theta_b = safe_acos(b.cos_theta_o);
  const float theta_d = angle_between(a.w, b.w);
  if (std::min(theta_d + theta_b, kPi) <= theta_a) {
    r.w = a.w;
    r.cos_theta_o = a.cos_theta_o;
    return r;
  }
  if (std::min(theta_d + theta_a, kPi) <= theta_b) {
    r.w = b.w;
    r.cos_theta_o = b.cos_theta_o;
    return r;
  }
  // Widened by a little, so that float rounding of the rotated axis cannot leave a normal
  // just outside (the importance would then be 0 where a light contributes).
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b) + 1e-4f;
  const glm::vec3 axis = glm::cross(a.w, b.w);
  const float axis_len = glm::length(axis);
  if (theta_o >= kPi || !(axis_len > 0.0f)) {
    r.w = a.w;
    r.cos_theta_o = -1.0f;
    return r;
  }
  // a.w turned by theta_o - theta_a towards b.w about their common normal (Rodrigues;
  // the axis is perpendicular to a.w).
  const glm::vec3 k = axis / axis_len;
  const float theta_r = theta_o - theta_a;
  r.w = glm::normalize(a.w * std::cos(theta_r) + glm::cross(k, a.w) * std::sin(theta_r));
  r.cos_theta_o = std::cos(theta_o);
  return r;
}

LightBvh::Node LightBvh::Node::of(const LightBounds& b) {
  Node node;
  node.center = 0.5f * (b.lo + b.hi);
  const glm::vec3 diag = b.hi - b.lo;
  node.radius = 0.5f * std::sqrt(glm::dot(diag, diag));
  node.w = b.w;
  node.phi = b.phi;
  node.cos_theta_o = b.cos_theta_o;
  node.sin_theta_o = safe_sqrt(1.0f - b.cos_theta_o * b.cos_theta_o);
  node.cos_theta_e = b.cos_theta_e;
  node.two_sided = b.two_sided;
  return node;
}

// Every sine and cosine is a square root of a difference of squares times 1 / |d|, so the
// square roots do not wait on one another (the traversal is bound by this function's
// latency, one node after the other); the clamps of pbrt-v4's cosSubClamped are selects.
float LightBvh::importance(const Node& b, glm::vec3 p, glm::vec3 n) {
  const glm::vec3 d = p - b.center;  // from the lights towards p
  const float d2 = glm::dot(d, d);
  const float r2 = b.radius * b.radius;  // bounding sphere
  // Inside the bounding sphere every direction is possible: the angular factors are 1, and
  // the distance is clamped to the sphere's radius.
  if (d2 <= r2) return std::min(b.phi / std::max(r2, kMinDistance2), kMaxImportance);
  const float inv_d = 1.0f / std::sqrt(std::max(d2, kMinDistance2));
  // theta_b: half the angle the bounding sphere subtends at p.
  const float sin_b = std::min(b.radius * inv_d, 1.0f);
  const float cos_b = std::sqrt(d2 - r2) * inv_d;
  // theta_w: between the cone axis and wi = d / |d|; theta' = max(0, theta_w - theta_o -
  // theta_b), the smallest angle between a normal in the cone and a direction towards p.
  float dw = glm::dot(b.w, d);
  if (b.two_sided) dw = std::fabs(dw);
  const float cos_w = dw * inv_d;
  const float sin_w = std::sqrt(std::max(d2 - dw * dw, 0.0f)) * inv_d;
  const bool in_cone = cos_w > b.cos_theta_o;
  const float cos_x = in_cone ? 1.0f : cos_w * b.cos_theta_o + sin_w * b.sin_theta_o;
  const float sin_x = in_cone ? 0.0f : sin_w * b.cos_theta_o - cos_w * b.sin_theta_o;
  const float cos_p = cos_x > cos_b ? 1.0f : cos_x * cos_b + sin_x * sin_b;
  // Beyond the emission spread nothing reaches p. (Strictly beyond: a spot light, whose
  // spread is 0, reaches the points inside its cone, where theta' = 0.)
  if (cos_p < b.cos_theta_e) return 0.0f;
  float result = b.phi * cos_p * (inv_d * inv_d);
  if (n != glm::vec3(0.0f)) {
    // The receiver's cosine at the smallest angle theta_i - theta_b.
    const float dn = std::fabs(glm::dot(d, n));
    const float cos_i = dn * inv_d;
    const float sin_i = std::sqrt(std::max(d2 - dn * dn, 0.0f)) * inv_d;
    result *= cos_i > cos_b ? 1.0f : cos_i * cos_b + sin_i * sin_b;
  }
  return std::min(std::max(result, 0.0f), kMaxImportance);
}

namespace {

#if defined(__SSE2__)
inline __m128 select(__m128 mask, __m128 if_true, __m128 if_false) {
  return _mm_or_ps(_mm_and_ps(mask, if_true), _mm_andnot_ps(mask, if_false));
}
#endif

}  // namespace

void LightBvh::WideNode::set(int k, const Node& b) {
  cx[k] = b.center.x;
  cy[k] = b.center.y;
  cz[k] = b.center.z;
  radius[k] = b.radius;
  wx[k] = b.w.x;
  wy[k] = b.w.y;
  wz[k] = b.w.z;
  phi[k] = b.phi;
  cos_theta_o[k] = b.cos_theta_o;
  sin_theta_o[k] = b.sin_theta_o;
  cos_theta_e[k] = b.cos_theta_e;
  two_sided[k] = b.two_sided ? -1 : 0;
}

namespace {

#if defined(__SSE2__)
// importance() of a node's four children at once, one per SSE lane: the traversal
// evaluates every child of every node it passes, and its time goes to the four square
// roots and the division of each evaluation, which the vector units do for four lanes at
// the cost of one. The same operations in the same order as the scalar function (the build
// does not contract a * b + c), and SSE's min/max/compare/sqrt are IEEE's, so each lane is
// bit-identical to importance() of its child. Always inlined, as are its callers: out of
// line, a call clobbers every vector register and the traversal's live values are spilled
// around it at each level.
[[gnu::always_inline]] inline void children_importance(const LightBvh::WideNode& b, glm::vec3 p,
                                                       glm::vec3 n, float out[4]) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 max_importance = _mm_set1_ps(kMaxImportance);
  const __m128 min_distance2 = _mm_set1_ps(kMinDistance2);
  const __m128 dx = _mm_sub_ps(_mm_set1_ps(p.x), _mm_load_ps(b.cx));
  const __m128 dy = _mm_sub_ps(_mm_set1_ps(p.y), _mm_load_ps(b.cy));
  const __m128 dz = _mm_sub_ps(_mm_set1_ps(p.z), _mm_load_ps(b.cz));
  const __m128 d2 =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
  const __m128 radius = _mm_load_ps(b.radius);
  const __m128 r2 = _mm_mul_ps(radius, radius);
  const __m128 phi = _mm_load_ps(b.phi);
  const __m128 inside = _mm_cmple_ps(d2, r2);
  const __m128 inside_result =
      _mm_min_ps(max_importance, _mm_div_ps(phi, _mm_max_ps(min_distance2, r2)));
  const __m128 inv_d = _mm_div_ps(one, _mm_sqrt_ps(_mm_max_ps(min_distance2, d2)));
  const __m128 sin_b = _mm_min_ps(one, _mm_mul_ps(radius, inv_d));
  // (Inside the sphere d2 - r2 < 0: that lane's result is inside_result.)
  const __m128 cos_b = _mm_mul_ps(_mm_sqrt_ps(_mm_max_ps(zero, _mm_sub_ps(d2, r2))), inv_d);
  const __m128 sign = _mm_set1_ps(-0.0f);
  __m128 dw =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(b.wx), dx), _mm_mul_ps(_mm_load_ps(b.wy), dy)),
                 _mm_mul_ps(_mm_load_ps(b.wz), dz));
  const __m128 two_sided =
      _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(b.two_sided)));
  dw = select(two_sided, _mm_andnot_ps(sign, dw), dw);
  const __m128 cos_w = _mm_mul_ps(dw, inv_d);
  const __m128 sin_w =
      _mm_mul_ps(_mm_sqrt_ps(_mm_max_ps(zero, _mm_sub_ps(d2, _mm_mul_ps(dw, dw)))), inv_d);
  const __m128 cos_o = _mm_load_ps(b.cos_theta_o);
  const __m128 sin_o = _mm_load_ps(b.sin_theta_o);
  const __m128 in_cone = _mm_cmpgt_ps(cos_w, cos_o);
  const __m128 cos_x =
      select(in_cone, one, _mm_add_ps(_mm_mul_ps(cos_w, cos_o), _mm_mul_ps(sin_w, sin_o)));
  const __m128 sin_x =
      select(in_cone, zero, _mm_sub_ps(_mm_mul_ps(sin_w, cos_o), _mm_mul_ps(cos_w, sin_o)));
  const __m128 cos_p = select(_mm_cmpgt_ps(cos_x, cos_b), one,
                              _mm_add_ps(_mm_mul_ps(cos_x, cos_b), _mm_mul_ps(sin_x, sin_b)));
  const __m128 unreached = _mm_cmplt_ps(cos_p, _mm_load_ps(b.cos_theta_e));
  __m128 result = _mm_mul_ps(_mm_mul_ps(phi, cos_p), _mm_mul_ps(inv_d, inv_d));
  if (n != glm::vec3(0.0f)) {
    const __m128 dn = _mm_andnot_ps(sign, _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, _mm_set1_ps(n.x)),
                                                                _mm_mul_ps(dy, _mm_set1_ps(n.y))),
                                                     _mm_mul_ps(dz, _mm_set1_ps(n.z))));
    const __m128 cos_i = _mm_mul_ps(dn, inv_d);
    const __m128 sin_i =
        _mm_mul_ps(_mm_sqrt_ps(_mm_max_ps(zero, _mm_sub_ps(d2, _mm_mul_ps(dn, dn)))), inv_d);
    result =
        _mm_mul_ps(result, select(_mm_cmpgt_ps(cos_i, cos_b), one,
                                  _mm_add_ps(_mm_mul_ps(cos_i, cos_b), _mm_mul_ps(sin_i, sin_b))));
  }
  result = _mm_min_ps(max_importance, _mm_max_ps(zero, result));
  result = select(inside, inside_result, select(unreached, zero, result));
  _mm_storeu_ps(out, result);
}
#else
inline void children_importance(const LightBvh::WideNode& b, glm::vec3 p, glm::vec3 n,
                                float out[4]) {
  for (int k = 0; k < 4; ++k) {
    LightBvh::Node node;
    node.center = {b.cx[k], b.cy[k], b.cz[k]};
    node.radius = b.radius[k];
    node.w = {b.wx[k], b.wy[k], b.wz[k]};
    node.phi = b.phi[k];
    node.cos_theta_o = b.cos_theta_o[k];
    node.sin_theta_o = b.sin_theta_o[k];
    node.cos_theta_e = b.cos_theta_e[k];
    node.two_sided = b.two_sided[k] != 0;
    out[k] = LightBvh::importance(node, p, n);
  }
}
#endif

}  // namespace

void LightBvh::importance4(const WideNode& node, glm::vec3 p, glm::vec3 n, float out[4]) {
  children_importance(node, p, n, out);
}

float light_importance(const LightBounds& b, glm::vec3 p, glm::vec3 n) {
  return LightBvh::importance(LightBvh::Node::of(b), p, n);
}

LightBvh::LightBvh(const std::vector<LightBounds>& lights) {
  trails_.assign(lights.size(), kNotInTree);
  std::vector<Item> items;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const LightBounds& b = lights[i];
    if (!(b.phi > 0.0f) || !std::isfinite(b.phi)) continue;
    items.push_back({b, 0.5f * (b.lo + b.hi), std::uint32_t(i)});
    total_power_ += double(b.phi);
  }
  if (items.empty()) return;
  if (items.size() == 1) {
    single_ = std::int64_t(items[0].light);
    trails_[items[0].light] = 0;
    return;
  }
  std::vector<BuildNode> tree;
  tree.reserve(2 * items.size() - 1);
  const std::uint32_t root = build(tree, items, 0, items.size(), 0);
  nodes_.reserve(items.size() / 2 + 1);
  collapse(tree, root, 0, 0);
}

std::uint32_t LightBvh::build(std::vector<BuildNode>& tree, std::vector<Item>& items,
                              std::size_t begin, std::size_t end, int depth) const {
  const auto node_index = std::uint32_t(tree.size());
  tree.emplace_back();
  if (end - begin == 1) {
    BuildNode& leaf = tree[node_index];
    leaf.bounds = items[begin].bounds;
    leaf.leaf = true;
    leaf.light = items[begin].light;
    return node_index;
  }
  LightBounds all;
  glm::vec3 cmin(std::numeric_limits<float>::max()), cmax(-std::numeric_limits<float>::max());
  for (std::size_t i = begin; i < end; ++i) {
    all = LightBounds::merge(all, items[i].bounds);
    cmin = glm::min(cmin, items[i].centroid);
    cmax = glm::max(cmax, items[i].centroid);
  }
  tree[node_index].bounds = all;

  // The split of least cost over 12 buckets of the centroids along each axis (pbrt-v4's
  // BVHLightSampler::buildBVH). The trail has 64 bits, two per level of the collapsed tree:
  // past the depth at which halving would still fit, nodes are split at the median instead.
  const std::size_t count = end - begin;
  int levels_left = 0;
  while ((std::size_t(1) << levels_left) < count) ++levels_left;
  std::size_t mid = begin;
  if (depth + levels_left < 56) {
    constexpr int kBuckets = 12;
    const glm::vec3 extent = all.hi - all.lo;
    const glm::vec3 cextent = cmax - cmin;
    auto bucket_of = [&](const Item& item, int axis) {
      const int b = int(float(kBuckets) * ((item.centroid[axis] - cmin[axis]) / cextent[axis]));
      return std::clamp(b, 0, kBuckets - 1);
    };
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bucket = -1;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(cextent[axis] > 0.0f) || !(extent[axis] > 0.0f)) continue;
      LightBounds buckets[kBuckets];
      for (std::size_t i = begin; i < end; ++i) {
        LightBounds& bucket = buckets[bucket_of(items[i], axis)];
        bucket = LightBounds::merge(bucket, items[i].bounds);
      }
      // Costs of every split: the buckets below it against those above.
      LightBounds below[kBuckets - 1], above[kBuckets - 1];
      LightBounds acc;
      for (int b = 0; b < kBuckets - 1; ++b) below[b] = acc = LightBounds::merge(acc, buckets[b]);
      acc = LightBounds{};
      for (int b = kBuckets - 1; b > 0; --b)
        above[b - 1] = acc = LightBounds::merge(acc, buckets[b]);
      for (int b = 0; b < kBuckets - 1; ++b) {
        if (!(below[b].phi > 0.0f) || !(above[b].phi > 0.0f)) continue;
        const double cost = split_cost(below[b], extent, axis) + split_cost(above[b], extent, axis);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bucket = b;
        }
      }
    }
    if (best_axis >= 0) {
      const auto it = std::partition(
          items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end),
          [&](const Item& item) { return bucket_of(item, best_axis) <= best_bucket; });
      mid = std::size_t(it - items.begin());
    }
  }
  if (mid == begin || mid == end) {
    // No split separates the centroids (or the depth is running out): halves by the
    // median along the centroids' longest extent.
    const glm::vec3 cextent = cmax - cmin;
    const int axis = cextent.x >= cextent.y && cextent.x >= cextent.z ? 0
                     : cextent.y >= cextent.z                         ? 1
                                                                      : 2;
    mid = begin + count / 2;
    std::nth_element(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(mid),
                     items.begin() + std::ptrdiff_t(end), [axis](const Item& a, const Item& b) {
                       return a.centroid[axis] < b.centroid[axis];
                     });
  }
  const std::uint32_t first = build(tree, items, begin, mid, depth + 1);
  const std::uint32_t second = build(tree, items, mid, end, depth + 1);
  tree[node_index].first = first;
  tree[node_index].second = second;
  return node_index;
}

std::uint32_t LightBvh::collapse(const std::vector<BuildNode>& tree, std::uint32_t b, int depth,
                                 std::uint64_t trail) {
  // The children: each binary child's own two children, or the child itself where it is a
  // light. (Two levels of the binary tree in one; its splits are kept.)
  std::uint32_t children[4];
  int count = 0;
  for (const std::uint32_t c : {tree[b].first, tree[b].second}) {
    if (tree[c].leaf) {
      children[count++] = c;
    } else {
      children[count++] = tree[c].first;
      children[count++] = tree[c].second;
    }
  }
  const auto index = std::uint32_t(nodes_.size());
  nodes_.emplace_back();
  WideNode node{};  // unused lanes: phi 0, so importance 0
  node.count = std::uint8_t(count);
  for (int k = 0; k < count; ++k) {
    const BuildNode& c = tree[children[k]];
    node.set(k, Node::of(c.bounds));
    const std::uint64_t child_trail = trail | (std::uint64_t(k) << (2 * depth));
    if (c.leaf) {
      node.leaf_mask = std::uint8_t(node.leaf_mask | (1u << k));
      node.child[k] = c.light;
      trails_[c.light] = child_trail;
      depth_ = std::max(depth_, depth + 1);
    } else {
      node.child[k] = collapse(tree, children[k], depth + 1, child_trail);
    }
  }
  nodes_[index] = node;
  return index;
}

namespace {

// The importances of `node`'s children (lane k: child k) and 1 / their sum (((i0 + i1) +
// (i2 + i3)), the order sample() and pmf() share); false when none of them reaches p.
// Inlined into the traversals (see importance4).
[[gnu::always_inline]] inline bool child_importances(const LightBvh::WideNode& node, glm::vec3 p,
                                                     glm::vec3 n, float imp[4], float& inv_sum) {
  children_importance(node, p, n, imp);
  const float sum = (imp[0] + imp[1]) + (imp[2] + imp[3]);
  if (!(sum > 0.0f)) return false;  // no light below reaches p
  inv_sum = 1.0f / sum;
  return true;
}

}  // namespace

std::int64_t LightBvh::sample(glm::vec3 p, glm::vec3 n, float u, float& pmf) const {
  pmf = 0.0f;
  if (single_ >= 0) {
    pmf = 1.0f;
    return single_;
  }
  if (nodes_.empty()) return -1;
  std::uint32_t i = 0;
  float prob = 1.0f;
  for (;;) {
    const WideNode& node = nodes_[i];
    alignas(16) float imp[4];
    float inv_sum = 0.0f;
    if (!child_importances(node, p, n, imp, inv_sum)) return -1;
    // The child whose interval of the cumulative probabilities holds u. Each probability is
    // its own importance's share (1 minus the others' would round a child far less
    // important than its siblings, a relative 1e-8, to 0, and a light that reaches p to
    // never); where rounding leaves u past the last interval, the last child with a
    // probability is taken.
    int k = 0;
    float lo = 0.0f, q = imp[0] * inv_sum;
    while (!(u < lo + q) && k + 1 < node.count) {
      lo += q;
      ++k;
      q = imp[k] * inv_sum;
    }
    while (!(q > 0.0f) && k > 0) {
      --k;
      q = imp[k] * inv_sum;
      lo -= q;
    }
    // The random number, rescaled to [0, 1) within the child taken, decides the next step.
    u = std::clamp((u - lo) / q, 0.0f, kOneMinusEpsilon);
    prob *= q;
    if (node.leaf_mask & (1u << k)) {
      if (!(prob > 0.0f)) return -1;
      pmf = prob;
      return std::int64_t(node.child[k]);
    }
    i = node.child[k];
  }
}

float LightBvh::pmf(glm::vec3 p, glm::vec3 n, std::uint32_t light) const {
  if (light >= trails_.size() || trails_[light] == kNotInTree) return 0.0f;
  if (single_ >= 0) return 1.0f;
  std::uint64_t trail = trails_[light];
  std::uint32_t i = 0;
  float prob = 1.0f;
  // The same decisions as sample(), in the same order, so the product is the same float.
  for (;;) {
    const WideNode& node = nodes_[i];
    alignas(16) float imp[4];
    float inv_sum = 0.0f;
    if (!child_importances(node, p, n, imp, inv_sum)) return 0.0f;
    const auto k = unsigned(trail & 3u);
    prob *= imp[k] * inv_sum;
    if (node.leaf_mask & (1u << k)) return prob;
    i = node.child[k];
    trail >>= 2;
  }
}

}  // namespace pbrkit
