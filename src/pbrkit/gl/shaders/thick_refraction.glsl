// Refraction through both interfaces of a thick transmissive object (KHR_materials_volume
// with a thickness > 0), after Wyman 2005, "An Approximate Image-Space Approach for
// Interactive Refraction" (SIGGRAPH): the renderer first draws the object's back faces
// alone (their world position and normal, renderer.cpp's back-face pass); the front face
// refracts the view ray at the entry, estimates how far the refracted ray travels to the
// back face, refracts it again there with the back face's normal, and reads the captured
// opaque frame where that exit ray meets the frame's depth (an iterative search), or the
// environment where the exit ray leaves the screen. A smooth sphere so shows the inverted,
// minified wide view behind it that the path tracer shows, where one refraction shows a
// magnified patch just behind it.
#include "transmission.glsl"

// Wyman 2005, eq. 2: the distance from the entry point to the back face along the refracted
// ray, interpolated between d_v, the distance to the back face along the view ray (the
// back-face pass at the fragment's own pixel), and d_n, the distance along the inward normal
// (the material's thickness), by the ratio of the refraction angle to the incidence angle:
// d = (theta_t / theta_i) d_v + (1 - theta_t / theta_i) d_n. At normal incidence the ratio
// tends to 1 / ior (Snell for small angles), where d_v = d_n anyway.
float wyman_distance(float d_v, float d_n, float cos_i, float ior) {
  float sin_i = sqrt(max(1.0 - cos_i * cos_i, 0.0));
  float theta_i = acos(clamp(cos_i, -1.0, 1.0));
  float theta_t = asin(clamp(sin_i / ior, -1.0, 1.0));
  float ratio = theta_i > 1e-4 ? theta_t / theta_i : 1.0 / ior;
  return ratio * d_v + (1.0 - ratio) * d_n;
}

// One refinement of the distance along the refracted ray (origin p, direction t1): where the
// ray meets the plane of the back face seen at the current estimate (point p_back, normal
// n_back). Repeated, it converges to the exit point of a smooth convex back face; `d` is
// kept where the ray runs nearly parallel to that plane.
float back_plane_distance(vec3 p, vec3 t1, float d, vec3 p_back, vec3 n_back) {
  float c = dot(t1, n_back);
  if (c < 1e-3) return d;
  return max(dot(p_back - p, n_back) / c, 0.0);
}

// The direction the ray t1 (unit, inside the medium of index `ior`) leaves in through the
// back face of outward normal n_back (Snell, from ior to 1); under total internal reflection
// (sin_t > 1) the ray reflected inside, the direction in which that light mostly leaves
// after it (`tir` true).
vec3 exit_direction(vec3 t1, vec3 n_back, float ior, out bool tir) {
  vec3 n = dot(t1, n_back) > 0.0 ? -n_back : n_back;  // against the ray, as refract() wants
  vec3 t2 = refract(t1, n, ior);
  tir = dot(t2, t2) == 0.0;
  return normalize(tir ? reflect(t1, n) : t2);
}

// The view ray (towards -v) refracted at the entry (normal n) and again at the back face
// (normal n_back): the two-interface direction of the exit ray.
vec3 refract_twice(vec3 v, vec3 n, vec3 n_back, float ior, out bool tir) {
  vec3 t1 = refract(-v, n, 1.0 / ior);
  tir = false;
  if (dot(t1, t1) == 0.0) return -v;
  return exit_direction(normalize(t1), n_back, ior, tir);
}

// The texel of a single-level target at texture coordinates uv, unfiltered: a blend of two
// texels would be a position or depth between two surfaces, on neither.
vec4 texel_at(sampler2D target, ivec2 size, vec2 uv) {
  return texelFetch(target, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), 0);
}

vec4 texel_at(sampler2D target, vec2 uv) { return texel_at(target, textureSize(target, 0), uv); }

// Where the ray from `origin` along `dir` meets the captured frame (Wyman 2005's
// nearby-geometry lookup made iterative, as relief and parallax mapping search a height
// field): from d = 0, the distance to the frame's surface point seen where the ray's point at
// d projects (unprojected from the frame's depth), repeated; for a smooth surface behind the
// object (a floor, a wall) it converges to the ray's intersection with it in a few steps,
// with one depth fetch each where a march needs one per step. It converges where the step
// contracts: on a plane of normal n, g'(d) = 1 - (n.e)(e.w) / (n.w) (e the ray, w the view
// direction to its hit), near 0 for a ray close to the view direction; past |g'| = 1 (a ray
// bent steeply onto a surface seen at a grazing angle) the steps oscillate about the hit
// (tests/gl/thick_refraction_glsl_test.cpp), `iterations` steps. Returns the frame's texture
// coordinates and the distance; false where the ray leaves the screen, goes behind the
// camera or meets the background (the environment is what it sees then). `o` and `e` are
// origin and dir in clip space (view_projection times (origin, 1) and (dir, 0)): the ray's
// point at d projects from o + d e, one multiply-add per step instead of a projection.
const int kFrameHitIterations = 4;
bool frame_hit(vec3 origin, vec4 o, vec4 e, mat4 inverse_view_projection, sampler2D frame_depth,
               int iterations, out vec2 uv, out float d) {
  d = 0.0;
  // Per step, the texel and the unprojection of (uv, depth), with what does not change
  // hoisted: the target's size, and the inverse matrix applied to texture
  // coordinates and depth in [0, 1] rather than to NDC (its columns scaled by 2, the -1
  // offsets folded into the last column); and |p / w - origin| as |p - origin w| / |w|.
  ivec2 size = textureSize(frame_depth, 0);
  mat4 m = inverse_view_projection;
  vec4 mu = 2.0 * m[0], mv = 2.0 * m[1], mz = 2.0 * m[2], m1 = m[3] - m[0] - m[1] - m[2];
  for (int k = 0; k < iterations; ++k) {
    if (!clip_to_screen(o + d * e, uv)) return false;
    float scene = texel_at(frame_depth, size, uv).r;
    if (scene >= 1.0) return false;
    vec4 b = mu * uv.x + mv * uv.y + mz * scene + m1;
    d = length(b.xyz - origin * b.w) / abs(b.w);
  }
  return clip_to_screen(o + d * e, uv);
}

// The length of the part of the ray o + d e (clip space) inside the view frustum's sides and
// far plane, from d = 0: where it leaves the screen or goes beyond the far plane.
float on_screen_length(vec4 o, vec4 e) {
  float len = 1e30;
  vec4 planes[5] = vec4[5](vec4(1, 0, 0, 1), vec4(-1, 0, 0, 1), vec4(0, 1, 0, 1),
                           vec4(0, -1, 0, 1), vec4(0, 0, -1, 1));
  for (int i = 0; i < 5; ++i) {
    float po = dot(planes[i], o), pe = dot(planes[i], e);
    if (pe < 0.0) len = min(len, max(po, 0.0) / -pe);
  }
  return len;
}

// Where the ray o + d e (clip space) first passes behind the frame's surface: a march over
// the ray's on-screen length in kMarchSteps steps, denser near the origin (d_k ~ k^2), then
// kMarchBisections halvings of the step that crossed. Unlike frame_hit's fixed point it does
// not depend on the ray's angle to the view direction; it can stop at a depth
// discontinuity (a ray passing behind a nearer object), which the caller's settling test
// rejects. Runs while `running`, as the loop's condition rather than a branch around it: a
// software rasteriser runs both sides of a branch, but leaves a loop once all its lanes have
// (on llvmpipe 6, 8 and 12 steps cost the same frame time within 3%).
const int kMarchSteps = 12;
const int kMarchBisections = 4;
bool frame_march(vec4 o, vec4 e, sampler2D frame_depth, bool running, out vec2 uv, out float d) {
  ivec2 size = textureSize(frame_depth, 0);
  // A hair short of the screen's edge, so that the last step's point projects onto it.
  float len = 0.999 * on_screen_length(o, e);
  float front = 0.0, back = -1.0;
  uv = vec2(0.0);
  d = 0.0;
  for (int k = 1; k <= kMarchSteps && running; ++k) {
    float dk = len * float(k * k) / float(kMarchSteps * kMarchSteps);
    vec4 c = o + dk * e;
    vec2 u;
    if (!clip_to_screen(c, u)) break;
    if (c.z / c.w * 0.5 + 0.5 >= texel_at(frame_depth, size, u).r) {
      back = dk;
      running = false;
    } else {
      front = dk;
    }
  }
  for (int k = 0; k < kMarchBisections && back >= 0.0; ++k) {
    float mid = 0.5 * (front + back);
    vec4 c = o + mid * e;
    vec2 u;
    clip_to_screen(c, u);
    if (c.z / c.w * 0.5 + 0.5 >= texel_at(frame_depth, size, u).r)
      back = mid;
    else
      front = mid;
  }
  d = back;
  return back >= 0.0 && clip_to_screen(o + d * e, uv);
}

// Whether a search along the ray from `origin` (world) along `dir` that ended at distance d
// and texture coordinates uv found the frame's surface: the surface seen there lies within
// kSettledTolerance d of the ray's point at d. Not so where frame_hit's steps oscillate (a
// ray far from the view direction) or frame_march stopped at a depth discontinuity.
const float kSettledTolerance = 0.1;
bool settled_on_frame(vec3 origin, vec3 dir, vec2 uv, float d, mat4 inverse_view_projection,
                      sampler2D frame_depth) {
  float scene = texel_at(frame_depth, uv).r;
  vec4 q = inverse_view_projection * vec4(vec3(uv, scene) * 2.0 - 1.0, 1.0);
  return scene < 1.0 && distance(q.xyz / q.w, origin + d * dir) <= kSettledTolerance * d;
}

// Where a search along the ray from `origin` (world) along `dir` (o, e: clip space) has not
// settled, frame_march's crossing if it settles (settled_on_frame), in uv and d: whether it
// did. Both frame searches end with it.
bool march_where_unsettled(vec3 origin, vec3 dir, vec4 o, vec4 e, mat4 inverse_view_projection,
                           sampler2D frame_depth, bool settled, inout vec2 uv, inout float d) {
  vec2 uv_march;
  float d_march;
  if (!frame_march(o, e, frame_depth, !settled, uv_march, d_march) ||
      !settled_on_frame(origin, dir, uv_march, d_march, inverse_view_projection, frame_depth))
    return false;
  uv = uv_march;
  d = d_march;
  return true;
}

// The opaque frame where the mirror direction `dir` from a thick transmissive surface at
// `origin` meets it (a screen-space reflection: frame_hit's search, as for the exit ray, and
// frame_march where it has not settled), read at the blur `lod`; false where the ray leaves
// the screen, goes behind the camera, meets the background, or neither search settles
// (settled_on_frame). There the split sum's environment is what the surface reflects.
const int kReflectionIterations = 8;
bool reflected_frame(vec3 origin, vec3 dir, mat4 view_projection, mat4 inverse_view_projection,
                     sampler2D frame_depth, sampler2D frame, float lod, out vec3 seen) {
  seen = vec3(0.0);
  vec4 o = view_projection * vec4(origin, 1.0), e = view_projection * vec4(dir, 0.0);
  vec2 uv;
  float d;
  bool settled = frame_hit(origin, o, e, inverse_view_projection, frame_depth,
                           kReflectionIterations, uv, d) &&
                 settled_on_frame(origin, dir, uv, d, inverse_view_projection, frame_depth);
  if (march_where_unsettled(origin, dir, o, e, inverse_view_projection, frame_depth, settled, uv,
                            d))
    settled = true;
  if (!settled) return false;
  seen = textureLod(frame, uv, lod).rgb;
  return true;
}

// The back faces of the object being drawn (renderer.cpp's back-face pass): world position
// (w = 1 where a back face is) and outward normal, per pixel, inside the rectangle `rect`
// ((min, max) texture coordinates) where the pass ran for it.
struct BackFaceHit {
  vec3 position;
  vec3 normal;
  bool found;
};

BackFaceHit back_face_at(sampler2D back_position, sampler2D back_normal, vec4 rect, vec2 uv) {
  vec4 p = texel_at(back_position, uv);
  BackFaceHit h;
  h.position = p.xyz;
  h.found = p.w > 0.5 && all(greaterThanEqual(uv, rect.xy)) && all(lessThan(uv, rect.zw));
  h.normal = h.found ? normalize(texel_at(back_normal, uv).xyz) : vec3(0.0, 0.0, 1.0);
  return h;
}

// The refinements of the distance to the back face after Wyman's estimate.
const int kBackFaceRefinements = 2;
// The segments followed inside: the refracted ray's, then, where the back face reflects it
// totally, the reflected ray's to the next back face (a slab's side face sends the light
// down to its bottom face); past these, the light leaves along the last reflected ray.
const int kInsideSegments = 2;

// From `origin` along `dir` inside the object (`o`, `e`: both in clip space, as frame_hit
// takes them), the distance `d` to its back face (from the estimate `d` on:
// back_plane_distance at the back face seen where the ray's point at d projects) and that
// face's normal; false where no back face the ray heads for is seen there.
bool to_back_face(vec3 origin, vec3 dir, vec4 o, vec4 e, sampler2D back_position,
                  sampler2D back_normal, vec4 rect, inout float d, out vec3 n_back) {
  n_back = vec3(0.0);
  bool found = false;
  for (int k = 0; k < kBackFaceRefinements; ++k) {
    vec2 uv;
    if (!clip_to_screen(o + d * e, uv)) break;
    BackFaceHit h = back_face_at(back_position, back_normal, rect, uv);
    // A face the ray runs away from (or along) is not where it leaves: a reflected ray in a
    // thin curved wall heads for the outer wall's front face, which the pass does not hold.
    if (!h.found || dot(dir, h.normal) < 1e-3) break;
    d = back_plane_distance(origin, dir, d, h.position, h.normal);
    n_back = h.normal;
    found = true;
  }
  return found;
}

// One channel's ray out of the object (ior `ior`): the view ray refracted at the entry,
// carried to the back face (Wyman's estimate, then to_back_face), refracted out of it (or
// reflected inside, kInsideSegments); where it leaves (`origin`, and `o` in clip space), its
// direction (`dir`, and `e` in clip space) and the path length inside, for Beer-Lambert.
// Where the back-face pass holds nothing at the fragment's own pixel (a silhouette), or has
// not run for this draw (`two_faces` false), one refraction: the ray crosses the material's
// thickness (transmission.glsl's volume_transmission_ray) unbent.
struct ExitRay {
  vec3 origin, dir;
  vec4 o, e;
  float inside;
};

ExitRay exit_ray(TransmissionInputs t, float ior, bool two_faces, BackFaceHit own, float d_v,
                 vec4 entry, sampler2D back_position, sampler2D back_normal, vec4 back_rect,
                 mat4 view_projection) {
  ExitRay r;
  r.dir = refract(-t.v, t.n, 1.0 / ior);
  r.dir = dot(r.dir, r.dir) > 0.0 ? normalize(r.dir) : -t.v;
  float d_n = length(volume_transmission_ray(t.n, t.v, t.thickness, ior, t.model_scale));
  float d = two_faces ? wyman_distance(d_v, d_n, saturate(dot(t.n, t.v)), ior) : d_n;
  r.origin = t.position;
  r.o = entry;
  r.e = view_projection * vec4(r.dir, 0.0);
  r.inside = 0.0;
  for (int segment = 0; segment < kInsideSegments; ++segment) {
    vec3 n_back = own.normal;
    bool found = two_faces && to_back_face(r.origin, r.dir, r.o, r.e, back_position, back_normal,
                                           back_rect, d, n_back);
    // The first segment keeps Wyman's estimate and the fragment's own back face where the
    // refined point sees none. A reflected ray that meets no back face heads for a front
    // face (which the pass does not hold): it is taken to cross the object once more, as
    // long as the segment before, and to leave along its direction.
    if (!found && segment == 0) n_back = own.normal;
    r.origin += d * r.dir;
    r.o += d * r.e;
    r.inside += d;
    if ((!found && segment > 0) || !two_faces) break;
    bool tir;
    r.dir = exit_direction(r.dir, n_back, ior, tir);
    r.e = view_projection * vec4(r.dir, 0.0);
    if (!tir) break;
  }
  return r;
}

// What the exit ray `r` of a channel of ior `ior` sees: the frame at `uv` where `on`, else
// the environment along it, at the rough interface's blur, attenuated along the path inside.
vec3 exit_radiance(TransmissionInputs t, ExitRay r, float ior, bool on, vec2 uv, sampler2D frame,
                   vec2 frame_size, samplerCube env_cube, vec2 env_rotation, int env_levels,
                   float env_scale) {
  float rough = transmission_roughness(t.roughness, ior);
  vec3 seen;
  if (on) {
    seen = textureLod(frame, uv, log2(frame_size.x) * rough).rgb;
  } else {
    seen = env_scale * textureLod(env_cube, world_to_env(r.dir, env_rotation),
                                  rough * float(env_levels - 1)).rgb;
  }
  return seen * volume_attenuation(r.inside, t.attenuation_color, t.attenuation_distance);
}

// refracted_radiance (transmission.glsl) through both interfaces: per channel (three iors
// with dispersion) the exit ray (exit_ray), followed to the frame's surface (frame_hit) for
// green, or the one ior, alone: the other channels' exit rays are read at the same distance
// along them, so the search runs once per fragment. Their exit rays are traced after green's
// search, which sits outside the loop over channels rather than in a branch on the channel:
// a software rasteriser (llvmpipe) runs both sides of a branch, so in the loop it would run
// masked for every channel (5% of a frame of thick dispersive spheres on llvmpipe). The
// silhouette case (no back face at the fragment's own pixel) runs through the same code
// rather than a branch of its own, for the same reason. The rays are carried in clip space
// alongside world space (clip = view_projection x world is linear), so each direction is
// projected once.
vec3 thick_refracted_radiance(TransmissionInputs t, bool back_faces, sampler2D frame,
                              sampler2D frame_depth, vec2 frame_size, sampler2D back_position,
                              sampler2D back_normal, vec4 back_rect, vec2 pixel_uv,
                              mat4 view_projection, mat4 inverse_view_projection,
                              samplerCube env_cube, vec2 env_rotation, int env_levels,
                              float env_scale, bool dispersion) {
  BackFaceHit own = back_face_at(back_position, back_normal, back_rect, pixel_uv);
  bool two_faces = back_faces && own.found;
  float d_v = distance(own.position, t.position);
  vec4 entry = view_projection * vec4(t.position, 1.0);
  int first = dispersion ? 1 : 0;  // green first: its search serves the others
  float ior = t.iors[first];
  ExitRay r = exit_ray(t, ior, two_faces, own, d_v, entry, back_position, back_normal, back_rect,
                       view_projection);
  vec2 uv;
  float t_hit;
  bool hit = frame_hit(r.origin, r.o, r.e, inverse_view_projection, frame_depth,
                       kFrameHitIterations, uv, t_hit);
  bool settled =
      hit && settled_on_frame(r.origin, r.dir, uv, t_hit, inverse_view_projection, frame_depth);
  // Where the exit point lies behind the frame's surface, the light leaves into that
  // surface: a body resting on a floor sends the rays it reflects totally down to the floor,
  // and a segment carried past its back faces (exit_ray's kInsideSegments) can end under the
  // floor, where the search from that point finds no crossing.
  vec2 uv_exit;
  if (!hit && clip_to_screen(r.o, uv_exit)) {
    float scene = texel_at(frame_depth, uv_exit).r;
    if (scene < 1.0 && r.o.z / r.o.w * 0.5 + 0.5 > scene) {
      hit = settled = true;
      uv = uv_exit;
      t_hit = 0.0;
    }
  }
  // Where frame_hit's steps have not settled (an exit ray bent far from the view direction:
  // the block's rays reflected down to the floor inside it) or found nothing, the march; where
  // it finds nothing either, frame_hit's estimate or the environment as before.
  if (march_where_unsettled(r.origin, r.dir, r.o, r.e, inverse_view_projection, frame_depth,
                            settled, uv, t_hit))
    hit = true;
  vec3 result = exit_radiance(t, r, ior, hit, uv, frame, frame_size, env_cube, env_rotation,
                              env_levels, env_scale);
  if (dispersion) {
    for (int c = 0; c < 3; c += 2) {
      ExitRay rc = exit_ray(t, t.iors[c], two_faces, own, d_v, entry, back_position, back_normal,
                            back_rect, view_projection);
      vec2 uv_c;
      bool on = hit && clip_to_screen(rc.o + t_hit * rc.e, uv_c);
      result[c] = exit_radiance(t, rc, t.iors[c], on, uv_c, frame, frame_size, env_cube,
                                env_rotation, env_levels, env_scale)[c];
    }
  }
  return result;
}
