#pragma once
// How much work one camera sample can take, known before rendering. The report's tree model
// traces every lobe of every hit, so a sphere with two or three lobes (mirror and glass, or
// the report's "weird" material) multiplies the rays of a path at each bounce on it: in a
// closed room the cost grows as branching^max_depth, and a depth accepted in a second can run
// for days. The one-lobe (chain) models trace at most one bounce ray per hit and are linear.

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>

#include "glint/config.hpp"
#include "glint/detail/text.hpp"
#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/estimators/tree.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// An upper bound on the rays of one camera sample under the tree model: every hit is assumed
/// to be on the sphere with the most lobes and to gather every point light (and, when emitters
/// are sampled, one emitter).
struct TreeWork {
  double rays_per_sample = 1.0;             ///< the bound (capped at 1e300)
  int branching = 0;                        ///< most lobes of any sphere: rays a hit can spawn
  std::uint32_t widest_sphere = kNoSphere;  ///< a sphere with that many lobes
};

/// R(max_depth) = 1 + shadow rays (+ branching where the last bounce is traced, its hits only
/// collecting light: PathContext::bounces_from); R(d) = 1 + shadow rays + branching * R(d + 1),
/// capped at 1e300 so that no depth overflows.
inline double tree_rays_bound(int branching, int max_depth, int shadow_rays,
                              bool last_bounce_traced) {
  const double per_hit = 1.0 + shadow_rays;
  double rays = per_hit + (last_bounce_traced ? branching : 0);
  for (int depth = max_depth - 1; depth >= 0 && rays < 1e300; --depth)
    rays = per_hit + branching * rays;
  return std::min(rays, 1e300);
}

/// The bound for max_depth bounces, with `shadow_rays` rays traced at each diffuse hit.
inline TreeWork estimate_tree_work(const Scene& scene, int max_depth, int shadow_rays) {
  TreeWork work;
  for (std::uint32_t i = 0; i < scene.sphere_count(); ++i) {
    const Material& m = scene.surface(i).material;
    const int lobes = int(m.diffuse > 0.0f) + int(m.mirror > 0.0f) + int(m.transparent > 0.0f);
    if (lobes > work.branching) {
      work.branching = lobes;
      work.widest_sphere = i;
    }
  }
  work.rays_per_sample =
      tree_rays_bound(work.branching, max_depth, shadow_rays, rays_can_find_light(scene));
  return work;
}

/// Whether variant C follows every lobe (the tree model), whose cost depends on the scene.
template <RenderConfig C>
inline constexpr bool traces_every_lobe = std::is_same_v<typename C::estimator, TreePathTracing>;

/// Throws SettingsError when variant C would trace more than limits::max_tree_rays_per_sample
/// rays for one camera sample in the worst case, naming the bound, a sphere that branches and
/// the ways out. Nothing to check for the one-lobe models.
template <RenderConfig C>
void check_work(const Scene& scene, int max_depth) {
  if constexpr (traces_every_lobe<C>) {
    const int shadow_rays = static_cast<int>(scene.lights().size()) +
                            (C::light_sampling::samples_emitters && !scene.emitters().empty());
    const TreeWork work = estimate_tree_work(scene, max_depth, shadow_rays);
    if (work.rays_per_sample <= limits::max_tree_rays_per_sample) return;
    int depth_within = max_depth;
    while (depth_within > 0 &&
           tree_rays_bound(work.branching, depth_within, shadow_rays, rays_can_find_light(scene)) >
               limits::max_tree_rays_per_sample)
      --depth_within;
    const std::string where =
        scene.sphere_line(work.widest_sphere) > 0
            ? detail::concat({" (such as the sphere on line ",
                              std::to_string(scene.sphere_line(work.widest_sphere)), " of ",
                              scene.source(), ")"})
            : std::string();
    throw SettingsError(detail::concat(
        {"glint: the report's tree model would trace up to ",
         detail::format_number(static_cast<float>(work.rays_per_sample)),
         " rays per sample here: spheres with ", std::to_string(work.branching), " lobes", where,
         " split every ray that hits them, ", std::to_string(max_depth),
         " bounces deep; the limit is ",
         detail::format_number(static_cast<float>(limits::max_tree_rays_per_sample)),
         ". Lower max_depth to ", std::to_string(depth_within),
         ", or use a one-lobe variant (glint-render-fast, glint-render-stochastic-material)"}));
  }
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
