// glint's sphere accelerators against Embree 3 on the same spheres and the same rays.
//
//   glint-embree-compare [--quick] [--only NAME] [--markdown FILE]
//
// --only NAME keeps the scenes whose name starts with NAME ("packing", "random 10^6").
//
// Scenes: glint's random scenes of 10^3 to 10^6 spheres (the generator's six walls of radius
// 1e5 included, 10^6 spheres per cube of side 2000), and a dense packing (a cubic
// lattice of nearly touching spheres). Rays, at least 2^20 distinct ones per set: coherent
// camera rays (one per pixel of a 1024x1024 image of the scene's camera, in 4x2 pixel blocks, so
// that Embree's 8-ray packets are pixel neighbours) and incoherent random rays (origins uniform
// in the box of the ordinary spheres' centres, directions uniform on the sphere). Each engine
// answers closest-hit queries: glint through Scene::closest_hit (its BVH, with the walls kept
// apart as glint does) and through Scene::closest_hits, eight rays (one 4x2 block of camera
// rays) a query, whose answers must be those of closest_hit exactly (else exit status 1);
// Embree through rtcIntersect1 and rtcIntersect8 over one
// RTC_GEOMETRY_TYPE_SPHERE_POINT geometry. Both engines are told which rays are coherent:
// glint's batched query by RayCoherence::incoherent for the random rays, Embree's by the
// coherent or incoherent flag of its intersection context. Throughput is rays per wall-clock second
// on 1 and 2 threads, build time that of glint's SphereBvh over all the spheres and of Embree's
// rtcCommitScene, each limited to the row's number of threads (glint builds on one core below
// 65,536 spheres): the best of 5 runs after a warm-up, the engines' runs taken in turns. The
// share of rays on which both engines report the same sphere (or both a miss) is printed, so that a
// fast wrong answer cannot pass unnoticed: below 99.9% on any row the program fails (exit status
// 1), as it does when Embree fails. The few rays that differ graze a sphere or pass between two at
// equal distance, where single precision cannot tell which is first.
//
// Built only when Embree 3 is found (bench/CMakeLists.txt); nothing else depends on it.

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "glint/generate/random_scene.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/math/random.hpp"
#include "glint/render/camera.hpp"
#include "glint/scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct TestScene {
  std::string name;
  glint::SceneDescription description;
};

/// A random scene of about `count` spheres at the density of a million-sphere random scene
/// (a cube of side 2000 for 10^6, radii 1 to 8).
TestScene random_scene(int count) {
  glint::RandomSceneParameters p;
  p.sphere_count = count;
  p.domain_size = float(2000.0 * std::cbrt(count / 1e6));
  p.min_radius = 1.0f;
  p.max_radius = 8.0f;
  p.seed = 1;
  glint::RandomSceneResult result = glint::generate_random_scene(p);
  return {"random 10^" + std::to_string(int(std::lround(std::log10(count)))),
          std::move(result.scene)};
}

/// side^3 spheres of radius 0.49 on the unit lattice, and a camera outside it.
TestScene packed_scene(int side) {
  glint::SceneDescription d;
  d.source = "packing";
  const float half = 0.5f * float(side - 1);
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        glint::SphereDescription s;
        s.center = glint::Vec3(float(x) - half, float(y) - half, float(z) - half);
        s.radius = 0.49f;
        d.spheres.push_back(s);
      }
  d.camera.position = glint::Vec3(0.6f, 0.8f, 1.0f) * (2.0f * float(side));
  d.camera.look_at = glint::Vec3(0.0f);
  return {"packing " + std::to_string(side) + "^3", std::move(d)};
}

struct RaySet {
  std::string name;
  bool coherent;  ///< told to both engines: glint's RayCoherence, Embree's context flags
  std::vector<glint::Ray> rays;
};

RaySet camera_rays(const glint::SceneDescription& d, int side) {
  const glint::Camera camera(d.camera, side, side);
  RaySet set{"camera", true, {}};
  set.rays.reserve(std::size_t(side) * std::size_t(side));
  for (int by = 0; by < side; by += 2)
    for (int bx = 0; bx < side; bx += 4)
      for (int y = by; y < by + 2; ++y)
        for (int x = bx; x < bx + 4; ++x)
          set.rays.push_back(camera.ray_through(glint::Vec2(float(x) + 0.5f, float(y) + 0.5f)));
  return set;
}

RaySet random_rays(const glint::SceneDescription& d, std::size_t count) {
  // The box of the ordinary spheres' centres: the walls (radius >= 1000) would make it huge.
  glint::Vec3 lower(std::numeric_limits<float>::max()), upper(-std::numeric_limits<float>::max());
  for (const glint::SphereDescription& s : d.spheres)
    if (s.radius < 1000.0f) {
      lower = glm::min(lower, s.center);
      upper = glm::max(upper, s.center);
    }
  glint::Pcg32 rng(12345, 678);
  RaySet set{"random", false, {}};
  set.rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    glint::Ray ray;
    ray.origin =
        lower + (upper - lower) * glint::Vec3(rng.next_float(), rng.next_float(), rng.next_float());
    const float z = 1.0f - 2.0f * rng.next_float();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 6.2831853f * rng.next_float();
    ray.direction = glint::Vec3(r * std::cos(phi), r * std::sin(phi), z);
    set.rays.push_back(ray);
  }
  return set;
}

/// Runs work(begin, end) over [0, count) in chunks on `threads` threads; wall seconds.
double timed_parallel(std::size_t count, int threads,
                      const std::function<void(std::size_t, std::size_t)>& work) {
  constexpr std::size_t kChunk = 4096;  // a multiple of 8: packets never straddle chunks
  std::atomic<std::size_t> next{0};
  const auto start = Clock::now();
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (std::size_t begin = next.fetch_add(kChunk); begin < count;
           begin = next.fetch_add(kChunk))
        work(begin, std::min(count, begin + kChunk));
    });
  for (std::thread& t : pool)
    t.join();
  return seconds_since(start);
}

/// The best of `runs` timings of each of `run`, after a warm-up: taken in turns, a round of
/// one run each at a time, so that a slow spell of the machine falls on all of them rather than
/// on one.
std::vector<double> best_in_turns(int runs, const std::vector<std::function<double()>>& run) {
  for (const auto& r : run)
    r();
  std::vector<double> best(run.size(), std::numeric_limits<double>::infinity());
  for (int i = 0; i < runs; ++i)
    for (std::size_t k = 0; k < run.size(); ++k)
      best[k] = std::min(best[k], run[k]());
  return best;
}

constexpr std::uint32_t kMiss = std::numeric_limits<std::uint32_t>::max();

class EmbreeScene {
 public:
  EmbreeScene(const glint::SceneDescription& d, int threads) {
    const std::string config = "threads=" + std::to_string(threads);
    device_ = rtcNewDevice(config.c_str());
    if (!device_) fail("rtcNewDevice");
    const auto start = Clock::now();
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* points = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                                               d.spheres.size()));
    if (!points) fail("rtcSetNewGeometryBuffer");
    for (std::size_t i = 0; i < d.spheres.size(); ++i) {
      const glint::SphereDescription& s = d.spheres[i];
      std::memcpy(points + 4 * i, &s.center, 3 * sizeof(float));
      points[4 * i + 3] = s.radius;
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    build_seconds_ = seconds_since(start);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) fail("building the scene");
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  double build_seconds() const { return build_seconds_; }

  void intersect1(const glint::Ray* rays, std::size_t count, bool coherent,
                  std::uint32_t* hits) const {
    RTCIntersectContext context;
    init_context(context, coherent);
    for (std::size_t i = 0; i < count; ++i) {
      RTCRayHit rh;
      set_ray(rh.ray, rays[i]);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context, &rh);
      hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kMiss : rh.hit.primID;
    }
  }

  /// `count` a multiple of 8.
  void intersect8(const glint::Ray* rays, std::size_t count, bool coherent,
                  std::uint32_t* hits) const {
    RTCIntersectContext context;
    init_context(context, coherent);
    alignas(32) int valid[8];
    std::fill(valid, valid + 8, -1);
    for (std::size_t base = 0; base < count; base += 8) {
      alignas(32) RTCRayHit8 rh;
      for (int k = 0; k < 8; ++k) {
        const glint::Ray& r = rays[base + std::size_t(k)];
        rh.ray.org_x[k] = r.origin.x;
        rh.ray.org_y[k] = r.origin.y;
        rh.ray.org_z[k] = r.origin.z;
        rh.ray.dir_x[k] = r.direction.x;
        rh.ray.dir_y[k] = r.direction.y;
        rh.ray.dir_z[k] = r.direction.z;
        rh.ray.tnear[k] = 0.0f;
        rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
        rh.ray.time[k] = 0.0f;
        rh.ray.mask[k] = ~0u;
        rh.ray.id[k] = 0;
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect8(valid, scene_, &context, &rh);
      for (int k = 0; k < 8; ++k)
        hits[base + std::size_t(k)] =
            rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? kMiss : rh.hit.primID[k];
    }
  }

 private:
  static void init_context(RTCIntersectContext& context, bool coherent) {
    rtcInitIntersectContext(&context);
    context.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  }
  static void set_ray(RTCRay& ray, const glint::Ray& r) {
    ray.org_x = r.origin.x;
    ray.org_y = r.origin.y;
    ray.org_z = r.origin.z;
    ray.dir_x = r.direction.x;
    ray.dir_y = r.direction.y;
    ray.dir_z = r.direction.z;
    ray.tnear = 0.0f;
    ray.tfar = std::numeric_limits<float>::infinity();
    ray.time = 0.0f;
    ray.mask = ~0u;
    ray.id = 0;
    ray.flags = 0;
  }
  [[noreturn]] static void fail(const char* what) {
    std::fprintf(stderr, "glint-embree-compare: Embree failed: %s\n", what);
    std::exit(1);
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_seconds_ = 0.0;
};

struct Row {
  std::string scene, rays;
  std::size_t spheres = 0, ray_count = 0;
  int threads = 0;
  double glint_mrays = 0, glint8_mrays = 0, embree1_mrays = 0, embree8_mrays = 0;
  double glint_build = 0, embree_build = 0;
  double agreement = 0;       ///< share of rays whose hits (sphere or miss) agree
  bool batched_exact = true;  ///< closest_hits answered closest_hit's hits exactly
};

std::string format_row(const Row& r) {
  char line[512];
  // Each library at its best: one ray at a time or eight, whichever is faster on the row.
  const double best_glint = std::max(r.glint_mrays, r.glint8_mrays);
  const double best_embree = std::max(r.embree1_mrays, r.embree8_mrays);
  std::snprintf(line, sizeof line,
                "| %s | %zu | %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f | "
                "%.4f%% |",
                r.scene.c_str(), r.spheres, r.rays.c_str(), r.threads, r.glint_mrays,
                r.glint8_mrays, r.embree1_mrays, r.embree8_mrays, best_glint / best_embree,
                r.glint_build, r.embree_build, r.embree_build / r.glint_build, 100.0 * r.agreement);
  return line;
}

const char* kHeader =
    "| scene | spheres | rays | threads | glint Mrays/s | glint 8 Mrays/s | Embree 1 Mrays/s | "
    "Embree 8 Mrays/s | best glint / best Embree | glint build s | Embree build s | "
    "Embree / glint build | hits agree |\n"
    "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|";

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string markdown, only;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--markdown" && i + 1 < argc) {
      markdown = argv[++i];
    } else if (arg == "--only" && i + 1 < argc) {
      only = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: glint-embree-compare [--quick] [--only NAME] [--markdown FILE]\n");
      return 2;
    }
  }
  const int image_side = quick ? 256 : 1024;
  const std::size_t random_count = quick ? 1 << 16 : 1 << 20;
  const int runs = quick ? 1 : 5;

  std::vector<TestScene> scenes;
  for (const int count :
       quick ? std::vector<int>{1000, 10000} : std::vector<int>{1000, 10000, 100000, 1000000})
    scenes.push_back(random_scene(count));
  scenes.push_back(packed_scene(quick ? 16 : 64));
  std::erase_if(scenes, [&](const TestScene& s) { return !s.name.starts_with(only); });
  if (scenes.empty()) {
    std::fprintf(stderr, "glint-embree-compare: no scene's name starts with \"%s\"\n",
                 only.c_str());
    return 2;
  }

  std::vector<Row> rows;
  std::puts(kHeader);
  for (const TestScene& test : scenes) {
    const glint::Scene scene = glint::Scene::build(test.description);
    std::vector<glint::bvh::SphereInput> inputs;
    for (std::size_t i = 0; i < test.description.spheres.size(); ++i)
      inputs.push_back({test.description.spheres[i].center, test.description.spheres[i].radius,
                        std::uint32_t(i)});
    for (const RaySet& set :
         {camera_rays(test.description, image_side), random_rays(test.description, random_count)}) {
      const std::size_t n = set.rays.size();
      std::vector<std::uint32_t> glint_hits(n), glint8_hits(n), embree_hits(n);
      std::vector<float> glint_t(n), glint8_t(n);
      for (const int threads : {1, 2}) {
        Row row;
        row.scene = test.name;
        row.rays = set.name;
        row.spheres = test.description.spheres.size();
        row.ray_count = n;
        row.threads = threads;
        const EmbreeScene embree(test.description, threads);
        const std::vector<double> build_seconds =
            best_in_turns(runs, {[&] {
                                   const auto start = Clock::now();
                                   const glint::SphereBvh bvh(inputs, std::size_t(threads));
                                   return seconds_since(start);
                                 },
                                 [&] {
                                   const EmbreeScene rebuilt(test.description, threads);
                                   return rebuilt.build_seconds();
                                 }});
        row.glint_build = build_seconds[0];
        row.embree_build = build_seconds[1];
        const auto glint_run = [&] {
          return timed_parallel(n, threads, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
              const std::optional<glint::SphereHit> hit = scene.closest_hit(set.rays[i]);
              glint_hits[i] = hit ? hit->sphere : kMiss;
              glint_t[i] = hit ? hit->t : glint::kInfinity;
            }
          });
        };
        const auto glint8_run = [&] {
          return timed_parallel(n, threads, [&](std::size_t begin, std::size_t end) {
            glint::RayBatch batch;
            glint::HitBatch hits;
            for (std::size_t base = begin; base < end; base += 8) {
              for (int k = 0; k < 8; ++k)
                batch.set(k, set.rays[base + std::size_t(k)]);
              scene.closest_hits(
                  batch, glint::RayBatch::kAllLanes, hits,
                  set.coherent ? glint::RayCoherence::unknown : glint::RayCoherence::incoherent);
              for (int k = 0; k < 8; ++k) {
                glint8_hits[base + std::size_t(k)] = hits.sphere[k];
                glint8_t[base + std::size_t(k)] = hits.t[k];
              }
            }
          });
        };
        const auto embree1_run = [&] {
          return timed_parallel(n, threads, [&](std::size_t begin, std::size_t end) {
            embree.intersect1(set.rays.data() + begin, end - begin, set.coherent,
                              embree_hits.data() + begin);
          });
        };
        const auto embree8_run = [&] {
          return timed_parallel(n, threads, [&](std::size_t begin, std::size_t end) {
            embree.intersect8(set.rays.data() + begin, end - begin, set.coherent,
                              embree_hits.data() + begin);
          });
        };
        const std::vector<double> seconds =
            best_in_turns(runs, {glint_run, glint8_run, embree1_run, embree8_run});
        const double glint_seconds = seconds[0], glint8_seconds = seconds[1],
                     embree1_seconds = seconds[2], embree8_seconds = seconds[3];
        for (std::size_t i = 0; i < n; ++i)
          row.batched_exact = row.batched_exact && glint8_hits[i] == glint_hits[i] &&
                              std::memcmp(&glint8_t[i], &glint_t[i], sizeof(float)) == 0;
        std::size_t agree = 0;
        for (std::size_t i = 0; i < n; ++i)
          agree += glint_hits[i] == embree_hits[i] ? 1 : 0;
        row.agreement = double(agree) / double(n);
        row.glint_mrays = double(n) / glint_seconds * 1e-6;
        row.glint8_mrays = double(n) / glint8_seconds * 1e-6;
        row.embree1_mrays = double(n) / embree1_seconds * 1e-6;
        row.embree8_mrays = double(n) / embree8_seconds * 1e-6;
        std::puts(format_row(row).c_str());
        std::fflush(stdout);
        rows.push_back(row);
      }
    }
  }
  constexpr double kMinAgreement = 0.999;
  bool agreed = true;
  for (const Row& r : rows) {
    if (!r.batched_exact) {
      std::fprintf(stderr,
                   "glint-embree-compare: Scene::closest_hits differs from closest_hit on the %s "
                   "rays of %s\n",
                   r.rays.c_str(), r.scene.c_str());
      agreed = false;
    }
    if (r.agreement < kMinAgreement) {
      std::fprintf(stderr,
                   "glint-embree-compare: glint and Embree disagree on %.3f%% of the %s rays of "
                   "%s (at most %.1f%% may differ)\n",
                   100.0 * (1.0 - r.agreement), r.rays.c_str(), r.scene.c_str(),
                   100.0 * (1.0 - kMinAgreement));
      agreed = false;
    }
  }
  if (!markdown.empty()) {
    std::ofstream out(markdown);
    out << kHeader << "\n";
    for (const Row& r : rows)
      out << format_row(r) << "\n";
    if (!out) {
      std::fprintf(stderr, "glint-embree-compare: cannot write %s\n", markdown.c_str());
      return 1;
    }
  }
  return agreed ? 0 : 1;
}
