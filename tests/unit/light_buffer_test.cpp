// The light buffer (geometry/light_buffer.hpp) lets a shadow ray toward a point light test only
// the spheres its cell lists; the verdict must stay the full scan's, bit for bit. Checked on
// shadow rays as the renderers make them (from points on spheres and in space), rays grazing a
// sphere's silhouette as seen from the light, lights inside, on and next to spheres, and rays
// that do not quite end at the light (which the buffer must leave to the full scan).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "glint/geometry/light_buffer.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/scene.hpp"
#include "random_vectors.hpp"

#ifdef GLINT_AVX2
namespace {

using glint::LaneMask;
using glint::LightBuffer;
using glint::Ray;
using glint::RayBatch;
using glint::Vec3;

constexpr int kBatchWidth = RayBatch::kWidth;

using glint::test::uniform;
using glint::test::unit_vector;

Vec3 random_point(glint::Pcg32& rng, float half) {
  return {uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half)};
}

/// The shadow ray of PathContext::light_rays from `point` to `light`.
Ray shadow_ray(const Vec3& point, const Vec3& light, std::uint32_t sphere, const Vec3& normal) {
  const Vec3 to_light = light - point;
  const float distance = std::sqrt(glm::dot(to_light, to_light));
  const Vec3 direction = to_light / distance;
  if (sphere == glint::kNoSphere) {
    Ray ray;
    ray.origin = point;
    ray.direction = direction;
    ray.t_max = distance;
    return ray;
  }
  return glint::ray_leaving_sphere(point, direction, sphere, normal, distance);
}

struct World {
  std::vector<glint::SphereDescription> spheres;
  std::vector<Vec3> lights;
  float half = 20.0f;
};

/// A shadow ray toward one of the lights, of one of several kinds: from a point on a sphere;
/// from a point in space; grazing a sphere's silhouette as seen from the light; or one that
/// ends a little short of the light, beyond it, or misses it (not a shadow ray of that light).
Ray random_shadow_ray(glint::Pcg32& rng, const World& world) {
  const Vec3& light = world.lights[rng.next_u32() % world.lights.size()];
  const auto id = std::uint32_t(rng.next_u32() % world.spheres.size());
  const glint::SphereDescription& s = world.spheres[id];
  const std::uint32_t kind = rng.next_u32() % 6;
  if (kind <= 1 && s.radius < 1e3f) {
    const Vec3 normal = unit_vector(rng);
    return shadow_ray(s.center + s.radius * normal, light, id, normal);
  }
  if (kind == 2 && s.radius < 1e3f && glm::length(s.center - light) > s.radius) {
    // Grazing: through a point of the silhouette (the tangent cone from the light), pushed
    // in or out by up to 1e-5 of the radius, from a point beyond it.
    const Vec3 axis = glm::normalize(s.center - light);
    Vec3 side = glm::cross(axis, unit_vector(rng));
    if (glm::dot(side, side) < 1e-6f) side = glm::cross(axis, Vec3(0.3f, 0.5f, 0.8f));
    side = glm::normalize(side);
    const float distance = glm::length(s.center - light);
    const float sin_a = s.radius / distance;
    const float cos_a = std::sqrt(std::max(0.0f, 1.0f - sin_a * sin_a));
    const Vec3 to_tangent = cos_a * axis + sin_a * side;
    const float scale = 1.0f + uniform(rng, -1e-5f, 1e-5f);
    const Vec3 tangent = light + (distance * cos_a * scale) * to_tangent;
    const Vec3 origin = light + uniform(rng, 1.05f, 3.0f) * (tangent - light);
    return shadow_ray(origin, light, glint::kNoSphere, Vec3(0.0f));
  }
  Ray ray = shadow_ray(random_point(rng, world.half), light, glint::kNoSphere, Vec3(0.0f));
  if (kind == 5) {
    // Not quite toward the light: the buffer must not take it, or answer as the scan.
    const float off = std::pow(10.0f, uniform(rng, -7.0f, -1.0f));
    switch (rng.next_u32() % 3) {
      case 0:
        ray.t_max *= 1.0f - off;
        break;
      case 1:
        ray.t_max *= 1.0f + off;
        break;
      default:
        ray.direction = glm::normalize(ray.direction + off * unit_vector(rng));
        break;
    }
  }
  return ray;
}

/// Random spheres, some nested, some near or around the lights, and lights of which some sit
/// inside, on or just off a sphere.
World random_world(glint::Pcg32& rng, int count, int lights, bool room) {
  World world;
  auto add = [&](Vec3 c, float r) {
    glint::SphereDescription sphere;
    sphere.center = c;
    sphere.radius = r;
    world.spheres.push_back(sphere);
  };
  if (room)
    for (int axis = 0; axis < 3; ++axis)
      for (const float side : {-1.0f, 1.0f}) {
        Vec3 center(0.0f);
        center[axis] = side * (1e5f + 30.0f);
        add(center, 1e5f);
      }
  for (int i = 0; i < count; ++i) {
    const Vec3 c = random_point(rng, world.half);
    const float r = std::pow(10.0f, uniform(rng, -2.0f, 0.8f));
    add(c, r);
    if (rng.next_u32() % 8 == 0) add(c, 0.5f * r);  // nested
  }
  for (int l = 0; l < lights; ++l) {
    Vec3 light = random_point(rng, world.half);
    const glint::SphereDescription& s =
        world.spheres[(room ? 6 : 0) + rng.next_u32() % unsigned(count)];
    switch (rng.next_u32() % 5) {
      case 0:
        light = s.center + 0.5f * s.radius * unit_vector(rng);
        break;  // inside
      case 1:
        light = s.center + s.radius * unit_vector(rng);
        break;  // on it
      case 2:
        light = s.center +
                s.radius * (1.0f + std::pow(10.0f, uniform(rng, -6.0f, -1.0f))) * unit_vector(rng);
        break;
      default:
        break;
    }
    world.lights.push_back(light);
  }
  return world;
}

glint::Scene build(const World& world) {
  glint::SceneDescription description;
  description.spheres = world.spheres;
  for (const Vec3& position : world.lights) {
    glint::PointLight light;
    light.position = position;
    description.lights.push_back(light);
  }
  return glint::Scene::build(description);
}

}  // namespace

TEST_CASE("LightBuffer: the cells of eight directions at once are cell_of's", "[light_buffer]") {
  glint::Pcg32 rng(3, 4);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<Vec3> directions = {{1, 0, 0},    {-1, 0, 0}, {0, 1, 0},   {0, -1, 0},
                                  {0, 0, 1},    {0, 0, -1}, {1, 1, 0},   {1, -1, 1},
                                  {-1, -1, -1}, {0, 0, 0},  {nan, 0, 0}, {0.5f, 0.5f, -0.5f}};
  for (int i = 0; i < 4000; ++i) {
    Vec3 d = unit_vector(rng);
    // On a cell's border now and then: a coordinate ratio of k / 16 - 1.
    if (i % 3 == 0) d.y = d.x * (float(rng.next_u32() % 33) / 16.0f - 1.0f);
    directions.push_back(d);
  }
  int faces_seen = 0;
  for (std::size_t base = 0; base + kBatchWidth <= directions.size(); base += kBatchWidth) {
    RayBatch batch;
    for (int lane = 0; lane < kBatchWidth; ++lane) {
      Ray ray;
      ray.direction = -directions[base + std::size_t(lane)];  // cells() looks back along a ray
      batch.set(lane, ray);
    }
    alignas(32) std::int32_t cells[kBatchWidth];
    _mm256_store_si256(reinterpret_cast<__m256i*>(cells),
                       LightBuffer::cells(glint::avx2::ray_lanes(batch)));
    for (int lane = 0; lane < kBatchWidth; ++lane) {
      const Vec3& d = directions[base + std::size_t(lane)];
      INFO("direction (" << d.x << ", " << d.y << ", " << d.z << ")");
      CHECK(cells[lane] == LightBuffer::cell_of(d));
      CHECK(cells[lane] >= 0);
      CHECK(cells[lane] < LightBuffer::kCells);
      faces_seen |= 1 << (cells[lane] / (LightBuffer::kCellsPerEdge * LightBuffer::kCellsPerEdge));
    }
  }
  CHECK(faces_seen == 0b111111);
  // The faces: +x, -x, +y, -y, +z, -z.
  const int per_face = LightBuffer::kCellsPerEdge * LightBuffer::kCellsPerEdge;
  CHECK(LightBuffer::cell_of({-2, 1, 1}) / per_face == 1);
  CHECK(LightBuffer::cell_of({0, 3, 1}) / per_face == 2);
  CHECK(LightBuffer::cell_of({0, 1, -3}) / per_face == 5);
}

TEST_CASE("LightBuffer: a cell lists the spheres in its directions only", "[light_buffer]") {
  // Spheres on the +x side of the light: the other faces' cells list none, and a cell of +x
  // lists the groups of the spheres around its direction.
  glint::SphereSet spheres;
  for (std::uint32_t i = 0; i < 24; ++i)
    spheres.add(Vec3(30.0f, float(i % 6) * 8.0f - 20.0f, float(i / 6) * 8.0f - 12.0f), 1.0f, i);
  const LightBuffer buffer(Vec3(0.0f), spheres.columns());
  const int per_face = LightBuffer::kCellsPerEdge * LightBuffer::kCellsPerEdge;
  int listed = 0;
  for (int cell = per_face; cell < LightBuffer::kCells; ++cell)
    listed += buffer.groups(cell) != 0;
  CHECK(listed == 0);
  int empty_on_x = 0;
  for (int cell = 0; cell < per_face; ++cell)
    empty_on_x += buffer.groups(cell) == 0;
  CHECK(empty_on_x > per_face / 2);  // between the spheres, and beyond them
  CHECK(buffer.groups(LightBuffer::cell_of(Vec3(30.0f, -20.0f, -12.0f))) != 0);
}

TEST_CASE("LightBuffer: a direction's cell lists every sphere that the direction meets",
          "[light_buffer]") {
  // Worked out in double, apart from the buffer: direction w from the light meets the sphere
  // if the angle between w and the centre is at most asin(r / distance), or the light is
  // inside the sphere.
  glint::Pcg32 rng(11, 12);
  for (int scene = 0; scene < 20; ++scene) {
    glint::SphereSet spheres;
    const Vec3 light = random_point(rng, 10.0f);
    struct Kept {
      Vec3 center;
      float radius;
    };
    std::vector<Kept> kept;
    for (std::uint32_t i = 0; i < 64; ++i) {
      const Vec3 c = random_point(rng, 30.0f);
      const float r = std::pow(10.0f, uniform(rng, -2.0f, 0.7f));
      spheres.add(c, r, i);
      kept.push_back({c, r});
    }
    const LightBuffer buffer(light, spheres.columns());
    const auto columns = buffer.columns();
    int met = 0;
    for (int i = 0; i < 20000; ++i) {
      Vec3 w = unit_vector(rng);
      // Aim at a sphere's silhouette half of the time.
      if (i % 2 == 0) {
        const Kept& s = kept[rng.next_u32() % kept.size()];
        const Vec3& c = s.center;
        const Vec3 axis = glm::normalize(c - light);
        const Vec3 side = glm::normalize(glm::cross(axis, unit_vector(rng)));
        const float distance = glm::length(c - light);
        const float angle =
            std::asin(std::min(1.0f, s.radius / distance)) * uniform(rng, 0.9f, 1.0f);
        w = std::cos(angle) * axis + std::sin(angle) * side;
      }
      const int cell = LightBuffer::cell_of(w);
      const glm::dvec3 dw = glm::normalize(glm::dvec3(w));
      for (std::size_t slot = 0; slot < columns.size; ++slot) {
        const glm::dvec3 c(columns.cx[slot], columns.cy[slot], columns.cz[slot]);
        const glm::dvec3 to_center = c - glm::dvec3(light);
        const double distance = glm::length(to_center);
        const double r = std::sqrt(double(columns.r2[slot]));
        const bool meets = distance <= r ||
                           glm::dot(dw, to_center / distance) >= std::cos(std::asin(r / distance));
        if (!meets) continue;
        ++met;
        INFO("scene " << scene << " direction " << i << " sphere slot " << slot);
        CHECK((buffer.groups(cell) >> (slot / LightBuffer::kGroupSize) & 1u) == 1u);
      }
    }
    CHECK(met > 1000);
  }
}

TEST_CASE("LightBuffer: blocks answers as the full scan for rays that end at the light",
          "[light_buffer]") {
  for (const int count : {1, 7, 8, 30, 64}) {
    DYNAMIC_SECTION(count << " spheres") {
      glint::Pcg32 rng(std::uint64_t(count), 9);
      const World world = random_world(rng, count, 6, false);
      glint::SphereSet set;
      for (std::size_t i = 0; i < world.spheres.size() && i < LightBuffer::kMaxSpheres; ++i)
        set.add(world.spheres[i].center, world.spheres[i].radius, std::uint32_t(i));
      std::vector<LightBuffer> buffers;
      for (const Vec3& light : world.lights)
        buffers.emplace_back(light, set.columns());
      int taken = 0, blocked = 0, tested = 0;
      for (int i = 0; i < 3000; ++i) {
        const Ray ray = random_shadow_ray(rng, world);
        RayBatch batch;
        for (int lane = 0; lane < kBatchWidth; ++lane)
          batch.set(lane, ray);
        const glint::avx2::RayLanes lanes = glint::avx2::ray_lanes(batch);
        const int cell = _mm256_extract_epi32(LightBuffer::cells(lanes), 0);
        const bool expected =
            glint::avx2::any_hit(ray, glint::hit_to_beat(ray, glint::SphereHit{}), set.columns());
        for (const LightBuffer& buffer : buffers) {
          if (buffer.ends_here(lanes, _mm256_load_ps(batch.t_max), 1u) == 0) continue;
          ++taken;
          INFO("ray " << i << " origin (" << ray.origin.x << ", " << ray.origin.y << ", "
                      << ray.origin.z << ") to light (" << buffer.light().x << ", "
                      << buffer.light().y << ", " << buffer.light().z << ")");
          CHECK(buffer.blocks(ray, cell) == expected);
          blocked += expected;
        }
        ++tested;
      }
      CHECK(taken > tested / 2);
      CHECK(blocked > 0);
      CHECK(blocked < taken);
    }
  }
}

TEST_CASE("LightBuffer: ends_here takes the rays of PathContext::light_rays only",
          "[light_buffer]") {
  glint::SphereSet spheres;
  spheres.add(Vec3(5.0f, 0.0f, 0.0f), 1.0f, 0);
  const Vec3 light(0.0f, 10.0f, 0.0f);
  const LightBuffer buffer(light, spheres.columns());
  const Ray to_light = shadow_ray(Vec3(3.0f, -2.0f, 1.0f), light, glint::kNoSphere, Vec3(0.0f));
  const auto taken = [&](const Ray& ray) {
    RayBatch batch;
    for (int lane = 0; lane < kBatchWidth; ++lane)
      batch.set(lane, ray);
    return buffer.ends_here(glint::avx2::ray_lanes(batch), _mm256_load_ps(batch.t_max), 0xFFu);
  };
  CHECK(taken(to_light) == 0xFFu);
  Ray behind = to_light;
  behind.t_min = -1.0f;  // would reach behind the origin, beyond the margins' bounds
  CHECK(taken(behind) == 0u);
  Ray short_of_it = to_light;
  short_of_it.t_max *= 0.999f;
  CHECK(taken(short_of_it) == 0u);
  Ray long_way = shadow_ray(Vec3(0.0f, 10.0f, -1e4f), light, glint::kNoSphere, Vec3(0.0f));
  CHECK(taken(long_way) == 0u);  // longer than four times the spheres' reach
  Ray scaled = to_light;
  scaled.direction *= 2.0f;
  scaled.t_max *= 0.5f;
  CHECK(taken(scaled) == 0u);
}

TEST_CASE("occluded: batches of shadow rays answer as the single-ray query",
          "[light_buffer][ray_batch]") {
  for (const int count : {3, 30, 58}) {  // the first without light buffers
    for (const bool room : {false, true}) {
      for (const int lights : {1, 3, 20}) {
        DYNAMIC_SECTION(count << " spheres, " << lights << " lights" << (room ? ", a room" : "")) {
          glint::Pcg32 rng(std::uint64_t(count * 100 + lights), room ? 5 : 6);
          const World world = random_world(rng, count, lights, room);
          const glint::Scene scene = build(world);
          int lanes_checked = 0, blocked_lanes = 0;
          for (int b = 0; b < 500; ++b) {
            Ray rays[kBatchWidth];
            RayBatch batch;
            for (int lane = 0; lane < kBatchWidth; ++lane) {
              rays[lane] = random_shadow_ray(rng, world);
              batch.set(lane, rays[lane]);
            }
            const LaneMask active =
                b % 2 == 0 ? RayBatch::kAllLanes : rng.next_u32() & RayBatch::kAllLanes;
            const LaneMask blocked = scene.occluded(batch, active);
            CHECK((blocked & ~active) == 0);
            for (int lane = 0; lane < kBatchWidth; ++lane) {
              if (!((active >> lane) & 1u)) continue;
              const Ray& ray = rays[lane];
              INFO("lane " << lane << " origin (" << ray.origin.x << ", " << ray.origin.y << ", "
                           << ray.origin.z << ") direction (" << ray.direction.x << ", "
                           << ray.direction.y << ", " << ray.direction.z << ") t_max " << ray.t_max
                           << " origin sphere " << ray.origin_sphere);
              const bool expected = scene.occluded(ray);
              CHECK(((blocked >> lane) & 1u) == (expected ? 1u : 0u));
              ++lanes_checked;
              blocked_lanes += expected;
            }
          }
          CHECK(blocked_lanes > lanes_checked / 20);
          CHECK(blocked_lanes < lanes_checked);
        }
      }
    }
  }
}
#endif
