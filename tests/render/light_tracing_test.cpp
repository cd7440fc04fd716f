// Light tracing (render/light_tracing_execution.hpp) in whole renders: the same bits whatever
// the threads, tiles and passes; the same image as the path tracer wherever both see all the
// light (a diffuse room under lamps, and a diffuse ball seen from inside the glass that holds it,
// which checks the adjoint scaling at refraction); and a point light's caustic under a glass
// ball against the irradiance a deterministic fan of rays through the ball gives, worked out in
// the test with its own ray-sphere and Fresnel arithmetic.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "block_statistics.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

using glint::Color;
using glint::Vec2;

namespace light_tracing_test {

// The report's material, one lobe per vertex, fixed depth: light tracing follows the Config's
// policies, and the path tracer compared with it is the same Config's chain.
using Chain = glint::variants::report::with_estimator<glint::PathTracing>;
template <typename C>
using LightTracing = glint::Renderer<C, glint::LightTracingExecution<C>>;
/// The path tracer the light tracer is compared with: Chain's image, with less noise per sample
/// (cosine bounces, emitter sampling with MIS).
using PathReference = Chain::with_diffuse_sampling<glint::CosineHemisphere>::with_light_sampling<
    glint::EmitterSampling<glint::PowerHeuristic>>;

glint::Scene build(const std::string& text, const char* label) {
  return glint::Scene::build(glint::read_scene_text(text, label));
}

// A closed diffuse room lit by a lamp near the ceiling that the camera does not see and a
// small one it does, with diffuse balls (one patterned): everything the camera sees is diffuse
// or a lamp, so light tracing sees all the light the path tracer does.
constexpr const char* kRoom = R"(
image     width=16 height=16 spp=64 max_depth=3
camera    position=0,0,30 look_at=0,-4,0 up=0,1,0 fov=50
antialias sigma=0.5
sphere    center=-100016,0,0 radius=1e5 color=0.8,0.3,0.3
sphere    center=100016,0,0 radius=1e5 color=0.3,0.3,0.8
sphere    center=0,-100010,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,100016,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,-100016 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,100040 radius=1e5 color=0.5,0.5,0.5
sphere    center=0,13,-6 radius=2.5 diffuse=0 emission=20,18,14
sphere    center=7,-7,-4 radius=1 diffuse=0 emission=10,10,20
sphere    center=-5,-6,-2 radius=4 color=0.9,0.8,0.3
sphere    center=4,-7,4 radius=3 color=0.5,0.5,0.5 shading=checker
)";

// A diffuse ball seen from inside the glass sphere that holds it and the camera: every pixel
// sees the ball, lit through the glass by a room around it and the lamp near its ceiling.
constexpr const char* kInsideGlass = R"(
image     width=16 height=16 spp=256 max_depth=6
camera    position=0,0,10 look_at=0,0,0 up=0,1,0 fov=36
antialias sigma=0.5
sphere    center=0,0,0 radius=12 diffuse=0 transparent=1 ior=1.5
sphere    center=0,0,0 radius=5 color=0.8,0.8,0.8
sphere    center=0,17,0 radius=2 diffuse=0 emission=50,50,50
sphere    center=-100020,0,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=100020,0,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,-100020,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,100020,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,-100020 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,100020 radius=1e5 color=0.7,0.7,0.7
)";

TEST_CASE("light tracing: the same bits for any threads, tiles and passes, and after a resume",
          "[render][light]") {
  const glint::Scene scene = build(R"(
image     width=23 height=17 spp=5 max_depth=4
camera    position=0,0,20 look_at=0,0,0 up=0,1,0 fov=50
antialias sigma=0.5
light     position=0,9,5 intensity=300
sphere    center=0,-100008,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=-3,-3,0 radius=3 diffuse=0 transparent=1 ior=1.5
sphere    center=4,-4,-2 radius=2 mirror=0.5 diffuse=0.5
sphere    center=0,6,-4 radius=1 diffuse=0 emission=5,5,5
)",
                                   "mixed");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 7;
  std::vector<glint::Film> films;
  for (const auto& [threads, tile, pass] :
       std::vector<std::array<int, 3>>{{1, 16, 32}, {2, 7, 1}, {5, 3, 2}}) {
    settings.threads = threads;
    settings.tile_size = tile;
    settings.max_pass_samples = pass;
    const glint::RenderResult result = LightTracing<Chain>::render(scene, settings);
    REQUIRE(result.complete());
    CHECK(result.stats.invalid_samples == 0);
    films.push_back(result.film);
  }
  double total = 0.0;
  for (const Color& c : films[0].pixels())
    total += c.r + c.g + c.b;
  CHECK(total > 0.0);
  for (std::size_t i = 1; i < films.size(); ++i)
    CHECK(films[i].pixels() == films[0].pixels());

  // Stopped after two passes of one sample, its sums (splats included) kept, and resumed from
  // them on another thread count: the uninterrupted render's bits.
  settings.max_pass_samples = 1;
  settings.threads = 2;
  glint::RenderControl stop_early;
  stop_early.keep_sums = true;
  stop_early.pass_done = [](const glint::PassReport& report) { return report.passes_done < 2; };
  const glint::RenderResult first = LightTracing<Chain>::render(scene, settings, stop_early);
  REQUIRE(first.passes_done == 2);
  REQUIRE(first.sums.has_splats());
  settings.threads = 3;
  const glint::RenderResult resumed = LightTracing<Chain>::render(
      scene, settings, {}, glint::RenderStart{&first.sums, first.passes_done});
  REQUIRE(resumed.complete());
  CHECK(resumed.film.pixels() == films[0].pixels());
}

TEST_CASE("light tracing: agrees with the path tracer where the camera sees diffuse surfaces",
          "[render][light][statistical]") {
  glint_test::ComparisonFamily family;
  for (const auto& [text, name] : {std::pair{kRoom, "room"}, {kInsideGlass, "inside glass"}}) {
    const glint::Scene scene = build(text, name);
    const glint::RenderSettings settings = glint::RenderSettings::from(scene);
    // The scenes' samples per pixel are light tracing's.
    glint::RenderSettings path_settings = settings;
    path_settings.samples_per_pixel = 64;
    const double lit = glint_test::compare_independent(
        family, std::string(name) + ", light tracing against path tracing",
        glint_test::render_blocks<glint::Renderer<PathReference>>(scene, 100, path_settings),
        glint_test::render_blocks<LightTracing<Chain>>(scene, 200, settings));
    CHECK(lit > 0.01);
  }
  family.check();
}

TEST_CASE("light tracing: refuses what it cannot render, and checkpoints of its sums",
          "[render][light]") {
  const glint::Scene scene = build(kRoom, "room");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.antialias_sigma = 0.0f;
  CHECK_THROWS_AS(LightTracing<Chain>::render(scene, settings), glint::SettingsError);
  settings = glint::RenderSettings::from(scene);
  CHECK_THROWS_AS(
      LightTracing<glint::variants::no_antialiasing::with_estimator<glint::PathTracing>>::render(
          scene, settings),
      glint::SettingsError);

  const glint::Scene sky = build(R"(
camera     position=0,0,10 look_at=0,0,0 up=0,1,0 fov=50
background color=0.2,0.3,0.5
light      position=0,5,5 intensity=10
sphere     center=0,0,0 radius=2
)",
                                 "sky");
  CHECK_THROWS_AS(LightTracing<Chain>::render(sky, glint::RenderSettings::from(sky)),
                  glint::UnsupportedSceneError);

  // A start from sums without splats is refused; sums with splats go through a checkpoint and
  // back, and the render resumed from them is the uninterrupted one, bit for bit.
  const glint::PixelSums plain(settings.width, settings.height);
  CHECK_THROWS_AS(LightTracing<Chain>::render(scene, settings, {}, glint::RenderStart{&plain, 1}),
                  glint::SettingsError);
  settings.samples_per_pixel = 8;
  glint::RenderControl stop_early;
  stop_early.keep_sums = true;
  stop_early.pass_done = [](const glint::PassReport& report) { return report.passes_done < 3; };
  const glint::RenderResult first = LightTracing<Chain>::render(scene, settings, stop_early);
  REQUIRE(first.passes_done == 3);
  REQUIRE(first.sums.has_splats());
  const glint::Checkpoint back = glint::decode_checkpoint(
      glint::encode_checkpoint(glint::CheckpointKey::of(1, "light", settings), first.passes_done,
                               first.samples_per_pixel, first.sums),
      "ck");
  REQUIRE(back.sums.has_splats());
  CHECK(back.sums.splats().words() == first.sums.splats().words());
  const glint::RenderResult resumed = LightTracing<Chain>::render(
      scene, settings, {}, glint::RenderStart{&back.sums, back.passes_done});
  const glint::RenderResult whole = LightTracing<Chain>::render(scene, settings);
  REQUIRE(resumed.complete());
  CHECK(resumed.film.pixels() == whole.film.pixels());
}

// The named variant: `fast`'s policies (Sobol' samples, cosine bounces, Russian roulette)
// followed from the lights, compiled in glint-renderers. Inside a closed diffuse sphere of radius
// R and albedo rho with a point light of intensity I at its centre, every point of the wall has
// the radiance rho I / (pi R^2) (1 - rho^(n+1)) / (1 - rho) after at most n bounces (the series
// of tests/render/analytic_sphere_test.cpp), and so has every pixel.
TEST_CASE(
    "light tracing (variant light_tracing): a lit closed diffuse sphere shows "
    "rho I / (pi R^2) (1 - rho^(n+1)) / (1 - rho)",
    "[render][light][statistical]") {
  using Variant = glint::variants::light_tracing;
  const glint::Scene scene = build(R"(
camera    position=0,0,3 look_at=0,0,-10 up=0,1,0 fov=90
antialias sigma=0.5
light     position=0,0,0 intensity=400
sphere    center=0,0,0 radius=10 color=1,1,1 diffuse=0.5
)",
                                   "lit sphere");
  REQUIRE(glint::is_supported<Variant>(scene));
  const double rho = 0.5, intensity = 400.0, radius = 10.0;
  glint_test::ComparisonFamily family;
  for (const int depth : {0, 2, 40}) {
    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    settings.samples_per_pixel = 16;
    settings.max_depth = depth;
    const glint_test::BlockSamples blocks = glint_test::render_blocks<glint::Renderer<Variant>>(
        scene, 300 + std::uint64_t(depth), settings);
    // Three channels, each the same radiance.
    const double expected = 3.0 * rho * intensity / (M_PI * radius * radius) *
                            (1.0 - std::pow(rho, depth + 1)) / (1.0 - rho);
    for (std::size_t b = 0; b <= glint_test::kBlocks; ++b) {
      std::vector<double> error;
      for (const double v : blocks.per_seed[b])
        error.push_back(v - expected);
      const glint_test::MeanEstimate e = glint_test::estimate_mean(error);
      std::ostringstream line;
      line << "max depth " << depth << ", " << glint_test::block_name(b) << ": expected "
           << expected << ", off by " << e.mean << " +- " << e.standard_error;
      family.add(line.str(),
                 glint_test::zero_mean_p_value(e, glint_test::kRelativeRounding * expected));
    }
  }
  family.check();
}

// ---- the caustic of a glass ball under a point light -----------------------------------------

// A point light on the axis above a glass ball above a grey floor; the camera looks at the floor
// from the side, under the ball. max_depth 2 lets the point light's paths have three vertices
// (light, glass in, glass out, floor, camera): the floor's direct light, the light the ball
// reflects onto it and the light refracted through it without an internal reflection, which is
// what the fan below follows. The camera, below the ball, sees only the floor, within 4.5 of
// the axis.
constexpr float kBallHeight = 3.0f, kBallRadius = 1.0f, kIor = 1.5f;
constexpr float kLightHeight = 10.0f, kIntensity = 200.0f, kAlbedo = 0.5f;
constexpr const char* kCaustic = R"(
image     width=16 height=16 spp=1024 max_depth=2
camera    position=0,1.5,3.5 look_at=0,0,0 up=0,1,0 fov=24
antialias sigma=0.5
light     position=0,10,0 intensity=200
sphere    center=0,-100000,0 radius=1e5 color=0.5,0.5,0.5
sphere    center=0,3,0 radius=1 diffuse=0 transparent=1 ior=1.5
)";

/// Exact dielectric reflectance for unpolarised light, written out here.
double fresnel(double cos_i, double eta_i, double eta_t) {
  const double sin_t = eta_i / eta_t * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const double rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

struct D3 {
  double x, y, z;
};
D3 operator+(D3 a, D3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
D3 operator-(D3 a, D3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
D3 operator*(double s, D3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(D3 a, D3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
D3 unit(D3 a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}

/// The floor's irradiance from the light, as a function of the distance r from the axis: the
/// direct light where the ball does not shadow it, plus the flux of a fan of rays through and
/// off the ball (entry Fresnel, refraction in and out, exit Fresnel; a ray that reflects inside
/// is dropped, as such paths are longer than max_depth allows), binned by r.
class FloorIrradiance {
 public:
  static constexpr double kMaxRadius = 8.0;
  static constexpr int kBins = 4000;

  FloorIrradiance() : flux_(kBins, 0.0) {
    const D3 light{0.0, kLightHeight, 0.0}, center{0.0, kBallHeight, 0.0};
    const double d = kLightHeight - kBallHeight;
    const double cos_max = std::sqrt(1.0 - (kBallRadius / d) * (kBallRadius / d));
    // Rays uniform in solid angle in the ball's cone, one azimuth (the scene is symmetric):
    // each carries intensity x solid angle of its ring, 2 pi (1 - cos_max) / rays in all.
    constexpr int kRays = 8000000;
    const double ray_solid_angle = 2.0 * M_PI * (1.0 - cos_max) / kRays;
    for (int i = 0; i < kRays; ++i) {
      const double cos_theta = 1.0 - (1.0 - cos_max) * (i + 0.5) / kRays;
      const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
      const D3 dir{sin_theta, -cos_theta, 0.0};
      const double power = kIntensity * ray_solid_angle;
      // Entry.
      double t;
      if (!hit_sphere(light, dir, center, t, false)) continue;
      const D3 p = light + t * dir;
      const D3 n = unit(p - center);
      const double cos_i = -dot(dir, n);
      const double reflect = fresnel(cos_i, 1.0, kIor);
      land(p, dir + (2.0 * cos_i) * n, power * reflect);
      const D3 in = refract(dir, n, cos_i, 1.0 / kIor);
      // Exit.
      if (!hit_sphere(p, in, center, t, true)) continue;
      const D3 q = p + t * in;
      const D3 m = unit(center - q);  // the normal facing the ray, inside
      const double cos_j = -dot(in, m);
      const double exit_reflect = fresnel(cos_j, kIor, 1.0);
      if (exit_reflect >= 1.0) continue;
      land(q, refract(in, m, cos_j, kIor), power * (1.0 - reflect) * (1.0 - exit_reflect));
    }
    cos_shadow_ = cos_max;
  }

  /// Irradiance at distance r from the axis on the floor.
  double at(double r) const {
    const double d2 = r * r + double(kLightHeight) * kLightHeight;
    const double cos_floor = kLightHeight / std::sqrt(d2);
    // The direct light unless the ray from the light meets the ball: its angle to the axis
    // is within the ball's cone.
    const double direct = cos_floor > cos_shadow_ ? 0.0 : kIntensity * cos_floor / d2;
    const int bin = std::min(kBins - 1, int(r / kMaxRadius * kBins));
    const double r0 = kMaxRadius * bin / kBins, r1 = kMaxRadius * (bin + 1) / kBins;
    return direct + flux_[std::size_t(bin)] / (M_PI * (r1 * r1 - r0 * r0));
  }

 private:
  static bool hit_sphere(D3 origin, D3 dir, D3 center, double& t, bool inside) {
    const D3 oc = origin - center;
    const double b = dot(oc, dir);
    const double c = dot(oc, oc) - double(kBallRadius) * kBallRadius;
    const double disc = b * b - c;
    if (disc < 0.0) return false;
    t = inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
    return t > 0.0;
  }
  static D3 refract(D3 dir, D3 n, double cos_i, double eta) {
    const double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    return unit(eta * dir + (eta * cos_i - std::sqrt(k)) * n);
  }
  /// The flux `power` leaving `from` along `dir`: onto the floor (y = 0) if it goes down.
  void land(D3 from, D3 dir, double power) {
    if (dir.y >= 0.0) return;
    const double t = -from.y / dir.y;
    // The azimuth is symmetric: the ray stands for its whole ring, so only |x| matters.
    const double r = std::abs(from.x + t * dir.x);
    if (r < kMaxRadius) flux_[std::size_t(r / kMaxRadius * kBins)] += power;
  }

  std::vector<double> flux_;
  double cos_shadow_ = 1.0;
};

TEST_CASE("light tracing: a point light's caustic under a glass ball matches a fan of rays",
          "[render][light][statistical]") {
  const glint::Scene scene = build(kCaustic, "caustic");
  const glint::RenderSettings settings = glint::RenderSettings::from(scene);
  const glint_test::BlockSamples rendered =
      glint_test::render_blocks<LightTracing<Chain>>(scene, 300, settings);

  // The expected radiance of each pixel: albedo / pi x irradiance, averaged over the pixel
  // filter (the normal density of sigma 0.5 pixels, to the 5.77 sigmas its offsets reach) by a
  // 48 x 48 quadrature of offsets.
  const FloorIrradiance irradiance;
  const glint::Camera camera(scene.camera(), glint_test::kBlockImageSize,
                             glint_test::kBlockImageSize);
  std::array<double, glint_test::kBlocks + 1> expected{};
  constexpr int kSteps = 48;
  const double kReach = glint::GaussianAntialiasing::kLargestRadius;  // sigmas
  double weights = 0.0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double ox = (-1.0 + 2.0 * (i + 0.5) / kSteps) * kReach,
                   oy = (-1.0 + 2.0 * (j + 0.5) / kSteps) * kReach;
      weights += std::exp(-0.5 * (ox * ox + oy * oy));
    }
  for (int y = 0; y < glint_test::kBlockImageSize; ++y)
    for (int x = 0; x < glint_test::kBlockImageSize; ++x) {
      double pixel = 0.0;
      for (int i = 0; i < kSteps; ++i)
        for (int j = 0; j < kSteps; ++j) {
          const double ox = (-1.0 + 2.0 * (i + 0.5) / kSteps) * kReach,
                       oy = (-1.0 + 2.0 * (j + 0.5) / kSteps) * kReach;
          const glint::Ray ray =
              camera.ray_through(Vec2(float(x + 0.5 + 0.5 * ox), float(y + 0.5 + 0.5 * oy)));
          REQUIRE(ray.direction.y < 0.0f);  // every ray meets the floor, none the ball
          const double t = -double(ray.origin.y) / ray.direction.y;
          const double px = ray.origin.x + t * ray.direction.x,
                       pz = ray.origin.z + t * ray.direction.z;
          pixel +=
              std::exp(-0.5 * (ox * ox + oy * oy)) * irradiance.at(std::sqrt(px * px + pz * pz));
        }
      // Three channels of albedo / pi x irradiance.
      const double radiance = 3.0 * kAlbedo / M_PI * pixel / weights;
      expected[std::size_t((y / glint_test::kBlock) * glint_test::kBlocksPerSide +
                           x / glint_test::kBlock)] +=
          radiance / (glint_test::kBlock * glint_test::kBlock);
      expected[glint_test::kWholeImage] +=
          radiance / (glint_test::kBlockImageSize * glint_test::kBlockImageSize);
    }

  // The comparison, and the same with the fan's values 5% higher, which must be told apart:
  // the test has the power to see a bias of that size.
  const auto compare = [&](double scale) {
    glint_test::ComparisonFamily family;
    for (std::size_t b = 0; b <= glint_test::kBlocks; ++b) {
      const glint_test::MeanEstimate r = glint_test::estimate_mean(rendered.per_seed[b]);
      const double fan = scale * expected[b];
      std::ostringstream line;
      line << "caustic, " << glint_test::block_name(b) << ": fan of rays " << fan
           << ", light tracing " << r.mean << " +- " << r.standard_error;
      // The fan's own error is allowed as 0.5% of its value: its bins and quadrature, and the
      // light the ball reflects back onto the floor from the floor (a path of three vertices
      // that it does not follow, about 0.1%).
      glint_test::MeanEstimate difference = r;
      difference.mean = r.mean - fan;
      family.add(line.str(), glint_test::zero_mean_p_value(difference, 0.005 * fan));
    }
    return family;
  };
  compare(1.0).check();
  CHECK_FALSE(compare(1.05).rejected().empty());
}

}  // namespace light_tracing_test
