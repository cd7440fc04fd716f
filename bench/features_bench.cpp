// Each rendering feature's own cost, in isolation: one call of the feature per item, on inputs
// precomputed into arrays and cycled through, so that the compiler can neither fold the work
// into constants nor hoist it out of the loop. Compare alternatives of one feature with each
// other (items per second), not with whole-render figures: here everything sits in L1.
//
//   glint-features-bench --benchmark_min_time=0.1

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/generate/random_scene.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/antialiasing.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/fresnel.hpp"
#include "glint/policy/light_sampling.hpp"
#include "glint/policy/sampler.hpp"
#include "glint/policy/sphere_shading.hpp"
#include "glint/render/estimators/bidirectional.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/render/materials/microfacet_material.hpp"
#include "glint/render/merge_grid.hpp"
#include "glint/scene/emitters.hpp"
#include "glint/scene/environment.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/metals.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/scene_description.hpp"

namespace {

using glint::Vec2;
using glint::Vec3;

// A power of two, so that cycling is a mask; 1024 inputs of a few floats stay in L1 and are
// too many for the branch predictor to memorise.
constexpr std::size_t kInputs = 1024;
constexpr std::size_t kMask = kInputs - 1;

float uniform(glint::Pcg32& rng, float lo, float hi) {
  return lo + (hi - lo) * rng.next_float();
}

Vec3 random_unit_vector(glint::Pcg32& rng) {
  const float z = uniform(rng, -1.0f, 1.0f);
  const float phi = uniform(rng, 0.0f, 2.0f * glint::kPi);
  const float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  return glm::normalize(Vec3(r * std::cos(phi), r * std::sin(phi), z));
}

std::vector<Vec2> random_unit_squares() {
  glint::Pcg32 rng(1, 1);
  std::vector<Vec2> u(kInputs);
  for (Vec2& v : u)
    v = {rng.next_float(), rng.next_float()};
  return u;
}

// ---------------------------------------------------------------------------------------------
// Ray/sphere intersection

/// Rays from a shell around the origin aimed near it, and spheres around the origin: about
/// half the pairs hit, so neither the hit nor the miss branch is predictable.
struct RayInputs {
  std::vector<glint::Ray> rays;
  std::vector<Vec3> centers;
  std::vector<float> radii;

  RayInputs() : rays(kInputs), centers(kInputs), radii(kInputs) {
    glint::Pcg32 rng(2, 2);
    for (std::size_t i = 0; i < kInputs; ++i) {
      const Vec3 origin = 20.0f * random_unit_vector(rng);
      const Vec3 target =
          4.0f * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
      rays[i].origin = origin;
      rays[i].direction = glm::normalize(target - origin);
      centers[i] = Vec3(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3));
      radii[i] = uniform(rng, 0.5f, 3.0f);
    }
  }
};

void BM_IntersectSphere(benchmark::State& state) {
  const RayInputs in;
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    const glint::Ray& ray = in.rays[i & kMask];
    // Pair each ray with a sphere from elsewhere in the array so pairs do not repeat in step.
    const std::size_t s = (i * 7 + 3) & kMask;
    glint::SphereRoots roots{};
    const bool hit =
        glint::intersect_sphere(ray.origin, ray.direction, in.centers[s], in.radii[s], roots);
    benchmark::DoNotOptimize(roots);
    hits += hit;
    ++i;
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_rate"] = double(hits) / double(i);
}
BENCHMARK(BM_IntersectSphere);

/// A set of spheres scattered in a cube, and rays through it.
struct SphereSetInputs {
  glint::SphereSet set;
  std::vector<glint::Ray> rays;

  explicit SphereSetInputs(std::size_t count) : rays(kInputs) {
    glint::Pcg32 rng(3, count);
    const float extent = 2.0f * std::cbrt(float(count));  // keeps density, so hit depths, similar
    for (std::size_t i = 0; i < count; ++i)
      set.add(Vec3(uniform(rng, -extent, extent), uniform(rng, -extent, extent),
                   uniform(rng, -extent, extent)),
              uniform(rng, 0.3f, 1.0f), static_cast<std::uint32_t>(i));
    for (glint::Ray& ray : rays) {
      ray.origin = 3.0f * extent * random_unit_vector(rng);
      const Vec3 target = 0.5f * extent * random_unit_vector(rng);
      ray.direction = glm::normalize(target - ray.origin);
    }
  }
};

void BM_SphereSetScalar(benchmark::State& state) {
  const SphereSetInputs in(static_cast<std::size_t>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    glint::SphereHit hit;
    benchmark::DoNotOptimize(in.set.closest_hit_scalar(in.rays[i++ & kMask], hit));
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["spheres/s"] = benchmark::Counter(
      double(state.iterations()) * double(state.range(0)), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SphereSetScalar)->Arg(8)->Arg(32)->Arg(256);

#ifdef GLINT_AVX2
void BM_SphereSetAvx2(benchmark::State& state) {
  const SphereSetInputs in(static_cast<std::size_t>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    glint::SphereHit hit;
    benchmark::DoNotOptimize(in.set.closest_hit_avx2(in.rays[i++ & kMask], hit));
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["spheres/s"] = benchmark::Counter(
      double(state.iterations()) * double(state.range(0)), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SphereSetAvx2)->Arg(8)->Arg(32)->Arg(256);
#endif

// ---------------------------------------------------------------------------------------------
// Samplers

using Independent = glint::IndependentSampler;
using Stratified = glint::StratifiedSampler;
using Sobol = glint::SobolSampler;
using HybridSobol6 = glint::HybridSobolSampler<6>;

/// What the renderer does for a primary ray: start a pixel sample, draw the antialiasing pair.
/// Pixels and sample indices advance like a tile's loop over a 16 spp image.
template <glint::Sampler S>
void BM_SamplerStartNext2d(benchmark::State& state) {
  S sampler;
  std::uint32_t i = 0;
  for (auto _ : state) {
    sampler.start(glint::PixelSample{(i >> 4) & 63u, i >> 10, i & 15u, 16, 12345});
    benchmark::DoNotOptimize(sampler.next_2d());
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_SamplerStartNext2d, Independent);
BENCHMARK_TEMPLATE(BM_SamplerStartNext2d, Stratified);
BENCHMARK_TEMPLATE(BM_SamplerStartNext2d, Sobol);
BENCHMARK_TEMPLATE(BM_SamplerStartNext2d, HybridSobol6);

/// One start then eight 2D draws, as along a path of several bounces: items are draws, so
/// this is the per-draw cost with start() amortised.
template <glint::Sampler S>
void BM_SamplerPath8x2d(benchmark::State& state) {
  S sampler;
  std::uint32_t i = 0;
  for (auto _ : state) {
    sampler.start(glint::PixelSample{(i >> 4) & 63u, i >> 10, i & 15u, 16, 12345});
    for (int d = 0; d < 8; ++d)
      benchmark::DoNotOptimize(sampler.next_2d());
    ++i;
  }
  state.SetItemsProcessed(state.iterations() * 8);
}
BENCHMARK_TEMPLATE(BM_SamplerPath8x2d, Independent);
BENCHMARK_TEMPLATE(BM_SamplerPath8x2d, Stratified);
BENCHMARK_TEMPLATE(BM_SamplerPath8x2d, Sobol);
BENCHMARK_TEMPLATE(BM_SamplerPath8x2d, HybridSobol6);

/// BM_SamplerPath8x2d for W paths at once in the sampler's lane-wise form, every lane on: items
/// are one path's draws, so the figure compares with BM_SamplerPath8x2d's directly.
template <typename S, int W>
requires glint::WideSamplerStart<S, W>
void BM_SamplerWidePath8x2d(benchmark::State& state) {
  typename S::template Wide<W> samplers;
  const glint::Mask<W> all = glint::Mask<W>{} - 1;
  std::uint32_t i = 0;
  for (auto _ : state) {
    std::uint32_t x[W], y[W], index[W];
    for (int lane = 0; lane < W; ++lane) {
      const std::uint32_t n = i * W + std::uint32_t(lane);
      x[lane] = (n >> 4) & 63u;
      y[lane] = n >> 10;
      index[lane] = n & 15u;
    }
    const glint::PixelSamples<W> s{glint::load<glint::UInt<W>>(x), glint::load<glint::UInt<W>>(y),
                                   glint::load<glint::UInt<W>>(index), 16, 12345};
    samplers.start(all, s);
    for (int d = 0; d < 8; ++d) {
      auto u = samplers.next_2d(all);
      benchmark::DoNotOptimize(u);
    }
    ++i;
  }
  state.SetItemsProcessed(state.iterations() * 8 * W);
}
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, Independent, 8);
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, Independent, 16);
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, Sobol, 8);
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, Sobol, 16);
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, HybridSobol6, 8);
BENCHMARK_TEMPLATE(BM_SamplerWidePath8x2d, HybridSobol6, 16);

// ---------------------------------------------------------------------------------------------
// Diffuse bounce directions

template <glint::DiffuseSampling D>
void BM_HemisphereWarp(benchmark::State& state) {
  const std::vector<Vec2> u = random_unit_squares();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(D::sample(u[i++ & kMask]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_HemisphereWarp, glint::UniformHemisphere);
BENCHMARK_TEMPLATE(BM_HemisphereWarp, glint::CosineHemisphere);

// ---------------------------------------------------------------------------------------------
// Light sampling: a direction towards a sphere emitter, the choice of an emitter, MIS weights

/// Shading points around a lamp of radius 2 at the origin: outside it at distances 3 to 60 (the
/// cone sampling) or, for the inside benchmark, within it (area sampling).
struct EmitterInputs {
  glint::SphereLight lamp{glint::SphereEmitter{Vec3(0.0f), 2.0f, glint::Color(5.0f), 0}};
  std::vector<Vec3> outside, inside;
  std::vector<Vec2> u = random_unit_squares();
  EmitterInputs() : outside(kInputs), inside(kInputs) {
    glint::Pcg32 rng(7, 7);
    for (std::size_t i = 0; i < kInputs; ++i) {
      outside[i] = uniform(rng, 3.0f, 60.0f) * random_unit_vector(rng);
      inside[i] = uniform(rng, 0.0f, 1.9f) * random_unit_vector(rng);
    }
  }
};

void BM_EmitterDirection(benchmark::State& state) {
  const EmitterInputs in;
  const bool from_inside = state.range(0) != 0;
  const std::vector<Vec3>& points = from_inside ? in.inside : in.outside;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        in.lamp.sample_li(points[i & kMask], !from_inside, false, in.u[i & kMask]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmitterDirection)->ArgName("inside")->Arg(0)->Arg(1);

/// Choosing one of N emitters of random radii and radiances by power (a binary search).
void BM_EmitterChoice(benchmark::State& state) {
  glint::Pcg32 rng(8, 8);
  std::vector<glint::SphereEmitter> emitters;
  for (std::uint32_t k = 0; k < std::uint32_t(state.range(0)); ++k)
    emitters.push_back(
        {Vec3(0.0f), uniform(rng, 0.1f, 3.0f), glint::Color(uniform(rng, 1, 20)), k});
  const glint::EmitterTable table(std::move(emitters));
  const std::vector<Vec2> u = random_unit_squares();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(table.choose(u[i++ & kMask].x));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmitterChoice)->ArgName("emitters")->Arg(1)->Arg(64)->Arg(4096);

/// The background: kind 0 the radiance of a constant colour; for a 512x256 image of random
/// texels, kind 1 the radiance in a direction (the map's atan2 twice and a bilinear lookup),
/// kind 2 a direction drawn in proportion to its light (two binary searches and the map back),
/// kind 3 the density of a direction (a bounce's MIS weight needs it).
void BM_Background(benchmark::State& state) {
  glint::Pcg32 rng(9, 9);
  std::vector<glint::Color> texels(512 * 256);
  for (glint::Color& texel : texels)
    texel = glint::Color(uniform(rng, 0, 4), uniform(rng, 0, 4), uniform(rng, 0, 4));
  const glint::Environment constant(glint::Color(0.3f, 0.4f, 0.5f));
  const glint::Environment image(
      std::make_shared<const glint::Texture>("bench", 512, 256, std::move(texels)),
      glint::TexturePlacement{}, 1.0f);
  std::vector<Vec3> directions(kInputs);
  for (Vec3& d : directions)
    d = random_unit_vector(rng);
  const std::vector<Vec2> u = random_unit_squares();
  const int kind = int(state.range(0));
  std::size_t i = 0;
  for (auto _ : state) {
    if (kind == 0)
      benchmark::DoNotOptimize(constant.radiance(directions[i & kMask]));
    else if (kind == 1)
      benchmark::DoNotOptimize(image.radiance(directions[i & kMask]));
    else if (kind == 2)
      benchmark::DoNotOptimize(image.sample(u[i & kMask]));
    else
      benchmark::DoNotOptimize(image.pdf(directions[i & kMask]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Background)->ArgName("kind")->DenseRange(0, 3);

template <glint::MisHeuristic H>
void BM_MisWeight(benchmark::State& state) {
  const std::vector<Vec2> u = random_unit_squares();
  std::size_t i = 0;
  for (auto _ : state) {
    const Vec2& p = u[i++ & kMask];
    benchmark::DoNotOptimize(H::weight(p.x * 10.0f, p.y * 10.0f));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_MisWeight, glint::BalanceHeuristic);
BENCHMARK_TEMPLATE(BM_MisWeight, glint::PowerHeuristic);

// ---------------------------------------------------------------------------------------------
// Fresnel

/// Cosines over the whole range, half entering glass (1 -> 1.5) and half leaving it, where
/// some fall past the critical angle.
struct FresnelInputs {
  std::vector<float> cosines, eta_incident, eta_transmitted;
  FresnelInputs() : cosines(kInputs), eta_incident(kInputs), eta_transmitted(kInputs) {
    glint::Pcg32 rng(4, 4);
    for (std::size_t i = 0; i < kInputs; ++i) {
      cosines[i] = rng.next_float();
      const bool entering = rng.next_u32() & 1u;
      eta_incident[i] = entering ? 1.0f : 1.5f;
      eta_transmitted[i] = entering ? 1.5f : 1.0f;
    }
  }
};

template <glint::Fresnel F>
void BM_Fresnel(benchmark::State& state) {
  const FresnelInputs in;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & kMask;
    benchmark::DoNotOptimize(
        F::reflectance(in.cosines[k], in.eta_incident[k], in.eta_transmitted[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_Fresnel, glint::NoFresnel);
BENCHMARK_TEMPLATE(BM_Fresnel, glint::SchlickFresnel);
BENCHMARK_TEMPLATE(BM_Fresnel, glint::ExactFresnel);

// ---------------------------------------------------------------------------------------------
// Antialiasing jitter

template <glint::Antialiasing A>
void BM_AntialiasingOffset(benchmark::State& state) {
  const std::vector<Vec2> u = random_unit_squares();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(A::offset(u[i++ & kMask], 0.5f));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_AntialiasingOffset, glint::NoAntialiasing);
BENCHMARK_TEMPLATE(BM_AntialiasingOffset, glint::GaussianAntialiasing);
BENCHMARK_TEMPLATE(BM_AntialiasingOffset, glint::BoxAntialiasing);
BENCHMARK_TEMPLATE(BM_AntialiasingOffset, glint::TentAntialiasing);

// ---------------------------------------------------------------------------------------------
// Shading dispatch

/// Directions on the sphere and colours; the kinds argument fixes every sphere's kind, or
/// (-1) mixes the four built-in kinds at random so the switch cannot be predicted. Textured
/// spheres show a 2048x1024 image of random texels, so that lookups miss the caches as a
/// large texture's do.
struct ShadingInputs {
  std::vector<glint::ShadingPoint> points;
  std::vector<glint::Color> colors;
  std::vector<glint::ShadingKind> kinds;
  glint::SphereTexture texture;
  explicit ShadingInputs(int kind)
      : points(kInputs), colors(kInputs), kinds(kInputs), texture(random_texture(), {}) {
    glint::Pcg32 rng(5, 5);
    for (std::size_t i = 0; i < kInputs; ++i) {
      colors[i] = glint::Color(rng.next_float(), rng.next_float(), rng.next_float());
      kinds[i] = static_cast<glint::ShadingKind>(kind >= 0 ? kind : int(rng.next_u32() % 4));
      points[i] = {random_unit_vector(rng),
                   kinds[i] == glint::ShadingKind::texture ? &texture : nullptr};
    }
  }
  static std::shared_ptr<const glint::Texture> random_texture() {
    constexpr int kWidth = 2048, kHeight = 1024;
    glint::Pcg32 rng(6, 6);
    std::vector<glint::Color> texels(std::size_t(kWidth) * kHeight);
    for (glint::Color& texel : texels)
      texel = glint::Color(rng.next_float(), rng.next_float(), rng.next_float());
    return std::make_shared<const glint::Texture>("random", kWidth, kHeight, std::move(texels));
  }
};

template <glint::SphereShading H>
void BM_Shading(benchmark::State& state) {
  const ShadingInputs in(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & kMask;
    benchmark::DoNotOptimize(H::color(in.kinds[k], in.colors[k], in.points[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
// UniformShading supports the uniform kind only; BuiltinShading: 0 uniform, 1 octants,
// 2 checker, 3 texture, -1 a random mix.
BENCHMARK_TEMPLATE(BM_Shading, glint::UniformShading)->ArgName("kind")->Arg(0);
BENCHMARK_TEMPLATE(BM_Shading, glint::BuiltinShading)
    ->ArgName("kind")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Arg(-1);

// ---------------------------------------------------------------------------------------------
// Mirror lobes: what a rough or metal mirror costs a hit against the ideal mirror

enum MirrorKind {
  kReportMirror = 0,  // the report's material (ReportMaterial)
  kIdealMirror = 1,   // the same mirror through the microfacet material
  kSmoothGold = 2,
  kRoughMirror = 3,
  kRoughGold = 4,
};

/// Hits on a unit sphere's top (in air) of material `m`: from directions spread over the
/// hemisphere above, each with a light direction above the surface, or, `both_sides`, over the
/// whole sphere (half of them from inside) with light directions anywhere.
struct LobeInputs {
  glint::SurfaceProperties surface;
  std::vector<glint::SurfaceInteraction> hits;
  std::vector<Vec3> incoming, lights;
  LobeInputs(const glint::Material& m, bool both_sides)
      : hits(kInputs), incoming(kInputs), lights(kInputs) {
    surface = {m,
               Vec3(0.0f),
               1.0f,
               glint::ShadingKind::uniform,
               m.is_fully_transparent(),
               m.has_mirror_finish(),
               glint::kNotAnEmitter};
    glint::Pcg32 rng(6, 6);
    const Vec3 normal(0.0f, 0.0f, 1.0f);
    for (std::size_t i = 0; i < kInputs; ++i) {
      Vec3 d = random_unit_vector(rng);
      incoming[i] = d.z > 0.0f && !both_sides ? -d : d;
      const Vec3 l = random_unit_vector(rng);
      lights[i] = l.z < 0.0f && !both_sides ? -l : l;
      glint::SurfaceInteraction& it = hits[i];
      it.point = normal;
      it.outward_normal = normal;
      it.sphere = 0u;
      glint::detail::set_surface_lane(it.surface, 0, surface);
      it.at = glint::detail::interface_at(incoming[i], normal);
    }
  }
};

glint::Material mirror_of_kind(MirrorKind kind) {
  glint::Material m;
  m.diffuse = 0.0f;
  m.mirror = 1.0f;
  if (kind == kSmoothGold || kind == kRoughGold) {
    const glint::Metal gold = *glint::metal_named("gold");
    m.metal_eta = gold.eta;
    m.metal_k = gold.k;
  }
  if (kind == kRoughMirror || kind == kRoughGold) m.mirror_roughness = 0.4f;
  return m;
}

using MirrorConfig =
    glint::Config<glint::IndependentSampler, glint::PathTracing, glint::ExactFresnel,
                  glint::GaussianAntialiasing, glint::BuiltinShading, glint::CosineHemisphere,
                  glint::RussianRoulette, glint::PointLightsOnly, glint::MicrofacetMaterialModel>;

/// A hit's material built, a direction sampled, and a light direction's value and density: the
/// material's share of a path's step.
template <typename B>
void run_material_lobe(benchmark::State& state, const LobeInputs& in) {
  glint::IndependentSampler sampler;
  sampler.start({1u, 1u, 0u, 1u, 1u});
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & kMask;
    const B bsdf(in.hits[k], in.incoming[k]);
    const glint::ScatterSample s = bsdf.sample(sampler);
    benchmark::DoNotOptimize(s);
    benchmark::DoNotOptimize(bsdf.evaluate(in.lights[k]));
    benchmark::DoNotOptimize(bsdf.pdf(in.lights[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
void BM_MirrorLobe(benchmark::State& state) {
  const auto kind = static_cast<MirrorKind>(state.range(0));
  const LobeInputs in(mirror_of_kind(kind), false);
  if (kind == kReportMirror)
    run_material_lobe<glint::ReportMaterial<MirrorConfig, float>>(state, in);
  else
    run_material_lobe<glint::MicrofacetMaterial<MirrorConfig, float>>(state, in);
}
// 0 the report's mirror, 1 the same through the microfacet material, 2 polished gold, 3 a rough
// mirror (roughness 0.4), 4 rough gold.
BENCHMARK(BM_MirrorLobe)->ArgName("kind")->DenseRange(0, 4);

// ---------------------------------------------------------------------------------------------
// Glass lobes: what a rough interface costs a hit against the ideal one

enum GlassKind {
  kReportGlass = 0,  // the report's material (ReportMaterial)
  kIdealGlass = 1,   // the same glass through the microfacet material
  kRoughGlass = 2,   // transparent_roughness 0.3
};

void BM_GlassLobe(benchmark::State& state) {
  const auto kind = static_cast<GlassKind>(state.range(0));
  glint::Material m;
  m.diffuse = 0.0f;
  m.transparent = 1.0f;
  if (kind == kRoughGlass) m.transparent_roughness = 0.3f;
  const LobeInputs in(m, true);
  if (kind == kReportGlass)
    run_material_lobe<glint::ReportMaterial<MirrorConfig, float>>(state, in);
  else
    run_material_lobe<glint::MicrofacetMaterial<MirrorConfig, float>>(state, in);
}
// 0 the report's glass (index 1.5, from both sides), 1 the same through the microfacet material,
// 2 frosted glass (roughness 0.3).
BENCHMARK(BM_GlassLobe)->ArgName("kind")->DenseRange(0, 2);

// ---------------------------------------------------------------------------------------------
// Inclusion tree

glint::SphereDescription glass_sphere(Vec3 center, float radius, int line) {
  glint::SphereDescription s;
  s.center = center;
  s.radius = radius;
  s.material.diffuse = 0.0f;
  s.material.transparent = 1.0f;
  s.material.ior = 1.5f;
  s.line = line;
  return s;
}

enum InclusionKind { kDisjoint = 0, kConcentric = 1, kRandom = 2 };

/// Glass beads on a grid in a plane (disjoint), concentric glass shells (every pair nested: the
/// reference builder's worst case, n^2/2 pairs), or a random scene of the generator (half of it
/// glass, some of it nested, walls included) as dense as its million-sphere example.
glint::SceneDescription inclusion_scene(std::size_t count, InclusionKind kind) {
  if (kind == kRandom) {
    glint::RandomSceneParameters parameters;
    parameters.sphere_count = static_cast<int>(count);
    parameters.domain_size = 2000.0f * static_cast<float>(std::cbrt(double(count) / 1e6));
    parameters.min_radius = 1.0f;
    parameters.max_radius = 8.0f;
    return glint::generate_random_scene(parameters).scene;
  }
  glint::SceneDescription scene;
  scene.spheres.reserve(count);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(double(count))));
  for (std::size_t i = 0; i < count; ++i) {
    if (kind == kConcentric)
      scene.spheres.push_back(glass_sphere(Vec3(0.0f), 1.0f + float(i), int(i) + 1));
    else
      scene.spheres.push_back(glass_sphere(
          Vec3(3.0f * float(i % side), 3.0f * float(i / side), 0.0f), 1.0f, int(i) + 1));
  }
  return scene;
}

/// build_inclusion_tree (builder 0: the reference's loop while pairs are few, then the fast
/// builder), build_inclusion_tree_reference (1), or the fast builder alone (2).
void BM_InclusionTreeBuild(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const auto kind = static_cast<InclusionKind>(state.range(1));
  const auto builder = state.range(2);
  const glint::SceneDescription scene = inclusion_scene(count, kind);
  for (auto _ : state) {
    glint::InclusionTree tree = builder == 1   ? glint::build_inclusion_tree_reference(scene)
                                : builder == 2 ? *glint::detail::build_inclusion_tree_fast(scene)
                                               : glint::build_inclusion_tree(scene);
    benchmark::DoNotOptimize(tree.outside_ior.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(scene.spheres.size()));
  state.SetLabel(std::string(kind == kRandom       ? "random"
                             : kind == kConcentric ? "concentric"
                                                   : "disjoint") +
                 (builder == 1   ? ", reference"
                  : builder == 2 ? ", fast builder alone"
                                 : ""));
}
BENCHMARK(BM_InclusionTreeBuild)
    ->ArgNames({"spheres", "kind", "builder"})
    ->ArgsProduct({{100, 1000, 10000}, {kDisjoint}, {0, 1, 2}})
    ->ArgsProduct({{100, 1000, 10000, 30000}, {kConcentric}, {0, 1, 2}})
    ->ArgsProduct({{100000}, {kRandom}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------------------------
// Whole-scene queries: the SIMD set alone (up to 64 spheres) or the BVH (more)

/// A random scene of the generator (walls included) whose cube grows with the sphere count so
/// that the density, and so the free path of a ray, stays that of 40 spheres of radius 1 to 4
/// in a cube of side 80; rays start at random points of the cube in random directions.
struct SceneInputs {
  glint::Scene scene;
  std::vector<glint::Ray> rays;

  explicit SceneInputs(int count) : scene(build(count)), rays(kInputs) {
    glint::Pcg32 rng(3, 3);
    const float half = 0.5f * domain_size(count);
    for (glint::Ray& ray : rays) {
      ray.origin =
          Vec3(uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half));
      ray.direction = random_unit_vector(rng);
    }
  }

  static float domain_size(int count) { return 80.0f * std::cbrt(float(count) / 40.0f); }

  static glint::RandomSceneParameters parameters(int count) {
    glint::RandomSceneParameters parameters;
    parameters.sphere_count = count;
    parameters.domain_size = domain_size(count);
    parameters.min_radius = 1.0f;
    parameters.max_radius = 4.0f;
    parameters.seed = 7;
    return parameters;
  }

  static glint::Scene build(int count) {
    return glint::Scene::build(glint::generate_random_scene(parameters(count)).scene);
  }
};

void BM_SceneClosestHit(benchmark::State& state) {
  const SceneInputs in(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.scene.closest_hit(in.rays[i++ & kMask]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SceneClosestHit)->ArgName("spheres")->Arg(40)->Arg(1000)->Arg(100000)->Arg(1000000);

/// Shadow rays: the same rays cut to the length of a typical light distance (a quarter of the
/// cube), of which a third to three quarters are blocked.
void BM_SceneOccluded(benchmark::State& state) {
  SceneInputs in(static_cast<int>(state.range(0)));
  const float length = 0.25f * SceneInputs::domain_size(static_cast<int>(state.range(0)));
  for (glint::Ray& ray : in.rays)
    ray.t_max = length;
  std::size_t i = 0, blocked = 0;
  for (auto _ : state) {
    const bool occluded = in.scene.occluded(in.rays[i++ & kMask]);
    benchmark::DoNotOptimize(occluded);
    blocked += occluded;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["blocked"] = double(blocked) / double(i);
}
BENCHMARK(BM_SceneOccluded)->ArgName("spheres")->Arg(40)->Arg(1000)->Arg(100000);

// ---------------------------------------------------------------------------------------------
// Batched queries: eight rays at once (Scene::closest_hits, occluded) against eight single-ray
// queries, on the same scenes as above, for camera rays (4 x 2 pixel blocks of a 256 x 256
// image from the scene's camera, each block an 8-ray batch) and the random rays above.

constexpr int kBatch = glint::RayBatch::kWidth;

enum BatchRays { kCameraRays = 0, kRandomRays = 1 };
enum BatchMode { kEightSingle = 0, kBatched = 1 };

struct BatchInputs {
  SceneInputs in;
  std::vector<glint::RayBatch> batches;

  BatchInputs(int count, int kind, bool shadow) : in(count), batches(kInputs / kBatch) {
    glint::Pcg32 rng(5, 5);
    const glint::CameraDescription& camera = in.scene.camera();
    const Vec3 forward = glm::normalize(camera.look_at - camera.position);
    const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const Vec3 up = glm::cross(right, forward);
    const float half_height = std::tan(0.5f * camera.fov_degrees * glint::kPi / 180.0f);
    const float size = SceneInputs::domain_size(count);
    constexpr int kImage = 256;
    for (std::size_t b = 0; b < batches.size(); ++b) {
      glint::RayBatch& batch = batches[b];
      batch.heads_into_origin_sphere = 0;
      const int x0 = int(rng.next_u32() % (kImage / 4)) * 4,
                y0 = int(rng.next_u32() % (kImage / 2)) * 2;
      for (int lane = 0; lane < kBatch; ++lane) {
        glint::Ray ray;
        if (kind == kCameraRays) {
          const float u = (float(x0 + lane % 4) + 0.5f) / kImage * 2.0f - 1.0f;
          const float v = (float(y0 + lane / 4) + 0.5f) / kImage * 2.0f - 1.0f;
          ray.origin = camera.position;
          ray.direction = glm::normalize(forward + half_height * (u * right + v * up));
          // Shadow rays: as far as the middle of the spheres.
          if (shadow) ray.t_max = glm::length(camera.look_at - camera.position);
        } else {
          ray = in.rays[kBatch * b + std::size_t(lane)];
          if (shadow) ray.t_max = 0.25f * size;
        }
        batch.set(lane, ray);
      }
    }
  }
};

void BM_SceneBatchClosestHit(benchmark::State& state) {
  const BatchInputs inputs(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           false);
  const bool batched = state.range(2) == kBatched;
  std::size_t i = 0;
  glint::HitBatch hits;
  for (auto _ : state) {
    const glint::RayBatch& batch = inputs.batches[i++ & (kMask / kBatch)];
    if (batched) {
      benchmark::DoNotOptimize(
          inputs.in.scene.closest_hits(batch, glint::RayBatch::kAllLanes, hits));
      benchmark::ClobberMemory();
    } else {
      for (int lane = 0; lane < kBatch; ++lane)
        benchmark::DoNotOptimize(inputs.in.scene.closest_hit(batch.get(lane)));
    }
  }
  state.SetItemsProcessed(kBatch * state.iterations());
}
BENCHMARK(BM_SceneBatchClosestHit)
    ->ArgNames({"spheres", "random", "batched"})
    ->ArgsProduct({{40, 10000, 100000}, {kCameraRays, kRandomRays}, {kEightSingle, kBatched}});

void BM_SceneBatchOccluded(benchmark::State& state) {
  const BatchInputs inputs(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           true);
  const bool batched = state.range(2) == kBatched;
  std::size_t i = 0;
  for (auto _ : state) {
    const glint::RayBatch& batch = inputs.batches[i++ & (kMask / kBatch)];
    if (batched) {
      benchmark::DoNotOptimize(inputs.in.scene.occluded(batch, glint::RayBatch::kAllLanes));
    } else {
      for (int lane = 0; lane < kBatch; ++lane)
        benchmark::DoNotOptimize(inputs.in.scene.occluded(batch.get(lane)));
    }
  }
  state.SetItemsProcessed(kBatch * state.iterations());
}
BENCHMARK(BM_SceneBatchOccluded)
    ->ArgNames({"spheres", "random", "batched"})
    ->ArgsProduct({{40, 10000, 100000}, {kCameraRays, kRandomRays}, {kEightSingle, kBatched}});

// ---------------------------------------------------------------------------------------------
// The linear scan or the BVH: Scene's batched queries on one scene built both ways
// (Scene::build's linear_scene_size), for the rays of a renderer: 4 x 2 pixel blocks of camera
// rays, the diffuse bounces from their hits (one batch per block, each ray leaving the sphere it
// hit) for closest_hits, and from the same hits the shadow rays toward the scene's first point
// light, or else the centre of its first emissive sphere, for occluded. Scene::kLinearSceneSize
// is set where the linear scan stops beating the BVH on random scenes.

enum Accelerator { kBvh = 0, kLinear = 1 };
enum Query { kClosestHits = 0, kOccluded = 1 };

struct RendererRays {
  glint::Scene scene;
  std::vector<glint::RayBatch> closest;  ///< camera and bounce batches, in turn
  std::vector<glint::RayBatch> shadow;

  RendererRays(const glint::SceneDescription& description, Accelerator accelerator)
      : scene(glint::Scene::build(description,
                                  accelerator == kLinear ? description.spheres.size() : 0)) {
    Vec3 target = description.camera.look_at;
    float target_radius = 0.0f;
    if (!description.lights.empty()) {
      target = description.lights.front().position;
    } else {
      for (const glint::SphereDescription& sphere : description.spheres)
        if (sphere.material.is_emissive()) {
          target = sphere.center;
          target_radius = sphere.radius;
          break;
        }
    }
    const glint::CameraDescription& camera = description.camera;
    const Vec3 forward = glm::normalize(camera.look_at - camera.position);
    const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const Vec3 up = glm::cross(right, forward);
    const float half_height = std::tan(0.5f * camera.fov_degrees * glint::kPi / 180.0f);
    constexpr int kImage = 128;
    glint::Pcg32 rng(9, 9);
    for (int y0 = 0; y0 < kImage; y0 += 2)
      for (int x0 = 0; x0 < kImage; x0 += kBatch / 2) {
        glint::RayBatch camera_rays, bounces, shadow_rays;
        for (int lane = 0; lane < kBatch; ++lane) {
          glint::Ray ray;
          const float u = (float(x0 + lane % (kBatch / 2)) + 0.5f) / kImage * 2.0f - 1.0f;
          const float v = 1.0f - (float(y0 + lane / (kBatch / 2)) + 0.5f) / kImage * 2.0f;
          ray.origin = camera.position;
          ray.direction = glm::normalize(forward + half_height * (u * right + v * up));
          camera_rays.set(lane, ray);
          glint::Ray bounce = ray, shadow_ray = ray;
          if (const std::optional<glint::SphereHit> hit = scene.closest_hit(ray)) {
            const glint::SurfaceHit surface = scene.surface_hit(ray, *hit);
            Vec3 direction = random_unit_vector(rng);
            if (glm::dot(direction, surface.outward_normal) < 0.0f) direction = -direction;
            bounce = glint::ray_leaving_sphere(surface.point, direction, hit->sphere, false);
            const Vec3 to_target = target - surface.point;
            const float distance = glm::length(to_target);
            shadow_ray =
                glint::ray_leaving_sphere(surface.point, to_target / distance, hit->sphere,
                                          surface.outward_normal, distance - target_radius);
          }
          bounces.set(lane, bounce);
          shadow_rays.set(lane, shadow_ray);
        }
        closest.push_back(camera_rays);
        closest.push_back(bounces);
        shadow.push_back(shadow_rays);
      }
  }
};

void run_linear_or_bvh(benchmark::State& state, const glint::SceneDescription& description) {
  const RendererRays rays(description, static_cast<Accelerator>(state.range(1)));
  const bool occluded = state.range(2) == kOccluded;
  const std::vector<glint::RayBatch>& batches = occluded ? rays.shadow : rays.closest;
  std::size_t i = 0;
  glint::HitBatch hits;
  for (auto _ : state) {
    const glint::RayBatch& batch = batches[i++ % batches.size()];
    if (occluded) {
      benchmark::DoNotOptimize(rays.scene.occluded(batch, glint::RayBatch::kAllLanes));
    } else {
      benchmark::DoNotOptimize(rays.scene.closest_hits(batch, glint::RayBatch::kAllLanes, hits));
      benchmark::ClobberMemory();
    }
  }
  state.SetItemsProcessed(kBatch * state.iterations());
  state.SetLabel(std::to_string(description.spheres.size()) + " spheres");
}

/// A random scene of the generator (SceneInputs: walls and two point lights included).
void BM_LinearOrBvhRandom(benchmark::State& state) {
  run_linear_or_bvh(
      state, glint::generate_random_scene(SceneInputs::parameters(static_cast<int>(state.range(0))))
                 .scene);
}
BENCHMARK(BM_LinearOrBvhRandom)
    ->ArgNames({"spheres", "linear", "occluded"})
    ->ArgsProduct({{16, 32, 48, 64, 80, 96, 112, 128, 160, 192, 256, 384, 512},
                   {kBvh, kLinear},
                   {kClosestHits, kOccluded}});

const char* const kBenchScenes[] = {"cornell", "lamp-room", "many-lamps", "nested-glass",
                                    "random40"};

/// A scene of bench/scenes (the argument indexes kBenchScenes).
void BM_LinearOrBvhBenchScene(benchmark::State& state) {
  const std::string name = kBenchScenes[state.range(0)];
  run_linear_or_bvh(state, glint::read_scene_file(std::string(GLINT_SOURCE_DIR) + "/bench/scenes/" +
                                                  name + ".scene"));
  state.SetLabel(name);
}
BENCHMARK(BM_LinearOrBvhBenchScene)
    ->ArgNames({"scene", "linear", "occluded"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {kBvh, kLinear}, {kClosestHits, kOccluded}});

#ifdef GLINT_AVX2
/// The hierarchy alone (the scene's spheres but its walls), packet or one traversal per lane,
/// whatever same_octant would choose: what the choice is made on.
void BM_BvhBatch(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const BatchInputs inputs(count, static_cast<int>(state.range(1)), state.range(3) == 1);
  const glint::SceneDescription description =
      glint::generate_random_scene(SceneInputs::parameters(count)).scene;
  std::vector<glint::SphereBvh::Input> spheres;
  for (std::size_t s = 0; s < description.spheres.size(); ++s)
    if (description.spheres[s].radius <= 4.0f)
      spheres.push_back(
          {description.spheres[s].center, description.spheres[s].radius, std::uint32_t(s)});
  const glint::SphereBvh bvh(std::move(spheres));
  const bool packet = state.range(2) == 1;
  const bool any = state.range(3) == 1;
  std::size_t i = 0;
  for (auto _ : state) {
    const glint::RayBatch& batch = inputs.batches[i++ & (kMask / kBatch)];
    if (any) {
      benchmark::DoNotOptimize(packet ? bvh.any_hits_packet(batch, glint::RayBatch::kAllLanes)
                                      : bvh.any_hits_per_lane(batch, glint::RayBatch::kAllLanes));
    } else {
      glint::SphereHit hits[kBatch];
      benchmark::DoNotOptimize(
          packet ? bvh.closest_hits_packet(batch, glint::RayBatch::kAllLanes, hits)
                 : bvh.closest_hits_per_lane(batch, glint::RayBatch::kAllLanes, hits));
      benchmark::ClobberMemory();
    }
  }
  state.SetItemsProcessed(kBatch * state.iterations());
}
BENCHMARK(BM_BvhBatch)
    ->ArgNames({"spheres", "random", "packet", "occluded"})
    ->ArgsProduct({{10000, 100000}, {kCameraRays, kRandomRays}, {0, 1}, {0, 1}});
#endif

// ---------------------------------------------------------------------------------------------
// Vertex merging's grid

/// Indexing a pass's merge candidates (MergeGrid::build_grid: gathering the chunks, then the
/// in-place sort by bucket) for N candidates on a floor and a ball, three per light path, about
/// one per bucket. Unlike the rest of this file, memory-bound: N x 44 bytes, sorted in place.
void BM_MergeGridBuild(benchmark::State& state) {
  const std::size_t paths = std::size_t(state.range(0)) / 3;
  glint::MergeGrid<glint::MergeCandidate> grid(paths);
  for (auto _ : state) {
    state.PauseTiming();
    for (std::size_t chunk = 0; chunk < grid.chunk_count(); ++chunk)
      grid.fill_chunk(chunk, [](std::size_t path, auto& candidates) {
        glint::Pcg32 rng(path, 7);
        for (int k = 0; k < 3; ++k) {
          glint::MergeCandidate candidate{};
          const float u = rng.next_float(), v = rng.next_float();
          if (k == 0) {
            candidate.point = Vec3(40.0f * u - 20.0f, -10.0f, 40.0f * v - 20.0f);
          } else {
            const float z = 2.0f * u - 1.0f, r = std::sqrt(1.0f - z * z), a = 6.2831853f * v;
            candidate.point = 10.0f * Vec3(r * std::cos(a), r * std::sin(a), z);
          }
          candidates.push_back(candidate);
        }
      });
    state.ResumeTiming();
    grid.build_grid(0.02f);
    benchmark::DoNotOptimize(grid.candidate_count());
  }
  state.SetItemsProcessed(std::int64_t(3 * paths) * state.iterations());
}
BENCHMARK(BM_MergeGridBuild)
    ->ArgName("candidates")
    ->Arg(1 << 16)
    ->Arg(3 << 20)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
