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
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/detail/text.hpp"
#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

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

/// Values a random material draws uniformly, in steps of 1/1000: colours and indices read
/// better in the file that way, and three digits are more than the eye can tell apart.
struct ThousandthsRange {
  std::uint32_t low, high;  ///< in thousandths, both included
  double low_value() const { return low / 1000.0; }
  double high_value() const { return high / 1000.0; }
};
/// Each channel of a diffuse sphere's colour: away from black and from pure white.
inline constexpr ThousandthsRange kRandomColorChannel{100, 900};
/// The refractive index of a glass sphere.
inline constexpr ThousandthsRange kRandomIor{1100, 1900};

/// RandomSceneParameters the generator refuses. what() is "random scene: PROBLEM", problem()
/// the PROBLEM alone, for a program that puts its own name in front.
class RandomSceneError : public Error {
 public:
  explicit RandomSceneError(const std::string& problem)
      : Error(detail::concat({"random scene: ", problem})), problem_(problem) {}
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string problem_;
};

namespace detail {

/// The distance kept between any two surfaces, and between a sphere and the walls.
inline double surface_gap(const RandomSceneParameters& p) {
  return double(p.gap_fraction) * p.min_radius;
}

inline double probability_sum(const RandomSceneParameters& p) {
  return double(p.diffuse_probability) + p.mirror_probability + p.transparent_probability;
}

}  // namespace detail

/// Throws RandomSceneError naming the first bad parameter.
inline void validate(const RandomSceneParameters& p) {
  using detail::concat;
  // Numbers come back as the shortest text of the float, so what the user typed comes back
  // unchanged.
  const auto text = [](double v) { return detail::format_number(static_cast<float>(v)); };
  const auto fail = [](const std::string& problem) { throw RandomSceneError(problem); };
  if (!(std::isfinite(p.domain_size) && p.domain_size > 0.0f))
    fail(concat({"domain size must be positive and finite, got ", text(p.domain_size)}));
  if (p.domain_size > kMaxRandomSceneDomain)
    fail(concat({"domain size must be at most ", text(kMaxRandomSceneDomain), ", got ",
                 text(p.domain_size)}));
  if (p.sphere_count < 1 || p.sphere_count > kMaxRandomSceneSpheres)
    fail(concat({"sphere count must be between 1 and ", std::to_string(kMaxRandomSceneSpheres),
                 ", got ", std::to_string(p.sphere_count)}));
  const std::pair<const char*, float> probabilities[] = {
      {"diffuse", p.diffuse_probability},
      {"mirror", p.mirror_probability},
      {"transparent", p.transparent_probability}};
  for (const auto& [name, value] : probabilities)
    if (!(std::isfinite(value) && value >= 0.0f && value <= 1.0f))
      fail(concat({name, " probability must be in [0, 1], got ", text(value)}));
  const double sum = detail::probability_sum(p);
  if (std::abs(sum - 1.0) > 1e-6)
    fail(concat({"diffuse, mirror and transparent probabilities must sum to 1, got ", text(sum)}));
  if (!(std::isfinite(p.min_radius) && p.min_radius > 0.0f))
    fail(concat({"minimum radius must be positive and finite, got ", text(p.min_radius)}));
  if (!(std::isfinite(p.max_radius) && p.max_radius > 0.0f))
    fail(concat({"maximum radius must be positive and finite, got ", text(p.max_radius)}));
  if (p.min_radius > p.max_radius)
    fail(concat({"minimum radius ", text(p.min_radius), " is larger than maximum radius ",
                 text(p.max_radius)}));
  if (!(std::isfinite(p.gap_fraction) && p.gap_fraction > 0.0f && p.gap_fraction <= 1.0f))
    fail(concat({"gap fraction must be in (0, 1], got ", text(p.gap_fraction)}));
  const double gap = detail::surface_gap(p);
  if (2.0 * (double(p.max_radius) + gap) > p.domain_size)
    fail(concat({"maximum radius ", text(p.max_radius), " is too large for a domain of size ",
                 text(p.domain_size),
                 " (a sphere and its gap must fit: 2 * (radius + gap) <= size)"}));
  // Centres are stored as floats, spaced about 6e-8 * s apart near the walls; a gap that is
  // not well above that spacing would be lost to rounding when the scene is written and read.
  if (gap < 1e-6 * p.domain_size)
    fail(concat({"the gap between spheres (", text(gap),
                 " = gap fraction * minimum radius) is too small for float positions in a "
                 "domain of size ",
                 text(p.domain_size), "; raise the minimum radius or shrink the domain"}));
  if (p.max_attempts < 1 || p.max_attempts > kMaxRandomSceneAttempts)
    fail(concat({"attempts per sphere must be between 1 and ",
                 std::to_string(kMaxRandomSceneAttempts), ", got ",
                 std::to_string(p.max_attempts)}));
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

/// A uniform value of `range`, from integers only so that no rounding can differ between
/// builds.
inline float random_thousandths(Pcg32& rng, ThousandthsRange range) {
  const std::uint32_t count = range.high - range.low + 1;
  const auto k = static_cast<std::uint32_t>((std::uint64_t{rng.next_u32()} * count) >> 32);
  return static_cast<float>(double(range.low + k) / 1000.0);
}

/// The random stream of the sphere with the given index.
inline Pcg32 sphere_stream(std::uint64_t seed, int index) {
  return Pcg32(hash_values(seed, std::uint64_t(index)), 0x5eedULL);
}

/// The camera at z = 1.4 s looking at the domain, and two lights above it.
inline void add_camera_and_lights(SceneDescription& scene, float s) {
  scene.camera.position = Vec3(0.0f, 0.0f, 1.4f * s);
  scene.camera.look_at = Vec3(0.0f);
  scene.camera.up = Vec3(0.0f, 1.0f, 0.0f);
  scene.camera.fov_degrees = 60.0f;
  // Intensities grow with s^2 so that the irradiance I / d^2 does not depend on the domain's
  // size: about 0.9 at its centre (about s away) and 0.4 on the back wall (about 1.45 s). The
  // closed room of albedo 0.75 multiplies that by up to 4 through interreflection.
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
}

/// The six walls of the room, red on the left and green on the right as in the report.
inline void add_walls(SceneDescription& scene, float s) {
  // Radius 1e5 as in the report and smallpt; a larger domain gets proportionally larger walls
  // so that they stay as flat relative to the room (a wall bulges into the room by about
  // s^2 / (4 R) at the domain's edges).
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
}

/// Draws a sphere's material: its kind with the parameters' probabilities, then its colour or
/// refractive index.
class MaterialDraw {
 public:
  explicit MaterialDraw(const RandomSceneParameters& p)
      : diffuse_below_(p.diffuse_probability / probability_sum(p)),
        mirror_below_((double(p.diffuse_probability) + p.mirror_probability) / probability_sum(p)) {
  }

  Material operator()(Pcg32& rng) const {
    Material material;
    const double kind = rng.next_float();
    if (kind < diffuse_below_) {
      material.diffuse = 1.0f;
      // One statement per draw: the order of a constructor's arguments is unspecified (GCC
      // and Clang differ), and the file must not depend on it.
      const float r = random_thousandths(rng, kRandomColorChannel);
      const float g = random_thousandths(rng, kRandomColorChannel);
      const float b = random_thousandths(rng, kRandomColorChannel);
      material.diffuse_color = Color(r, g, b);
    } else if (kind < mirror_below_) {
      material.diffuse = 0.0f;
      material.mirror = 1.0f;
    } else {
      material.diffuse = 0.0f;
      material.transparent = 1.0f;
      material.ior = random_thousandths(rng, kRandomIor);
    }
    return material;
  }

 private:
  double diffuse_below_;
  double mirror_below_;
};

/// Places the random spheres one at a time, each as large as the room and the spheres placed
/// before it allow.
///
/// For a candidate centre c and a placed sphere j at distance d, a radius r is allowed iff
///   r <= |d - r_j| - gap   (disjoint from j when d >= r_j, inside j when d < r_j), or
///   r >= d + r_j + gap     (containing j),
/// i.e. only r in the open interval (|d - r_j| - gap, d + r_j + gap) is forbidden. Since
/// r_j <= max_r, a sphere j with d >= 2 max_r + gap forbids nothing below max_r, so the grid's
/// cells are that wide and only the 27 cells around c need to be searched.
class SpherePlacer {
 public:
  struct Placed {
    Vec3 center;
    float radius;
  };

  /// `walls` are the room's walls: the room is the inside of every one of them.
  SpherePlacer(const RandomSceneParameters& p, const std::vector<SphereDescription>& walls)
      : half_(0.5 * double(p.domain_size)),
        gap_(surface_gap(p)),
        min_r_(p.min_radius),
        max_r_(p.max_radius),
        centre_low_(static_cast<float>(-half_ + min_r_ + gap_)),
        centre_span_(static_cast<float>(2.0 * (half_ - min_r_ - gap_))),
        grid_(p.domain_size, 2.0 * max_r_ + gap_, std::size_t(p.sphere_count)) {
    for (const SphereDescription& w : walls)
      walls_.push_back({w.center.x, w.center.y, w.center.z, w.radius});
  }

  /// Tries up to `max_attempts` centres drawn from `rng` and keeps the first where a sphere of
  /// at least the minimum radius fits, with the largest radius that fits there. `attempts`
  /// counts the centres tried.
  std::optional<Placed> place(Pcg32& rng, int max_attempts, long long& attempts) {
    for (int attempt = 0; attempt < max_attempts; ++attempt) {
      ++attempts;
      const Vec3 c = random_centre(rng);
      if (const std::optional<float> radius = largest_radius(c)) {
        grid_.insert(c.x, c.y, c.z, *radius);
        return Placed{c, *radius};
      }
    }
    return std::nullopt;
  }

 private:
  struct Wall {
    double x, y, z, r;
  };

  Vec3 random_centre(Pcg32& rng) const {
    // One statement per draw, as in MaterialDraw.
    const double low = centre_low_, span = centre_span_;
    const auto x = static_cast<float>(low + span * rng.next_float());
    const auto y = static_cast<float>(low + span * rng.next_float());
    const auto z = static_cast<float>(low + span * rng.next_float());
    return Vec3(x, y, z);
  }

  /// The largest radius a sphere centred at c may have, if it is at least the minimum. It is
  /// computed in double from the float centre that will be written, so that the checks hold
  /// for the scene as a reader will see it.
  std::optional<float> largest_radius(const Vec3& c) {
    const double cx = c.x, cy = c.y, cz = c.z;
    const double upper = room_bound(cx, cy, cz);
    if (upper < min_r_) return std::nullopt;

    forbidden_.clear();
    grid_.for_each_near(cx, cy, cz, [&](const GridSphere& o) {
      const double rj = o.r;
      const double d = distance(cx - o.x, cy - o.y, cz - o.z);
      const double low = std::abs(d - rj) - gap_, high = d + rj + gap_;
      if (low < upper && high > min_r_) forbidden_.emplace_back(low, high);
    });
    // Start at the upper bound and drop to the lower end of any forbidden interval containing
    // it. Each interval can lower it at most once, and the result is the top of the highest
    // allowed stretch below upper.
    double r = upper;
    for (bool lowered = true; lowered && r >= min_r_;) {
      lowered = false;
      for (const auto& [low, high] : forbidden_)
        if (low < r && r < high) {
          r = low;
          lowered = true;
        }
    }
    if (r < min_r_) return std::nullopt;
    // Rounding down can only break a containment, and only if the allowed stretch is narrower
    // than a float step; such a centre is simply given up.
    const float radius = float_at_most(r);
    for (const auto& [low, high] : forbidden_)
      if (low < radius && radius < high) return std::nullopt;
    return radius;
  }

  /// The largest radius the domain's cube and the walls allow at (cx, cy, cz).
  double room_bound(double cx, double cy, double cz) const {
    double upper = max_r_;
    upper = std::min(upper, half_ - std::abs(cx) - gap_);
    upper = std::min(upper, half_ - std::abs(cy) - gap_);
    upper = std::min(upper, half_ - std::abs(cz) - gap_);
    for (const Wall& w : walls_)
      upper = std::min(upper, w.r - distance(cx - w.x, cy - w.y, cz - w.z) - gap_);
    return upper;
  }

  double half_, gap_, min_r_, max_r_;
  // Centres come from the part of the domain where a sphere of the minimum radius fits. The
  // bounds are floats so that span * u (u has 24 bits) is exact in double and a centre is
  // rounded once whether or not the compiler fuses the multiply and the add. They are stored
  // as floats, not as doubles holding float values: GCC 12.2 at -O2 and above miscompiles the
  // two double-to-float-to-double conversions once it has vectorised them, dropping the
  // rounding.
  float centre_low_, centre_span_;
  std::vector<Wall> walls_;
  SphereGrid grid_;
  std::vector<std::pair<double, double>> forbidden_;  // reused: no allocation per attempt
};

}  // namespace detail

/// Generates the scene described by `p` (see the top of this file). Throws RandomSceneError
/// for bad parameters (see validate). Spheres that cannot reach the minimum radius after
/// p.max_attempts centres are left out: compare placed with requested.
inline RandomSceneResult generate_random_scene(const RandomSceneParameters& p) {
  validate(p);
  RandomSceneResult result;
  result.requested = p.sphere_count;
  result.gap = detail::surface_gap(p);
  SceneDescription& scene = result.scene;
  scene.source = "<random scene>";
  detail::add_camera_and_lights(scene, p.domain_size);
  detail::add_walls(scene, p.domain_size);
  result.wall_count = static_cast<int>(scene.spheres.size());
  scene.spheres.reserve(scene.spheres.size() + std::size_t(p.sphere_count));

  const detail::MaterialDraw draw_material(p);
  detail::SpherePlacer placer(p, scene.spheres);
  for (int index = 0; index < p.sphere_count; ++index) {
    Pcg32 rng = detail::sphere_stream(p.seed, index);
    // The material is drawn before the centre and kept across attempts, so whether a sphere
    // fits never depends on its material and the placed spheres keep the probabilities.
    const Material material = draw_material(rng);
    if (const auto placed = placer.place(rng, p.max_attempts, result.attempts)) {
      SphereDescription sphere;
      sphere.center = placed->center;
      sphere.radius = placed->radius;
      sphere.material = material;
      scene.spheres.push_back(sphere);
      ++result.placed;
    }
  }
  return result;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
