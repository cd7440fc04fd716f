// Random scene generation at the report's density (15 spheres in a cube of side 80, radii 5 to
// 10), scaled up by growing the cube with the cube root of the count. The grid keeps the cost
// per sphere flat, so spheres/s should barely move from 1e3 to 1e6 spheres.
//
//   build-gen/bench/glint-random-scene-bench --benchmark_out=random_scene.json

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "glint/generate/random_scene.hpp"
#include "glint/io/scene_writer.hpp"

namespace {

glint::RandomSceneParameters report_density(int count) {
  glint::RandomSceneParameters p;
  p.sphere_count = count;
  p.domain_size = static_cast<float>(80.0 * std::cbrt(count / 15.0));
  return p;
}

void BM_GenerateRandomScene(benchmark::State& state) {
  const glint::RandomSceneParameters p = report_density(static_cast<int>(state.range(0)));
  int placed = 0;
  long long attempts = 0;
  for (auto _ : state) {
    glint::RandomSceneResult result = glint::generate_random_scene(p);
    placed = result.placed;
    attempts = result.attempts;
    benchmark::DoNotOptimize(result.scene.spheres.data());
  }
  state.SetItemsProcessed(state.iterations() * p.sphere_count);
  state.counters["placed"] = placed;
  state.counters["attempts_per_sphere"] = double(attempts) / p.sphere_count;
}
BENCHMARK(BM_GenerateRandomScene)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Writing the scene text: shortest-float formatting of every number.
void BM_FormatScene(benchmark::State& state) {
  const glint::SceneDescription scene =
      glint::generate_random_scene(report_density(static_cast<int>(state.range(0)))).scene;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = glint::format_scene(scene);
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(scene.spheres.size()));
  state.SetBytesProcessed(state.iterations() * static_cast<long long>(bytes));
}
BENCHMARK(BM_FormatScene)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
