#pragma once
// The report's random scene generator (section 5): spheres of random materials scattered in a
// cube room, each as large as it can be while every two spheres stay disjoint or nested, so
// that transparent spheres always satisfy the inclusion rule (scene/inclusion_tree.hpp).
//
// Layout, for a domain of side s centred on the origin:
// - the spheres live in the cube [-s/2, s/2]^3;
// - the room is the cube extended towards +z to make space for the camera and the lights:
//   [-s/2, s/2]^2 x [-s/2, 3s/2]. Its six walls are huge diffuse spheres and, as in smallpt,
//   the room is the intersection of their insides (smallpt's left wall, centre x = 1e5 + 1 and
//   radius 1e5, is the sphere whose surface is the plane x = 1 near the room). That room is
//   closed and convex, so no ray escapes through the edges where two walls meet;
// - the camera sits at z = 1.4 s looking at the origin with a 60 degree field of view, so the
//   whole front face of the domain (0.9 s away, tan 30 degrees * 0.9 s = 0.52 s > s/2) is in
//   view; two point lights hang above it, in front of the domain, where no sphere can be.
//
// Randomness comes from Pcg32 streams keyed by (seed, sphere index), never from std
// distributions, so a seed gives the same file with every compiler and standard library. A
// sphere depends only on its own stream and on the spheres before it, so the scene with n
// spheres is a prefix of the scene with more spheres and the same parameters.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint {

struct RandomSceneParameters {
  float domain_size = 80.0f;  ///< side of the cube [-s/2, s/2]^3 the spheres are placed in
  int sphere_count = 15;      ///< spheres requested (the walls come on top)
  float diffuse_probability = 0.15f;
  float mirror_probability = 0.35f;
  float transparent_probability = 0.5f;
  float min_radius = 5.0f;
  float max_radius = 10.0f;
  std::uint64_t seed = 1;
  /// Surfaces stay at least gap_fraction * min_radius apart (and as far from the walls), so
  /// that no two surfaces touch and float rounding in the renderer cannot make them cross.
  float gap_fraction = 0.01f;
  int max_attempts = 100;  ///< centres tried for one sphere before it is given up
};

struct RandomSceneResult {
  SceneDescription scene;  ///< the walls first (wall_count of them), then the placed spheres
  int placed = 0;          ///< random spheres placed
  int requested = 0;       ///< random spheres asked for
  int wall_count = 0;
  long long attempts = 0;  ///< centres tried in all
  double gap = 0.0;        ///< the distance kept between surfaces
  bool complete() const { return placed == requested; }
};

inline constexpr int kMaxRandomSceneSpheres = 100'000'000;
inline constexpr int kMaxRandomSceneAttempts = 1'000'000;
inline constexpr float kMaxRandomSceneDomain = 1e6f;

/// Throws std::invalid_argument naming the first bad parameter.
inline void validate(const RandomSceneParameters& p) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("random scene: " + what);
  };
  // Shortest form of the value as a float: what the user typed comes back unchanged, and
  // unlike std::to_string this ignores the C locale.
  const auto text = [](double v) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(v));
    return std::string(buffer, r.ptr);
  };
  if (!(std::isfinite(p.domain_size) && p.domain_size > 0.0f))
    fail("domain size must be positive and finite, got " + text(p.domain_size));
  if (p.domain_size > kMaxRandomSceneDomain)
    fail("domain size must be at most " + text(kMaxRandomSceneDomain) + ", got " +
         text(p.domain_size));
  if (p.sphere_count < 1 || p.sphere_count > kMaxRandomSceneSpheres)
    fail("sphere count must be between 1 and " + std::to_string(kMaxRandomSceneSpheres) + ", got " +
         std::to_string(p.sphere_count));
  const std::pair<const char*, float> probabilities[] = {
      {"diffuse", p.diffuse_probability},
      {"mirror", p.mirror_probability},
      {"transparent", p.transparent_probability}};
  for (const auto& [name, value] : probabilities)
    if (!(std::isfinite(value) && value >= 0.0f && value <= 1.0f))
      fail(std::string(name) + " probability must be in [0, 1], got " + text(value));
  const double sum =
      double(p.diffuse_probability) + p.mirror_probability + p.transparent_probability;
  if (std::abs(sum - 1.0) > 1e-6)
    fail("diffuse, mirror and transparent probabilities must sum to 1, got " + text(sum));
  if (!(std::isfinite(p.min_radius) && p.min_radius > 0.0f))
    fail("minimum radius must be positive and finite, got " + text(p.min_radius));
  if (!(std::isfinite(p.max_radius) && p.max_radius > 0.0f))
    fail("maximum radius must be positive and finite, got " + text(p.max_radius));
  if (p.min_radius > p.max_radius)
    fail("minimum radius " + text(p.min_radius) + " is larger than maximum radius " +
         text(p.max_radius));
  if (!(std::isfinite(p.gap_fraction) && p.gap_fraction > 0.0f && p.gap_fraction <= 1.0f))
    fail("gap fraction must be in (0, 1], got " + text(p.gap_fraction));
  const double gap = double(p.gap_fraction) * p.min_radius;
  if (2.0 * (double(p.max_radius) + gap) > p.domain_size)
    fail("maximum radius " + text(p.max_radius) + " is too large for a domain of size " +
         text(p.domain_size) + " (a sphere and its gap must fit: 2 * (radius + gap) <= size)");
  // Centres are stored as floats, spaced about 6e-8 * s apart near the walls; a gap that is
  // not well above that spacing would be lost to rounding when the scene is written and read.
  if (gap < 1e-6 * p.domain_size)
    fail("the gap between spheres (" + text(gap) + " = gap fraction * minimum radius) is too " +
         "small for float positions in a domain of size " + text(p.domain_size) +
         "; raise the minimum radius or shrink the domain");
  if (p.max_attempts < 1 || p.max_attempts > kMaxRandomSceneAttempts)
    fail("attempts per sphere must be between 1 and " + std::to_string(kMaxRandomSceneAttempts) +
         ", got " + std::to_string(p.max_attempts));
}

namespace detail {

/// A placed sphere as the grid keeps it: the float values that go into the file (so every
/// check sees exactly what a reader will), next to the link to the next sphere of its cell, so
/// that visiting a sphere costs one cache line.
struct GridSphere {
  float x, y, z, r;
  std::int32_t next;
};

/// A uniform grid over the domain holding the placed spheres by centre. Each cell is a singly
/// linked list of GridSphere. Where a dense array of cells would be much larger than the sphere
/// count (a sparse domain), cells are hashed into a table of about twice the sphere count
/// instead; two cells sharing a bucket only add candidates, which the radius computation
/// handles like any other far sphere.
class SphereGrid {
 public:
  /// Cells are at least `reach` wide; for_each_near visits every sphere whose centre is closer
  /// than `reach` to the query point.
  SphereGrid(double domain_size, double reach, std::size_t capacity)
      : origin_(-0.5 * domain_size), reach_(reach) {
    // Rounding the cell count down keeps every cell at least `reach` wide, so the 3x3x3 block
    // of cells around a point holds everything within reach of it.
    const double cells = std::max(1.0, std::floor(domain_size / reach));
    n_ = static_cast<int>(cells);
    cell_width_ = domain_size / cells;
    inv_cell_ = cells / domain_size;
    const double total = cells * cells * cells;
    std::size_t buckets = 1024;
    while (buckets < 2 * capacity)
      buckets *= 2;
    dense_ = total <= double(buckets) * 4.0;
    if (dense_) buckets = static_cast<std::size_t>(total);
    mask_ = buckets - 1;
    head_.assign(buckets, -1);
    spheres_.reserve(capacity);
  }

  void insert(float x, float y, float z, float r) {
    const std::size_t k = key(coord(x), coord(y), coord(z));
    spheres_.push_back({x, y, z, r, head_[k]});
    head_[k] = static_cast<std::int32_t>(spheres_.size() - 1);
  }

  /// Calls f(sphere) for every sphere whose centre lies within reach of (x, y, z), and maybe
  /// for some farther ones (more than once in the hashed mode). Of the 27 cells around the
  /// point, those whose nearest point is out of reach are skipped: about a quarter of them, and
  /// each skipped cell is a cache miss saved on large scenes.
  template <typename F>
  void for_each_near(double x, double y, double z, F&& f) const {
    const int c[3] = {coord(x), coord(y), coord(z)};
    const double p[3] = {x, y, z};
    // Per axis and offset -1, 0, +1: a lower bound on the squared distance from the point to
    // that slab of cells. The position inside the cell is clamped to [0, 1] so that rounding
    // at cell borders and the clamping of coord() can only lower the bounds.
    double gap2[3][3];
    for (int a = 0; a < 3; ++a) {
      const double inside = std::clamp((p[a] - origin_) * inv_cell_ - c[a], 0.0, 1.0);
      const double below = inside * cell_width_, above = (1.0 - inside) * cell_width_;
      gap2[a][0] = below * below;
      gap2[a][1] = 0.0;
      gap2[a][2] = above * above;
    }
    // A small margin covers the rounding of the bounds themselves.
    const double reach2 = reach_ * reach_ * (1.0 + 1e-9) + 1e-12;
    for (int dz = -1; dz <= 1; ++dz) {
      const int iz = c[2] + dz;
      if (iz < 0 || iz >= n_) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        const int iy = c[1] + dy;
        if (iy < 0 || iy >= n_) continue;
        const double gyz = gap2[2][dz + 1] + gap2[1][dy + 1];
        if (gyz >= reach2) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int ix = c[0] + dx;
          if (ix < 0 || ix >= n_ || gyz + gap2[0][dx + 1] >= reach2) continue;
          for (std::int32_t i = head_[key(ix, iy, iz)]; i >= 0;) {
            const GridSphere& s = spheres_[std::size_t(i)];
            f(s);
            i = s.next;
          }
        }
      }
    }
  }

 private:
  int coord(double v) const {
    const auto i = static_cast<long long>(std::floor((v - origin_) * inv_cell_));
    return static_cast<int>(std::clamp<long long>(i, 0, n_ - 1));
  }
  std::size_t key(int ix, int iy, int iz) const {
    const auto n = static_cast<std::size_t>(n_);
    if (dense_) return (std::size_t(iz) * n + std::size_t(iy)) * n + std::size_t(ix);
    return static_cast<std::size_t>(hash_values(ix, iy, iz)) & mask_;
  }

  double origin_;
  double reach_;
  double cell_width_ = 1.0;
  double inv_cell_ = 1.0;
  int n_ = 1;
  bool dense_ = true;
  std::size_t mask_ = 0;
  std::vector<std::int32_t> head_;
  std::vector<GridSphere> spheres_;
};

/// The file must not depend on the compiler's flags, and GNU mode lets GCC fuse a * b + c
/// into one rounding where the CPU has FMA. Spelling the fused form out gives the same bits
/// everywhere (std::fma is exactly rounded, in hardware or not). The rest of the generator's
/// arithmetic has no product feeding a sum, or products that are exact.
inline double distance(double dx, double dy, double dz) {
  return std::sqrt(std::fma(dx, dx, std::fma(dy, dy, dz * dz)));
}

/// Rounds a non-negative double to the nearest float not above it, so that an upper bound on
/// a radius still holds once the radius is stored as a float.
inline float float_at_most(double v) {
  float f = static_cast<float>(v);
  if (double(f) > v) f = std::nextafter(f, 0.0f);
  return f;
}

/// A uniform multiple of 1/1000 in [first, first + count) / 1000, from integers only so no
/// rounding can differ between builds. Colours and indices read better in the file that way,
/// and three digits are more than the eye can tell apart.
inline float random_thousandths(Pcg32& rng, std::uint32_t first, std::uint32_t count) {
  const auto k = static_cast<std::uint32_t>((std::uint64_t{rng.next_u32()} * count) >> 32);
  return static_cast<float>(double(first + k) / 1000.0);
}

}  // namespace detail

/// Generates the scene described by `p` (see the top of this file). Throws
/// std::invalid_argument for bad parameters (see validate). Spheres that cannot reach the
/// minimum radius after p.max_attempts centres are left out: compare placed with requested.
inline RandomSceneResult generate_random_scene(const RandomSceneParameters& p) {
  validate(p);
  const double size = p.domain_size;
  const double half = 0.5 * size;
  const double gap = double(p.gap_fraction) * p.min_radius;
  const double min_r = p.min_radius, max_r = p.max_radius;

  RandomSceneResult result;
  result.requested = p.sphere_count;
  result.gap = gap;
  SceneDescription& scene = result.scene;
  scene.source = "<random scene>";
  scene.image.width = 800;  // the report's settings
  scene.image.height = 800;
  scene.image.samples_per_pixel = 1000;
  scene.image.max_depth = 12;
  const auto s = static_cast<float>(size);
  scene.camera.position = Vec3(0.0f, 0.0f, 1.4f * s);
  scene.camera.look_at = Vec3(0.0f);
  scene.camera.up = Vec3(0.0f, 1.0f, 0.0f);
  scene.camera.fov_degrees = 60.0f;
  scene.camera.near = 0.0f;
  scene.antialias_sigma = 0.5f;
  scene.background = Color(0.0f);
  scene.medium_ior = 1.0f;
  // A light of intensity I at distance d gives irradiance I / d^2. With I = 0.6 s^2 and
  // 0.3 s^2 for the two lights, the domain's centre (about s away) gets a direct irradiance of
  // about 0.9 and the back wall (about 1.45 s away) about 0.4, whatever the domain size. That
  // looks low, but the closed room of albedo 0.75 multiplies it by up to 1 / (1 - 0.75) = 4
  // through interreflection. A preview render has a median radiance of about 0.3; lights
  // three times as bright (direct irradiance 1 to 3) clipped most of the image to white.
  const float s2 = s * s;
  const auto light = [&](Vec3 position, float intensity) {
    PointLight l;
    l.position = position;
    l.intensity = intensity;
    l.color = Color(1.0f);
    scene.lights.push_back(l);
  };
  light(Vec3(-0.25f * s, 0.3f * s, 0.9f * s), 0.6f * s2);
  light(Vec3(0.25f * s, 0.3f * s, 0.9f * s), 0.3f * s2);

  // Walls of radius 1e5 as in the report and smallpt; a larger domain gets proportionally
  // larger walls so that they stay as flat relative to the room (a wall bulges into the room
  // by about s^2 / (4 R) at the domain's edges, 0.016 for the report's s = 80).
  const float wall_radius = std::max(1e5f, 1250.0f * s);
  const auto wall = [&](Vec3 center, Color color) {
    SphereDescription w;
    w.center = center;
    w.radius = wall_radius;
    w.material.diffuse = 1.0f;
    w.material.diffuse_color = color;
    scene.spheres.push_back(w);
  };
  const Color white(0.75f), red(0.75f, 0.25f, 0.25f), green(0.25f, 0.75f, 0.25f);
  const float hs = 0.5f * s;
  wall(Vec3(-hs + wall_radius, 0.0f, 0.0f), red);    // left, surface at x = -s/2
  wall(Vec3(hs - wall_radius, 0.0f, 0.0f), green);   // right, x = s/2
  wall(Vec3(0.0f, -hs + wall_radius, 0.0f), white);  // floor, y = -s/2
  wall(Vec3(0.0f, hs - wall_radius, 0.0f), white);   // ceiling, y = s/2
  wall(Vec3(0.0f, 0.0f, -hs + wall_radius), white);  // back, z = -s/2
  // 3 * hs is exact in double, so this rounds once whether or not the compiler fuses it.
  const auto behind = static_cast<float>(3.0 * double(hs) - double(wall_radius));
  wall(Vec3(0.0f, 0.0f, behind), white);  // behind the camera, z = 3s/2
  result.wall_count = static_cast<int>(scene.spheres.size());
  scene.spheres.reserve(scene.spheres.size() + std::size_t(p.sphere_count));

  // Which sphere can constrain a new one? For a candidate centre c and a placed sphere j at
  // distance d, a radius r is allowed iff
  //   r <= |d - r_j| - gap   (disjoint from j when d >= r_j, inside j when d < r_j), or
  //   r >= d + r_j + gap     (containing j),
  // i.e. only r in the open interval (|d - r_j| - gap, d + r_j + gap) is forbidden. If
  // d >= 2 max_r + gap, then d - r_j - gap >= max_r since r_j <= max_r, so the interval lies
  // above every radius we may choose and j does not matter. With cells at least 2 max_r + gap
  // wide, every j that matters has its centre in one of the 27 cells around c's cell, and a
  // sphere can neither contain nor be contained by anything farther away.
  //
  // In fact a new sphere never contains an earlier one: an earlier sphere has the maximum
  // radius, or lies within `gap` of a wall, or of a sphere that a container would then have to
  // contain too, and so on down to a sphere of maximum radius. Nesting in the output therefore
  // always puts a later sphere inside an earlier one. The interval keeps the general rule
  // anyway: it costs nothing and does not rest on that argument.
  detail::SphereGrid grid(size, 2.0 * max_r + gap, std::size_t(p.sphere_count));
  struct Wall {
    double x, y, z, r;
  };
  std::vector<Wall> walls;
  for (const SphereDescription& w : scene.spheres)
    walls.push_back({w.center.x, w.center.y, w.center.z, w.radius});

  const double sum =
      double(p.diffuse_probability) + p.mirror_probability + p.transparent_probability;
  const double diffuse_below = p.diffuse_probability / sum;
  const double mirror_below = (double(p.diffuse_probability) + p.mirror_probability) / sum;
  // Centres come from the part of the domain where a sphere of the minimum radius fits.
  // Both are made floats so that centre_span * u (u has 24 bits) is exact in double and the
  // centre is rounded once whether or not the compiler fuses the multiply and the add.
  const double centre_low = static_cast<float>(-half + min_r + gap);
  const double centre_span = static_cast<float>(2.0 * (half - min_r - gap));

  std::vector<std::pair<double, double>> forbidden;  // reused: no allocation per attempt
  for (int index = 0; index < p.sphere_count; ++index) {
    Pcg32 rng(hash_values(p.seed, std::uint64_t(index)), 0x5eedULL);
    // The material is drawn before the centre and kept across attempts, so whether a sphere
    // fits never depends on its material and the placed spheres keep the probabilities.
    Material material;
    const double kind = rng.next_float();
    if (kind < diffuse_below) {
      material.diffuse = 1.0f;
      // A concrete colour: each channel in [0.1, 0.9], away from black and pure white.
      const float r = detail::random_thousandths(rng, 100, 801);
      const float g = detail::random_thousandths(rng, 100, 801);
      const float b = detail::random_thousandths(rng, 100, 801);
      material.diffuse_color = Color(r, g, b);
    } else if (kind < mirror_below) {
      material.diffuse = 0.0f;
      material.mirror = 1.0f;
    } else {
      material.diffuse = 0.0f;
      material.transparent = 1.0f;
      material.ior = detail::random_thousandths(rng, 1100, 801);  // in [1.1, 1.9]
    }

    for (int attempt = 0; attempt < p.max_attempts; ++attempt) {
      ++result.attempts;
      // One statement per draw: the order of a constructor's arguments is unspecified (GCC and
      // Clang differ), and the file must not depend on it.
      const auto x = static_cast<float>(centre_low + centre_span * rng.next_float());
      const auto y = static_cast<float>(centre_low + centre_span * rng.next_float());
      const auto z = static_cast<float>(centre_low + centre_span * rng.next_float());
      const Vec3 c(x, y, z);
      const double cx = c.x, cy = c.y, cz = c.z;
      // Everything is computed in double from the float values that will be written, so the
      // checks hold for the scene as a reader will see it.
      double upper = max_r;
      upper = std::min(upper, half - std::abs(cx) - gap);
      upper = std::min(upper, half - std::abs(cy) - gap);
      upper = std::min(upper, half - std::abs(cz) - gap);
      for (const Wall& w : walls)  // the room is inside every wall sphere
        upper = std::min(upper, w.r - detail::distance(cx - w.x, cy - w.y, cz - w.z) - gap);
      if (upper < min_r) continue;

      forbidden.clear();
      grid.for_each_near(cx, cy, cz, [&](const detail::GridSphere& o) {
        const double rj = o.r;
        const double d = detail::distance(cx - o.x, cy - o.y, cz - o.z);
        const double low = std::abs(d - rj) - gap, high = d + rj + gap;
        if (low < upper && high > min_r) forbidden.emplace_back(low, high);
      });
      // The largest allowed radius: start at the upper bound and drop to the lower end of any
      // forbidden interval containing it. Each interval can lower it at most once, and the
      // result is the top of the highest allowed stretch below upper.
      double r = upper;
      for (bool lowered = true; lowered && r >= min_r;) {
        lowered = false;
        for (const auto& [low, high] : forbidden)
          if (low < r && r < high) {
            r = low;
            lowered = true;
          }
      }
      if (r < min_r) continue;
      const float radius = detail::float_at_most(r);
      // Rounding down can only break a containment, and only if the allowed stretch is
      // narrower than a float step; such a centre is simply retried.
      bool fits = true;
      for (const auto& [low, high] : forbidden)
        fits = fits && !(low < radius && radius < high);
      if (!fits) continue;

      SphereDescription sphere;
      sphere.center = c;
      sphere.radius = radius;
      sphere.material = material;
      scene.spheres.push_back(sphere);
      grid.insert(c.x, c.y, c.z, radius);
      ++result.placed;
      break;
    }
  }
  return result;
}

}  // namespace glint
