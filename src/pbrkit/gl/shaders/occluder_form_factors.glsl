// Form factors of the proxies that stand for transmissive objects (occluders.glsl): the
// share of a uniform environment's light, cosine-weighted over the hemisphere of a surface
// point x with unit normal n, that arrives from the directions the proxy covers.
#include "math.glsl"

// A point well inside a proxy (past kContentsMargin of the way in from its surface) is
// taken to be the object's contents, a liquid in its glass, and not shadowed by it: a
// container's proxy is solid, its opening is not in it.
const float kContentsMargin = 0.02;

// The form factor from (x, n) to a parallelepiped (centre c; N[k]: the unit normal of its
// k-th pair of faces and, in w, its half-extent along it; area[k]: the area of one of that
// pair's faces). A disc facing x of the body's projected area towards x,
// pi R^2 = sum_k area_k |l.N_k| (l the unit direction to c), at the distance h from x to
// halfway between the body's surface and c along l (the surface alone puts it too near for
// a line that enters low on a tall body's side): R^2 / (R^2 + h^2) cos, a coaxial disc's
// factor (the sphere's, r^2 / d^2 cos, from afar), at most 1/2 (beside the body, over none
// of its faces, it covers at most the half of x's hemisphere on its side of a plane through
// x). Over a face (x beyond that pair of faces alone), at least a coaxial disc of the face's
// area at x's height h over it, R^2 / (R^2 + h^2), times the cosine of n with the face's
// inward normal and, per edge, between 1/2 (a foot on the edge) and 1 (a foot as far inside
// as x is high). tests/gl/occluders_test.cpp measures it against Lambert's exact polygon
// formula (Arvo 1995), an acos per edge of the silhouette, which this approximation spares
// every opaque fragment.
float box_form_factor(vec3 x, vec3 n, vec3 c, vec4 N0, vec4 N1, vec4 N2, vec3 area) {
  vec3 w = c - x;
  vec3 offset = vec3(dot(w, N0.xyz), dot(w, N1.xyz), dot(w, N2.xyz));
  vec3 half_extent = vec3(N0.w, N1.w, N2.w);
  vec3 outside = abs(offset) - half_extent;  // > 0: beyond that pair's faces
  bool contents = all(lessThan(outside, -kContentsMargin * half_extent));
  float inv_d = inversesqrt(dot(w, w));
  vec3 cosines = abs(offset) * inv_d;  // |l.N_k|
  float R2 = dot(area, cosines) * kInvPi;
  vec3 reach = half_extent / max(cosines, vec3(1e-6));  // from c to each pair's planes along l
  float h = max(1.0 / inv_d - 0.5 * min(reach.x, min(reach.y, reach.z)), 0.0);
  float f = min(R2 / (R2 + h * h) * dot(n, w) * inv_d, 0.5);
  // All three pairs' faces side by side (component k: pair k's, its edges across pairs
  // k + 1 and k + 2; a foot on an edge, to rounding, is on the face).
  bvec3 beyond = greaterThan(outside, 1e-4 * half_extent);
  bvec3 over = bvec3(vec3(beyond) * (1.0 - vec3(beyond.yzx)) * (1.0 - vec3(beyond.zxy)));
  vec3 face_R2 = area * kInvPi;
  vec3 height = max(outside, vec3(0.0));
  vec3 facing = vec3(dot(n, N0.xyz), dot(n, N1.xyz), dot(n, N2.xyz)) * sign(offset);
  vec3 lift = 1.0 / max(height, vec3(1e-6));
  vec3 edges = (0.5 + 0.5 * clamp(-outside.yzx * lift, 0.0, 1.0)) *
               (0.5 + 0.5 * clamp(-outside.zxy * lift, 0.0, 1.0));
  vec3 near = mix(vec3(0.0), face_R2 / (face_R2 + height * height) * facing * edges, over);
  f = max(f, max(near.x, max(near.y, near.z)));
  return contents ? 0.0 : clamp(f, 0.0, 1.0);
}

// The form factor from (x, n) to a sphere (centre c, radius r) wholly above x's horizon:
// (r / d)^2 cos(theta), theta the angle between n and the direction to the centre (the
// differential-element-to-sphere factor of Howell's "A Catalog of Radiation Heat Transfer
// Configuration Factors"); 0 well inside it (kContentsMargin). Past x's horizon
// (cos(theta) < r / d) it is not clipped, only clamped at 0.
float sphere_form_factor(vec3 x, vec3 n, vec3 c, float r) {
  vec3 w = c - x;
  float d2 = dot(w, w);
  float inner = (1.0 - kContentsMargin) * r;
  if (d2 < inner * inner) return 0.0;
  return clamp(r * r / d2 * dot(n, w) * inversesqrt(d2), 0.0, 1.0);
}
