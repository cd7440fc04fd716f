// Whole-render cost of every named variant the build compiled (glint::compiled::Variants: all of
// them unless GLINT_RENDERER_VARIANTS chose fewer) on the small scenes of bench/scenes: one
// benchmark per (scene, variant, execution model), each iteration one 64x64 frame at 4 spp,
// depth 12, on one worker thread. Compare a variant with `report` on the same scene; the quality
// side of the trade (error at equal time and at equal samples) is bench/run-all's.
//
// Names: render/SCENE/VARIANT/MODEL, MODEL `scalar` (Renderer) for every variant and, next to it
// in the same run, `wavefront` (WavefrontRenderer) for each chain variant (WavefrontConfig), so
// that bench/run-all pairs them by name; for the default variant also `wavefront-wW`, the
// wavefront renderer shading W paths at once for each width this build's CPU target has
// (1, 8 with AVX2, 16 with AVX-512: glint-render's --simd scalar, avx2 and avx512 do the same
// arithmetic), for bench/run-all's table of shading widths.
//
//   glint-variants-bench [--scenes=DIR] --benchmark_out=variants.json --benchmark_out_format=json
//
// Times are the process's CPU time, not wall time: on a shared machine the wall time of a render
// counts the time other programs held the core (we saw wall times 3x the CPU time under load),
// while CPU time counts only our work (cache and SMT contention still add noise). Both are in
// the JSON output (cpu_time, real_time). Counters, per CPU second: seconds_per_sample and Mrays
// (millions of camera, bounce and shadow rays per second); per frame: samples and rays. One
// worker thread, because a single thread is disturbed less than several on a shared machine.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "glint/glint.hpp"
#include "glint_renderers.hpp"  // the renderers, compiled once in glint-renderers

namespace {

namespace fs = std::filesystem;

// Small enough that the whole study runs in seconds per benchmark, large enough (16 tiles,
// 16k samples) that thread start-up and film allocation are noise.
glint::RenderSettings frame_settings() {
  glint::RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.samples_per_pixel = 4;
  settings.max_depth = 12;
  settings.threads = 1;
  settings.seed = 0;
  return settings;
}

struct NamedScene {
  std::string name;
  glint::Scene scene;
};

/// Renders frames with `Renderer` (Renderer<V> or WavefrontRenderer<V>).
template <typename Renderer>
void render_frames(benchmark::State& state, const glint::Scene& scene) {
  const glint::RenderSettings settings = frame_settings();
  glint::RenderStats stats;
  for (auto _ : state) {
    glint::RenderResult result = Renderer::render(scene, settings);
    benchmark::DoNotOptimize(result.film.pixels().data());
    stats = result.stats;
  }
  // Every frame uses the same seed, so every iteration traces the same rays.
  const double frames = double(state.iterations());
  state.counters["seconds_per_sample"] = benchmark::Counter(
      double(stats.samples) * frames, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // Named so that the console reads "Mrays=12.3/s".
  state.counters["Mrays"] =
      benchmark::Counter(double(stats.rays) * 1e-6 * frames, benchmark::Counter::kIsRate);
  state.counters["samples_per_frame"] = double(stats.samples);
  state.counters["rays_per_frame"] = double(stats.rays);
}

/// Registers render/SCENE/VARIANT/MODEL, rendering with `Renderer`.
template <typename Renderer>
void register_render(const std::string& name, const glint::Scene* scene) {
  benchmark::RegisterBenchmark(
      name.c_str(), [scene](benchmark::State& state) { render_frames<Renderer>(state, *scene); })
      // The renderer's worker thread does the work while this thread waits: the default
      // (this thread's CPU time) would count nothing.
      ->MeasureProcessCPUTime()
      ->Unit(benchmark::kMillisecond);
}

/// Registers PREFIX wavefront-wW for each shading width W up to the default one.
template <glint::NamedVariant V>
void register_widths(const std::string& prefix, const glint::Scene* scene) {
  constexpr int kDefaultWidth = glint::default_shading_width<V>();
  const auto at_width = [&]<int W>() {
    if constexpr (W <= kDefaultWidth)
      register_render<glint::Renderer<V, glint::WavefrontExecution<V, W>>>(
          prefix + "wavefront-w" + std::to_string(W), scene);
  };
  at_width.template operator()<1>();
  at_width.template operator()<8>();
  at_width.template operator()<16>();
}

template <glint::NamedVariant V>
void register_variant(const std::deque<NamedScene>& scenes) {
  const std::string name(V::info.name);
  for (const NamedScene& s : scenes) {
    // A variant that cannot render a scene (uniform_shading on octants) is left out, not
    // failed: the other variants' numbers for that scene are still worth having.
    if (!glint::is_supported<V>(s.scene)) {
      std::fprintf(stderr, "glint-variants-bench: skipping %s on %s: a shading kind it lacks\n",
                   name.c_str(), s.name.c_str());
      continue;
    }
    const std::string prefix = "render/" + s.name + "/" + name + "/";
    register_render<glint::Renderer<V>>(prefix + "scalar", &s.scene);
    if constexpr (glint::WavefrontConfig<V>) {
      register_render<glint::WavefrontRenderer<V>>(prefix + "wavefront", &s.scene);
      if constexpr (std::is_same_v<V, glint::variants::default_variant>)
        register_widths<V>(prefix, &s.scene);
    }
  }
}

fs::path default_scene_directory() {
  return fs::path(__FILE__).parent_path() / "scenes";
}

}  // namespace

int main(int argc, char** argv) {
  fs::path scene_directory = default_scene_directory();
  // Our own flag is taken out before Google Benchmark sees (and rejects) it.
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with("--scenes="))
      scene_directory = arg.substr(std::string_view("--scenes=").size());
    else
      args.push_back(argv[i]);
  }
  int benchmark_argc = static_cast<int>(args.size());
  benchmark::Initialize(&benchmark_argc, args.data());
  if (benchmark::ReportUnrecognizedArguments(benchmark_argc, args.data())) return 2;

  std::vector<fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(scene_directory, error))
    if (entry.path().extension() == ".scene") files.push_back(entry.path());
  if (error || files.empty()) {
    std::fprintf(stderr, "glint-variants-bench: no .scene files in %s (use --scenes=DIR)\n",
                 scene_directory.string().c_str());
    return 1;
  }
  std::sort(files.begin(), files.end());

  // A deque, because the registered benchmarks keep pointers to its scenes.
  std::deque<NamedScene> scenes;
  try {
    for (const fs::path& file : files)
      scenes.push_back({file.stem().string(), glint::Scene::build(glint::read_scene_file(file))});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }

  [&]<typename... V>(std::tuple<V...>*) {
    (register_variant<V>(scenes), ...);
  }(static_cast<glint::compiled::Variants*>(nullptr));
  benchmark::AddCustomContext("frame", "64x64, 4 spp, depth 12, 1 worker thread, seed 0");
  benchmark::AddCustomContext("scenes", scene_directory.string());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
