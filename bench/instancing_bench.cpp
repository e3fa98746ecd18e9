// The path tracer's cost against instanced and unique triangles: memory (peak RSS) and time
// to the first sample of scenes built in code, and the trace rate of flattened against
// instanced single-use meshes (the choice pt/geometry.h makes).
//
//   instancing_bench instances N   N instances of one 5,696-triangle sphere on a grid
//   instancing_bench unique N      N triangles in distinct 5,696-triangle meshes, each once
//   instancing_bench flatten       ray rate on `spheres`, flattened vs behind instances
//   instancing_bench layout        BVH memory and ray rate on `spheres`, Embree's fast
//                                  layout vs its compact one (BvhLayout)
//
// One measurement per process (peak RSS is the process's); bench/run loops over N.
// Output: one line of key=value pairs.
#include <pmmintrin.h>
#include <sys/resource.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pbrkit/core/sampling.h"
#include "pbrkit/pt/geometry.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/primitives.h"
#include "pbrkit/util/parallel.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Process CPU time (all threads): rates per CPU-second stay comparable on a loaded machine.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // ru_maxrss is in kilobytes on Linux
}

// 2 x 89 x 32 = 5,696 triangles, the mesh of the 10,000-node glTF in bench/.
pbrkit::Mesh rock() {
  return pbrkit::make_uv_sphere(0.4f, 89, 33);
}

// `count` placements on a square grid in the XZ plane, spacing 1, each turned and scaled a
// little (a few mirrored), the camera above one corner looking across the field.
glm::mat4 placement(std::size_t i, std::size_t side) {
  const float x = float(i % side), z = float(i / side);
  const float turn = float((i * 2654435761u) % 1000) * 0.00628f;
  const float s = 0.8f + 0.4f * float((i * 40503u) % 100) / 100.0f;
  glm::mat4 M = glm::translate(glm::mat4(1.0f), {x, 0.4f, z});
  M = glm::rotate(M, turn, {0, 1, 0});
  return glm::scale(M, {i % 7 == 0 ? -s : s, s * 1.2f, s});
}

pbrkit::Scene field(std::size_t count, bool shared) {
  pbrkit::Scene scene;
  scene.source = shared ? "bench:instances" : "bench:unique";
  pbrkit::Material m;
  m.base_color_factor = glm::vec4(0.6f, 0.5f, 0.4f, 1.0f);
  m.roughness_factor = 0.6f;
  scene.materials.push_back(m);
  std::size_t side = 1;
  while (side * side < count) ++side;
  const pbrkit::Mesh mesh = rock();
  if (shared) {
    const int id = pbrkit::add_mesh_instance(scene, mesh, 0, placement(0, side));
    scene.instances.reserve(count);
    for (std::size_t i = 1; i < count; ++i) scene.instances.push_back({id, placement(i, side), -1});
  } else {
    scene.meshes.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
      pbrkit::add_mesh_instance(scene, mesh, 0, placement(i, side));
  }
  pbrkit::Camera camera;
  camera.yfov = 0.9f;
  const float e = float(side);
  camera.camera_to_world =
      glm::inverse(glm::lookAt(glm::vec3(-2.0f, 0.25f * e + 3.0f, -2.0f),
                               glm::vec3(0.5f * e, 0.0f, 0.5f * e), glm::vec3(0, 1, 0)));
  scene.cameras.push_back(camera);
  return scene;
}

int run_field(std::size_t count, bool shared) {
  const auto t0 = Clock::now();
  // The triangles asked for, in whole meshes.
  const std::size_t meshes = shared ? count : std::max<std::size_t>(1, (count + 5695) / 5696);
  const pbrkit::Scene scene = field(meshes, shared);
  const double scene_s = since(t0);
  const double scene_rss = peak_rss_mb();
  pbrkit::PathTracerSettings s;
  s.width = s.height = 64;
  s.spp = 1;
  s.noise_threshold = 0.0f;
  s.max_bounces = 2;
  s.threads = 2;
  const auto t1 = Clock::now();
  const pbrkit::PathTracerResult r = pbrkit::render_path(scene, nullptr, scene.cameras[0], s);
  const double first_sample_s = since(t1);
  std::size_t unique = 0;
  for (const pbrkit::Mesh& m : scene.meshes) unique += m.triangle_count();
  const pbrkit::GeometryMemory e = pbrkit::estimate_geometry_memory(scene);
  std::printf(
      "mode=%s instances=%zu unique_triangles=%zu instanced_triangles=%zu scene_s=%.3f "
      "scene_rss_mb=%.0f bvh_s=%.3f first_sample_s=%.3f peak_rss_mb=%.0f estimate_mb=%.0f\n",
      shared ? "instances" : "unique", scene.instances.size(), unique, scene.triangle_count(),
      scene_s, scene_rss, r.stats.bvh_seconds, first_sample_s, peak_rss_mb(),
      double(e.geometry + e.bvh) * 1e-6);
  return 0;
}

// Rays from points around the `spheres` grid towards points in it, through the geometry
// built with each of `variants` in turn (five rounds): the same rays through the same
// triangles, built differently.
int trace_variants(const char* mode,
                   const std::vector<std::pair<const char*, pbrkit::GeometryOptions>>& variants) {
  const pbrkit::Scene scene = pbrkit::builtin_scene("spheres");
  pbrkit::Pcg32 rng(7);
  const std::size_t n = 1 << 21;
  std::vector<glm::vec3> o(n), d(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 from(rng.next_float() * 10.0f - 5.0f, rng.next_float() * 10.0f - 5.0f,
                         rng.next_float() < 0.5f ? 6.0f : -6.0f);
    const glm::vec3 to(rng.next_float() * 7.0f - 3.5f, rng.next_float() * 7.0f - 3.5f, 0.0f);
    o[i] = from;
    d[i] = glm::normalize(to - from);
  }
  tbb::task_arena arena(2);
  for (int rep = 0; rep < 5; ++rep)
    for (const auto& [name, options] : variants) {
      const auto tb = Clock::now();
      double rate = 0.0, cpu_rate = 0.0, build = 0.0;
      std::size_t hits = 0;
      pbrkit::GeometryMemory memory;
      arena.execute([&] {
        const pbrkit::SceneGeometry g(scene, options);
        build = since(tb);
        memory = g.memory();
        const auto t = Clock::now();
        const double cpu0 = cpu_seconds();
        std::atomic<std::size_t> h{0};
        pbrkit::parallel_for(std::size_t(0), n / 4096, [&](std::size_t c) {
          _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
          _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
          std::uint32_t geom, prim;
          float tt, u, v;
          std::size_t local = 0;
          for (std::size_t i = c * 4096; i < (c + 1) * 4096; ++i) {
            if (g.intersect(o[i], d[i], 1e30f, ~0u, geom, prim, tt, u, v)) {
              const pbrkit::SurfaceHit hit = g.resolve(geom, prim, tt, u, v);
              local += hit.ng.z > 0.0f;
            }
          }
          h += local;
        });
        rate = double(n) / since(t) * 1e-6;
        cpu_rate = double(n) / (cpu_seconds() - cpu0) * 1e-6;
        hits = h;
      });
      std::printf(
          "mode=%s variant=%s build_s=%.4f bvh_mb=%.2f bvh_peak_mb=%.2f mrays_per_s=%.2f "
          "mrays_per_cpu_s=%.2f hits=%zu\n",
          mode, name, build, double(memory.bvh) * 1e-6, double(memory.bvh_peak) * 1e-6, rate,
          cpu_rate, hits);
    }
  return 0;
}

int run_flatten() {
  pbrkit::GeometryOptions flattened, instanced;
  instanced.flatten_single_use = false;
  return trace_variants("flatten", {{"flattened", flattened}, {"instanced", instanced}});
}

int run_layout() {
  pbrkit::GeometryOptions fast, compact;
  fast.layout = pbrkit::BvhLayout::kFast;
  compact.layout = pbrkit::BvhLayout::kCompact;
  return trace_variants("layout", {{"fast", fast}, {"compact", compact}});
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "flatten") return run_flatten();
  if (mode == "layout") return run_layout();
  if ((mode == "instances" || mode == "unique") && argc > 2)
    return run_field(std::size_t(std::strtoull(argv[2], nullptr, 10)), mode == "instances");
  std::fprintf(stderr,
               "usage: instancing_bench instances N | unique TRIANGLES | flatten | layout\n");
  return 2;
}
