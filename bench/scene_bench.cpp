// Scene loading speed: glTF/GLB load time against file size (it must be linear), the
// shared 2CylinderEngine model, tangent generation and the closure check of volumes.
// Generated grids are written to the temp folder as pbrkit-bench-grid-<triangles>.glb
// (reused by `pbrkit info` timings in BENCHMARKS.md).
#include <filesystem>

#include <benchmark/benchmark.h>

#include "pbrkit/scene/load.h"
#include "pbrkit/scene/mesh_attributes.h"
#include "pbrkit/scene/mesh_closure.h"
#include "pbrkit/util/log.h"

namespace {

using namespace pbrkit;

// A flat n x n grid of quads (2 n^2 triangles) with normals and uvs.
Mesh grid_mesh(int n) {
  Mesh m;
  m.name = "grid";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const glm::vec2 uv(float(x) / float(n), float(y) / float(n));
      m.positions.push_back({uv.x, 0.0f, uv.y});
      m.normals.push_back({0.0f, 1.0f, 0.0f});
      m.texcoords0.push_back(uv);
    }
  const auto row = std::uint32_t(n + 1);
  for (std::uint32_t y = 0; y < std::uint32_t(n); ++y)
    for (std::uint32_t x = 0; x < std::uint32_t(n); ++x) {
      const std::uint32_t a = y * row + x, b = a + 1, c = a + row, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  return m;
}

std::filesystem::path grid_glb(std::int64_t triangles) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("pbrkit-bench-grid-" + std::to_string(triangles) + ".glb");
  if (!std::filesystem::exists(path)) {
    Scene s;
    s.meshes.push_back(grid_mesh(int(std::sqrt(double(triangles) / 2.0))));
    s.instances.push_back({0, glm::mat4(1.0f), -1});
    write_glb(s, path);
  }
  return path;
}

void BM_LoadGeneratedGlb(benchmark::State& state) {
  const auto path = grid_glb(state.range(0));
  std::size_t tris = 0;
  for (auto _ : state) {
    const Scene s = load_scene(path.string());
    tris = s.triangle_count();
    benchmark::DoNotOptimize(s.meshes.data());
  }
  state.SetBytesProcessed(std::int64_t(state.iterations()) *
                          std::int64_t(std::filesystem::file_size(path)));
  state.counters["triangles"] = double(tris);
}
BENCHMARK(BM_LoadGeneratedGlb)
    ->Arg(250000)
    ->Arg(500000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

void BM_LoadEngine(benchmark::State& state) {
  const auto path =
      std::filesystem::path(PBRKIT_ASSETS_DIR) / "models/2CylinderEngine/2CylinderEngine.glb";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("shared assets not available");
    return;
  }
  for (auto _ : state) {
    const Scene s = load_scene(path.string());
    benchmark::DoNotOptimize(s.meshes.data());
  }
  state.SetBytesProcessed(std::int64_t(state.iterations()) *
                          std::int64_t(std::filesystem::file_size(path)));
}
BENCHMARK(BM_LoadEngine)->Unit(benchmark::kMillisecond);

void BM_GenerateTangents(benchmark::State& state) {
  const Mesh base = grid_mesh(int(std::sqrt(double(state.range(0)) / 2.0)));
  for (auto _ : state) {
    state.PauseTiming();
    Mesh m = base;
    state.ResumeTiming();
    generate_tangents(m);
    benchmark::DoNotOptimize(m.tangents.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(base.triangle_count()));
}
BENCHMARK(BM_GenerateTangents)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The closure check a volume's primitive gets (Mesh::closed, mesh_closure.h): welding by
// position and counting edges, on the same grid.
void BM_CountEdges(benchmark::State& state) {
  const Mesh m = grid_mesh(int(std::sqrt(double(state.range(0)) / 2.0)));
  for (auto _ : state) benchmark::DoNotOptimize(count_edges(m).unpaired);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(m.triangle_count()));
}
BENCHMARK(BM_CountEdges)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  pbrkit::set_log_sink([](pbrkit::LogLevel, const std::string&) {});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
