#pragma once
// The render-ready scene: immutable after build, shared read-only by all render threads.
// Geometry lives in three accelerators: a WallSet for huge spheres such as walls and floors,
// whose boxes would swallow everything in a hierarchy and whose surfaces near the camera need
// the anchored kernel (geometry/ray_sphere.hpp) to be exact in float; a SphereSet (structure
// of arrays, scanned with SIMD) for the other spheres of small scenes; and a SphereBvh for the
// many ordinary spheres of large scenes. What shading needs per sphere lives in one contiguous
// array of SurfaceProperties, touched only for a hit sphere. Of the description, the scene
// keeps only what rendering and its error messages need.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/common.hpp>

#include "glint/geometry/light_buffer.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/ray_batch_kernel.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/geometry/wall_set.hpp"
#include "glint/instruction_set.hpp"
#include "glint/scene/emitters.hpp"
#include "glint/scene/environment.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/sphere_texture.hpp"
#include "glint/scene/validate.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// What shading needs to know of one sphere.
struct SurfaceProperties {
  Material material;
  Vec3 center;
  float ior_outside;  ///< index of the medium around the sphere, from the inclusion tree
  ShadingKind shading;
  bool fully_transparent;  ///< the report applies Fresnel to these spheres only
  /// The mirror lobe is rough or a metal's (Material::has_mirror_finish): shading reads the
  /// material's roughness and metal index only where this is set.
  bool mirror_finish;
  std::uint32_t emitter;  ///< index in Scene::emitters(), or kNotAnEmitter
};

inline constexpr std::uint32_t kNotAnEmitter = std::numeric_limits<std::uint32_t>::max();

/// Where a ray meets a sphere, with what shading needs of the geometry there.
struct SurfaceHit {
  Vec3 point;
  Vec3 outward_normal;
  Vec3 local_direction;  ///< unit vector from the sphere's centre to the point (for shading)
  std::uint32_t sphere;
};

/// A ball: centre and radius.
struct BoundingSphere {
  Vec3 center{0.0f};
  float radius = 0.0f;
};

/// The ball about the middle of the box of a scene's spheres that `counts` (every sphere but the
/// walls, for Scene), point lights and camera that holds them all, its radius rounded up.
template <typename Counts>
BoundingSphere bounding_sphere_of(const SceneDescription& description, Counts&& counts) {
  glm::dvec3 low(description.camera.position), high(description.camera.position);
  const auto extend = [&](const Vec3& center, float radius) {
    low = glm::min(low, glm::dvec3(center) - double(radius));
    high = glm::max(high, glm::dvec3(center) + double(radius));
  };
  for (const SphereDescription& sphere : description.spheres)
    if (counts(sphere)) extend(sphere.center, sphere.radius);
  for (const PointLight& light : description.lights)
    extend(light.position, 0.0f);
  const glm::dvec3 middle = 0.5 * (low + high);
  double radius = glm::length(glm::dvec3(description.camera.position) - middle);
  for (const SphereDescription& sphere : description.spheres)
    if (counts(sphere))
      radius = std::max(radius, glm::length(glm::dvec3(sphere.center) - middle) + sphere.radius);
  for (const PointLight& light : description.lights)
    radius = std::max(radius, glm::length(glm::dvec3(light.position) - middle));
  return {Vec3(middle), std::max(float(radius * (1.0 + 1e-6)), 1e-3f)};
}

class Scene {
 public:
  /// Validates the description (SceneError on any problem, with its line) and builds the
  /// accelerators and the inclusion tree.
  static Scene build(const SceneDescription& description) {
    return build(description, kLinearSceneSize);
  }

  /// build, with the spheres of scenes up to `linear_scene_size` spheres (rather than
  /// kLinearSceneSize) scanned linearly and those of larger ones put in the BVH: for the
  /// benchmarks and tests that compare the two on one scene.
  static Scene build(const SceneDescription& description, std::size_t linear_scene_size) {
    validate(description);
    Scene scene;
    scene.source_ = description.source;
    scene.image_ = description.image;
    scene.camera_ = description.camera;
    scene.antialias_sigma_ = description.antialias_sigma;
    scene.environment_ =
        description.background_image
            ? Environment(description.background_image, description.background_placement,
                          description.background_scale)
            : Environment(description.background);
    scene.background_line_ = description.background_line;
    scene.lights_ = description.lights;
    const InclusionTree tree = build_inclusion_tree(description);
    const float huge_radius = huge_radius_threshold(description);
    scene.bounds_ = bounding_sphere_of(description, [&](const SphereDescription& sphere) {
      return !is_wall(sphere, huge_radius, description.camera.position);
    });
    const bool linear = description.spheres.size() <= linear_scene_size;
    std::vector<SphereBvh::Input> hierarchy_spheres;
    std::vector<SphereEmitter> emitters;
    scene.surfaces_.reserve(description.spheres.size());
    scene.sphere_lines_.reserve(description.spheres.size());
    for (std::size_t i = 0; i < description.spheres.size(); ++i) {
      const SphereDescription& sphere = description.spheres[i];
      const auto id = static_cast<std::uint32_t>(i);
      if (is_wall(sphere, huge_radius, description.camera.position))
        scene.walls_.add(sphere.center, sphere.radius, id, description.camera.position);
      else if (linear)
        scene.linear_.add(sphere.center, sphere.radius, id);
      else
        hierarchy_spheres.push_back({sphere.center, sphere.radius, id});
      std::uint32_t emitter = kNotAnEmitter;
      if (sphere.material.is_emissive()) {
        emitter = static_cast<std::uint32_t>(emitters.size());
        emitters.push_back({sphere.center, sphere.radius, sphere.material.emission, id});
      }
      scene.surfaces_.push_back(SurfaceProperties{
          sphere.material, sphere.center, tree.outside_ior[i], sphere.shading,
          sphere.material.is_fully_transparent(), sphere.material.has_mirror_finish(), emitter});
      scene.sphere_lines_.push_back(sphere.line);
      if (sphere.shading == ShadingKind::texture) {
        if (scene.sphere_textures_.empty())
          scene.sphere_textures_.assign(description.spheres.size(), kNoTexture);
        scene.sphere_textures_[i] = static_cast<std::uint32_t>(scene.textures_.size());
        scene.textures_.emplace_back(sphere.texture, sphere.texture_placement);
      }
    }
    scene.hierarchy_ = SphereBvh(std::move(hierarchy_spheres));
    scene.emitters_ = EmitterTable(std::move(emitters));
    scene.add_light_buffers();
    return scene;
  }

  /// The nearest sphere along the ray in (t_min, t_max), if any; of spheres at exactly the
  /// same distance, the one of lowest index.
  std::optional<SphereHit> closest_hit(const Ray& ray) const {
    SphereHit hit;
    hit.t = ray.t_max;
    bool found = origin_sphere_hit(ray, hit);
    if (!walls_.empty())
      found = closest_linear_hit(ray, hit) || found;
    else if (!linear_.empty())
      found = linear_.closest_hit(ray, hit) || found;
    if (!hierarchy_.empty()) found = hierarchy_.closest_hit(ray, hit) || found;
    if (!found) return std::nullopt;
    return hit;
  }

  /// Whether any sphere blocks the ray in (t_min, t_max).
  bool occluded(const Ray& ray) const {
    SphereHit hit;
    hit.t = ray.t_max;
    return origin_sphere_hit(ray, hit) ||
           (!walls_.empty() ? any_linear_hit(ray) : !linear_.empty() && linear_.any_hit(ray)) ||
           (!hierarchy_.empty() && hierarchy_.any_hit(ray));
  }

  SurfaceHit surface_hit(const Ray& ray, const SphereHit& hit) const {
    const Vec3 point = ray.at(hit.t);
    const Vec3& center = surfaces_[hit.sphere].center;
    const Vec3 normal = glm::normalize(point - center);
    return {point, normal, normal, hit.sphere};
  }

  const SurfaceProperties& surface(std::uint32_t sphere) const { return surfaces_[sphere]; }
  std::size_t sphere_count() const { return surfaces_.size(); }
  /// The images on the spheres of ShadingKind::texture, placed, one per such sphere.
  const std::vector<SphereTexture>& textures() const { return textures_; }
  /// The image on a sphere of ShadingKind::texture, placed; null for any other sphere.
  const SphereTexture* sphere_texture(std::uint32_t sphere) const {
    if (sphere >= sphere_textures_.size() || sphere_textures_[sphere] == kNoTexture) return nullptr;
    return &textures_[sphere_textures_[sphere]];
  }
  /// The line of the scene file that defined a sphere (0 if it did not come from a file).
  int sphere_line(std::uint32_t sphere) const { return sphere_lines_[sphere]; }
  const std::vector<PointLight>& lights() const { return lights_; }
  /// The emissive spheres, for light sampling.
  const EmitterTable& emitters() const { return emitters_; }
  const CameraDescription& camera() const { return camera_; }
  /// The light of the rays that escape: the background's colour or its image.
  const Environment& environment() const { return environment_; }
  /// The line of the scene file that set the background (0 if none did).
  int background_line() const { return background_line_; }
  /// A ball that holds every sphere but the walls (huge spheres such as a floor, and those whose
  /// surface is nearer the camera than their radius), every point light and the camera: where
  /// light paths from the environment enter the scene (render/lights/environment_light.hpp).
  const BoundingSphere& bounds() const { return bounds_; }
  /// The image settings and pixel filter width the scene asks for.
  const ImageDescription& image() const { return image_; }
  float antialias_sigma() const { return antialias_sigma_; }
  /// The file name (or label) the scene came from, for error messages.
  const std::string& source() const { return source_; }

  /// closest_hit for each active lane of `rays`: its hit in `hits` (t = kInfinity and
  /// kNoSphere where there is none); returns the lanes with a hit. Exactly closest_hit's answer
  /// lane by lane. Inactive lanes of `hits` are left as they were.
  ///
  /// With AVX2 the walls and the linear set are scanned for the eight rays at once
  /// (ray_batch_kernel.hpp) and the BVH traversed as `coherence` suggests
  /// (SphereBvh::closest_hits); without, this is closest_hit lane by lane.
  LaneMask closest_hits(const RayBatch& rays, LaneMask active, HitBatch& hits,
                        RayCoherence coherence = RayCoherence::unknown) const {
#ifdef GLINT_AVX2
    return closest_hits_simd<avx2::Lanes8>(&rays, active, &hits, coherence);
#else
    (void)coherence;
    return closest_hits_per_lane(rays, active, hits);
#endif
  }

  /// closest_hits for the sixteen rays of two batches, those of rays[0] in bits 0-7 of
  /// `active` and of the answer, those of rays[1] in bits 8-15. With AVX-512 the walls and the
  /// linear set are scanned for all sixteen at once; else batch by batch. The same answers.
  LaneMask closest_hits(std::span<const RayBatch, 2> rays, LaneMask active,
                        std::span<HitBatch, 2> hits,
                        RayCoherence coherence = RayCoherence::unknown) const {
#ifdef GLINT_AVX512
    return closest_hits_simd<avx2::Lanes16>(rays.data(), active, hits.data(), coherence);
#else
    return closest_hits(rays[0], batch_lanes(active, 0), hits[0], coherence) |
           closest_hits(rays[1], batch_lanes(active, 1), hits[1], coherence) << RayBatch::kWidth;
#endif
  }

  /// occluded for each active lane of `rays`: the lanes whose ray is blocked. With AVX2 in
  /// the same way as closest_hits, each step for the lanes that no earlier one blocked.
  LaneMask occluded(const RayBatch& rays, LaneMask active,
                    RayCoherence coherence = RayCoherence::unknown) const {
#ifdef GLINT_AVX2
    return occluded_simd<avx2::Lanes8>(&rays, active, coherence);
#else
    (void)coherence;
    return occluded_per_lane(rays, active);
#endif
  }

  /// occluded for the sixteen rays of two batches, as closest_hits for two.
  LaneMask occluded(std::span<const RayBatch, 2> rays, LaneMask active,
                    RayCoherence coherence = RayCoherence::unknown) const {
#ifdef GLINT_AVX512
    return occluded_simd<avx2::Lanes16>(rays.data(), active, coherence);
#else
    return occluded(rays[0], batch_lanes(active, 0), coherence) |
           occluded(rays[1], batch_lanes(active, 1), coherence) << RayBatch::kWidth;
#endif
  }

  /// The batched queries through the single-ray ones, lane by lane: the reference.
  LaneMask closest_hits_per_lane(const RayBatch& rays, LaneMask active, HitBatch& hits) const {
    LaneMask found = 0;
    for_each_lane(active, [&](int lane) {
      const std::optional<SphereHit> hit = closest_hit(rays.get(lane));
      hits.set(lane, hit.value_or(SphereHit{}));
      if (hit) found |= LaneMask(1) << lane;
    });
    return found;
  }
  LaneMask occluded_per_lane(const RayBatch& rays, LaneMask active) const {
    LaneMask blocked = 0;
    for_each_lane(active, [&](int lane) {
      if (occluded(rays.get(lane))) blocked |= LaneMask(1) << lane;
    });
    return blocked;
  }

  /// Light buffers are made for a linear set of at least this many spheres: a ray's cell
  /// costs about what a scan of that many spheres costs per ray of a batch of eight. With
  /// cells, lamp-room, cornell and nested-glass (3 to 5 spheres) took 8-30% more instructions
  /// for their shadow rays, random40 (40) 43% fewer (callgrind).
  static constexpr std::size_t kMinLightBufferSpheres = 24;

  /// Point lights beyond this many (in the scene's order) have no light buffer: a batch of
  /// shadow rays looks for its lights among the buffers, one test per buffer.
  static constexpr std::size_t kMaxLightBuffers = 16;

  /// Scenes up to this many spheres are scanned linearly: with SIMD, that beats a hierarchy.
  /// (Their walls, like those of larger scenes, are in the WallSet.) Closest hits cross over
  /// between 64 and 80 random spheres (bench/features_bench.cpp, BM_LinearOrBvhRandom).
  static constexpr std::size_t kLinearSceneSize = 72;

 private:
  Scene() = default;

  /// Spheres at least this large are walls: 100 times the median radius, such as the walls of
  /// a room (radius 1e5 around a scene of size 100), which would make every box of a hierarchy
  /// enormous.
  static float huge_radius_threshold(const SceneDescription& description) {
    if (description.spheres.empty()) return 0.0f;
    std::vector<float> radii;
    radii.reserve(description.spheres.size());
    for (const SphereDescription& s : description.spheres)
      radii.push_back(s.radius);
    auto middle = radii.begin() + std::ptrdiff_t(radii.size() / 2);
    std::nth_element(radii.begin(), middle, radii.end());
    return 100.0f * *middle;
  }

  /// Whether a sphere goes to the WallSet: a huge one (see huge_radius_threshold), or one whose
  /// surface is nearer the camera than its radius, where the anchored kernel's error, about u
  /// times the distance from the camera to the surface, is below the plain kernel's u r. This
  /// catches what the median misses: a lone floor, or a room whose walls are most of its
  /// spheres.
  static bool is_wall(const SphereDescription& sphere, float huge_radius, const Vec3& camera) {
    if (sphere.radius >= huge_radius) return true;
    const double distance = glm::length(glm::dvec3(camera) - glm::dvec3(sphere.center));
    return std::abs(distance - double(sphere.radius)) < double(sphere.radius);
  }

  /// The bits of batch `batch` of a mask over several batches, as a mask of that batch.
  static LaneMask batch_lanes(LaneMask lanes, int batch) {
    return (lanes >> (RayBatch::kWidth * batch)) & RayBatch::kAllLanes;
  }

#ifdef GLINT_AVX2
  /// The batched queries for the L::kWidth / 8 batches from `rays` on, with each of the
  /// single-ray ones' steps run for all lanes at once, the walls and the linear set in registers
  /// of L, the rest batch by batch.
  template <class L>
  LaneMask closest_hits_simd(const RayBatch* rays, LaneMask active, HitBatch* hits,
                             RayCoherence coherence) const {
    constexpr int kBatches = L::kWidth / RayBatch::kWidth;
    // closest_hit's steps, each for all lanes: the origin sphere, the linear sets, the BVH.
    HitBatch hit[kBatches];
    LaneMask found = 0;
    for (int i = 0; i < kBatches; ++i) {
      hit[i] = no_hits_within(rays[i]);
      found |= origin_sphere_hits(rays[i], batch_lanes(active, i), hit[i])
               << (RayBatch::kWidth * i);
    }
    if (!walls_.empty() || !linear_.empty()) {
      // hit_to_beat in every lane: the origin sphere's hit where there is one, else (t_max, 0);
      // t = -infinity, which nothing beats, in a lane without a ray.
      const BasicHitLanes<L> so_far = avx2::hit_lanes<L>(hit);
      BasicHitLanes<L> best(L::select(L::mask_of_bits(active), so_far.t, L::splat(-kInfinity)),
                            L::keep(L::mask_of_bits(found), so_far.sphere));
      const LaneMask linear_found =
          avx2::closest_hits(avx2::ray_lanes<L>(rays), best, walls_.columns(), linear_.columns()) &
          active;
      avx2::store_lanes(best, linear_found, hit);
      found |= linear_found;
    }
    LaneMask answered = 0;
    for (int i = 0; i < kBatches; ++i) {
      const LaneMask lanes = batch_lanes(active, i);
      LaneMask batch_found = batch_lanes(found, i);
      if (!hierarchy_.empty() && lanes != 0) {
        SphereHit tree[RayBatch::kWidth];
        for_each_lane(lanes, [&](int lane) { tree[lane] = hit[i].get(lane); });
        const LaneMask tree_found = hierarchy_.closest_hits(rays[i], lanes, tree, coherence);
        for_each_lane(tree_found, [&](int lane) { hit[i].set(lane, tree[lane]); });
        batch_found |= tree_found;
      }
      // The lanes without a hit say so (t = kInfinity, no sphere); the others give theirs.
      avx2::store_lanes(avx2::HitLanes(SphereHit{}), lanes & ~batch_found, &hits[i]);
      avx2::store_lanes(avx2::hit_lanes(&hit[i]), batch_found, &hits[i]);
      answered |= batch_found << (RayBatch::kWidth * i);
    }
    return answered;
  }
  template <class L>
  LaneMask occluded_simd(const RayBatch* rays, LaneMask active, RayCoherence coherence) const {
    constexpr int kBatches = L::kWidth / RayBatch::kWidth;
    LaneMask blocked = 0;
    for (int i = 0; i < kBatches; ++i) {
      HitBatch hit = no_hits_within(rays[i]);
      blocked |= origin_sphere_hits(rays[i], batch_lanes(active, i), hit) << (RayBatch::kWidth * i);
    }
    LaneMask pending = active & ~blocked;
    // The lanes that the linear set has still to answer for: those of shadow rays toward a
    // point light are answered by its light buffer, from the few spheres it lists.
    LaneMask linear_pending = pending;
    if (pending != 0 && !light_buffers_.empty()) {
      for (int i = 0; i < kBatches; ++i) {
        const LaneMask lanes = batch_lanes(pending, i);
        if (lanes == 0) continue;
        LaneMask served = 0;
        blocked |= light_buffer_hits(rays[i], lanes, served) << (RayBatch::kWidth * i);
        linear_pending &= ~(served << (RayBatch::kWidth * i));
      }
      pending = active & ~blocked;
    }
    if (pending != 0 && (!walls_.empty() || !linear_.empty())) {
      // All lanes at once, coherent or not. This scan stops once every lane is blocked, the
      // single-ray one at its ray's first blocker: for random shadow rays in a room of 40
      // spheres it is 0.92x as fast as eight single-ray queries, but a scan per lane measured
      // no better (0.88x, its overhead); for shadow rays of camera blocks it is 1.4x.
      const BasicRayLanes<L> lanes = avx2::ray_lanes<L>(rays);
      const typename L::F t_max = avx2::column_lanes<L>(rays, &RayBatch::t_max);
      // The bound, hit_to_beat(ray, SphereHit{}): (t_max, 0); -infinity without a ray.
      const auto bound = [&](LaneMask with_ray) {
        return BasicHitLanes<L>(L::select(L::mask_of_bits(with_ray), t_max, L::splat(-kInfinity)),
                                L::splat(std::int32_t(0)));
      };
      if (linear_pending == pending) {
        blocked |=
            avx2::any_hits(lanes, bound(pending), pending, walls_.columns(), linear_.columns());
      } else {
        if (!walls_.empty())
          blocked |= avx2::any_hits(lanes, bound(pending), pending, walls_.columns());
        linear_pending &= ~blocked;
        if (linear_pending != 0)
          blocked |=
              avx2::any_hits(lanes, bound(linear_pending), linear_pending, linear_.columns());
      }
      pending = active & ~blocked;
    }
    if (pending != 0 && !hierarchy_.empty()) {
      for (int i = 0; i < kBatches; ++i) {
        const LaneMask lanes = batch_lanes(pending, i);
        if (lanes != 0)
          blocked |= hierarchy_.any_hits(rays[i], lanes, coherence) << (RayBatch::kWidth * i);
      }
    }
    return blocked;
  }
#endif

  // The queries of the walls and the linear set together: in one 8-wide scan where there is
  // AVX2, so that a small scene pays one ray broadcast and one reduction for both. They stay
  // out of line, one copy for the single-ray queries of every caller.
  [[gnu::noinline]] bool closest_linear_hit(const Ray& ray, SphereHit& hit) const {
#ifdef GLINT_AVX2
    SphereHit best = hit_to_beat(ray, hit);
    if (!avx2::closest_hit(ray, best, walls_.columns(), linear_.columns())) return false;
    hit = best;
    return true;
#else
    const bool found = walls_.closest_hit(ray, hit);
    return (!linear_.empty() && linear_.closest_hit(ray, hit)) || found;
#endif
  }
  [[gnu::noinline]] bool any_linear_hit(const Ray& ray) const {
#ifdef GLINT_AVX2
    return avx2::any_hit(ray, hit_to_beat(ray, SphereHit{}), walls_.columns(), linear_.columns());
#else
    return walls_.any_hit(ray) || (!linear_.empty() && linear_.any_hit(ray));
#endif
  }

  /// Light buffers for the first kMaxLightBuffers point lights, where the linear set is large
  /// enough for them to pay (kMinLightBufferSpheres) and small enough for a buffer to list.
  void add_light_buffers() {
#ifdef GLINT_AVX2
    static_assert(kLinearSceneSize <= LightBuffer::kMaxSpheres);
    if (linear_.size() < kMinLightBufferSpheres || linear_.size() > LightBuffer::kMaxSpheres)
      return;
    const std::size_t buffered = std::min(lights_.size(), kMaxLightBuffers);
    for (std::size_t i = 0; i < buffered; ++i)
      light_buffers_.emplace_back(lights_[i].position, linear_.columns());
#endif
  }

#ifdef GLINT_AVX2
  /// The lanes of `pending` whose ray a light buffer takes (one ending at its light) go into
  /// `served`; returns those of them that a sphere of the linear set blocks.
  LaneMask light_buffer_hits(const RayBatch& rays, LaneMask pending, LaneMask& served) const {
    const avx2::RayLanes lanes = avx2::ray_lanes(rays);
    const __m256 t_max = _mm256_load_ps(rays.t_max);
    LaneMask unmatched = pending;
    LaneMask blocked = 0;
    alignas(32) std::int32_t cell[RayBatch::kWidth];
    bool have_cells = false;
    for (const LightBuffer& buffer : light_buffers_) {
      const LaneMask here = buffer.ends_here(lanes, t_max, unmatched);
      if (here == 0) continue;
      if (!have_cells) {
        _mm256_store_si256(reinterpret_cast<__m256i*>(cell), LightBuffer::cells(lanes));
        have_cells = true;
      }
      unmatched &= ~here;
      for_each_lane(here, [&](int lane) {
        if (buffer.blocks(rays.get(lane), cell[lane])) blocked |= LaneMask(1) << lane;
      });
      if (unmatched == 0) break;
    }
    served = pending & ~unmatched;
    return blocked;
  }
#endif

  // A ray leaving its origin sphere outwards cannot meet it again; heading inwards it meets
  // the far side only.
  bool origin_sphere_hit(const Ray& ray, SphereHit& hit) const {
    if (ray.origin_sphere == kNoSphere || !ray.heads_into_origin_sphere) return false;
    const float t =
        far_side_distance(ray.origin, ray.direction, surfaces_[ray.origin_sphere].center);
    if (!(t > ray.t_min && t < hit.t)) return false;
    hit.t = t;
    hit.sphere = ray.origin_sphere;
    return true;
  }
  /// Each lane's best before any sphere is tested: its ray's t_max, no sphere.
  static HitBatch no_hits_within(const RayBatch& rays) {
    HitBatch hit;
    std::copy(std::begin(rays.t_max), std::end(rays.t_max), std::begin(hit.t));
    return hit;
  }
  /// origin_sphere_hit for the lanes of `active` whose ray heads into the sphere it leaves,
  /// each against its best in `hit`, which it updates; returns the lanes it found a hit for.
  LaneMask origin_sphere_hits(const RayBatch& rays, LaneMask active, HitBatch& hit) const {
    LaneMask found = 0;
    for_each_lane(active & rays.heads_into_origin_sphere, [&](int lane) {
      SphereHit lane_hit = hit.get(lane);
      if (!origin_sphere_hit(rays.get(lane), lane_hit)) return;
      hit.set(lane, lane_hit);
      found |= LaneMask(1) << lane;
    });
    return found;
  }

  std::string source_;
  ImageDescription image_;
  CameraDescription camera_;
  float antialias_sigma_ = defaults::antialias_sigma;
  Environment environment_;
  int background_line_ = 0;
  BoundingSphere bounds_;
  std::vector<PointLight> lights_;
  EmitterTable emitters_;
  WallSet walls_;
  SphereSet linear_;
  SphereBvh hierarchy_;
#ifdef GLINT_AVX2
  std::vector<LightBuffer> light_buffers_;  ///< of the first kMaxLightBuffers point lights
#endif
  std::vector<SurfaceProperties> surfaces_;
  std::vector<int> sphere_lines_;
  static constexpr std::uint32_t kNoTexture = std::numeric_limits<std::uint32_t>::max();
  std::vector<SphereTexture> textures_;  ///< one per textured sphere
  /// Each sphere's index in textures_ (kNoTexture: none); empty in a scene without textures.
  std::vector<std::uint32_t> sphere_textures_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
