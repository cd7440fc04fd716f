#pragma once
// Emitter choice policies: which emissive sphere a light sample at a shading point goes to
// (policy/light_sampling.hpp's EmitterSampling), and the probability of that choice, which the
// light sample divides by and multiple importance sampling weighs a bounce that lands on the
// same emitter against.
//
// The choice by power ignores where the point is: in a room of many small lamps, most light
// samples go to bright lamps far away or behind the surface, and the lamp next to the point is
// rarely chosen. The choice by contribution weighs every emitter by an estimate of the light it
// can bring to the point (its radiance times the solid angle it subtends times the sine of the
// elevation of its highest point), so lamps that are near, bright and high above the surface
// are chosen more, and lamps wholly below the surface's horizon never. Any estimate that is
// positive wherever the emitter can light the point keeps the estimator unbiased; a better one only
// lowers the noise. Both choices are written once over the width type, so a lane's choice and
// probability are the same bits at every width, and the probability a bounce's weight needs is
// computed from the bounce's origin alone.

#include <concepts>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/emitters.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A Float's lanes of shading points an emitter is chosen for: where each lies, the unit normal
/// on the side light reflects from, the sphere it lies on, whether it is seen from that sphere's
/// inside, and whether light is taken from both sides of the surface (a lobe with a density
/// transmits: a rough interface), where the normal's side does not matter.
template <typename F>
struct EmitterChoicePoint {
  Vec3For<F> point;
  Vec3For<F> normal;
  UIntFor<F> sphere;
  MaskFor<F> from_inside;
  MaskFor<F> two_sided = mask_of<MaskFor<F>>(false);
};

/// How light sampling chooses an emitter: `choose` gives each lane of points an emitter and the
/// probability of choosing it (zero where it can choose none, which then brings no light), and
/// `probability` is that probability for one point and one emitter. Both at every width.
template <typename C>
concept EmitterChoice = requires(const EmitterTable& table, const EmitterChoicePoint<float>& at,
                                 float u, std::uint32_t index) {
  { C::choose(table, at, u) } -> std::same_as<EmitterLanes<float>>;
  { C::probability(table, at, index) } -> std::same_as<float>;
};

/// In proportion to power (EmitterTable's choice): one binary search, the same for every point.
struct EmitterChoiceByPower {
  template <FloatType F>
  static EmitterLanes<F> choose(const EmitterTable& table, const EmitterChoicePoint<F>&, F u) {
    return table.choose_lanes(u);
  }
  static float probability(const EmitterTable& table, const EmitterChoicePoint<float>&,
                           std::uint32_t index) {
    return table.probability(index);
  }
};

/// In proportion to each emitter's estimated light at the point: two passes over the emitters
/// (the sum of the estimates, then a count of those before the running sum passes u times the
/// sum), so the cost grows with their number. The probability of one emitter sums the estimates
/// again at the bounce's origin, in the same order, which gives the choice's own bits.
struct EmitterChoiceByContribution {
  /// The estimate for emitter `index` at the points `at`, an irradiance over pi: seen from
  /// outside, its mean radiance L times (r/d)^2 (the solid angle of a small sphere over pi) times
  /// (h + r)/d at most one, where h is the height of its centre above the point's tangent plane,
  /// so that (h + r)/d is the sine of the elevation of its highest point; L from inside, where
  /// it fills the hemisphere. Positive exactly where some of the sphere is above the plane
  /// (h > -r), or on either side of it at a two-sided point (|h| in place of h); zero where the
  /// point lies on its outer surface. One square root and one division: the estimate runs for
  /// every emitter at every light sample.
  template <FloatType F>
  static F estimate(const EmitterTable& table, std::uint32_t index,
                    const EmitterChoicePoint<F>& at) {
    using V3 = Vec3For<F>;
    const SphereEmitter& e = table[index];
    const float radiance = table.mean_radiance(index);
    const float radius2 = e.radius * e.radius;
    const V3 to_center = splat_vector<V3>(e.center) - at.point;
    const F distance2 = dot(to_center, to_center);
    const auto on_light = at.sphere == e.sphere;
    const MaskFor<F> outside = !on_light && distance2 > radius2;
    const MaskFor<F> none = on_light && !at.from_inside;
    const F distance = sqrt(distance2);
    const F height = dot(at.normal, to_center);
    const F top = select(at.two_sided, abs(height), height) + e.radius;
    // Lanes inside divide by zero where the point is the centre, and the select drops them.
    const F seen_from_outside =
        select(top > 0.0f, (radiance * radius2) * min(distance, top) / (distance2 * distance),
               splat<F>(0.0f));
    return select(outside, seen_from_outside, select(none, splat<F>(0.0f), splat<F>(radiance)));
  }

  /// The emitter of each lane by its share of the summed estimates, with that share as its
  /// probability (zero, and emitter 0, where every estimate is zero).
  template <FloatType F>
  static EmitterLanes<F> choose(const EmitterTable& table, const EmitterChoicePoint<F>& at, F u) {
    const auto count = std::uint32_t(table.size());
    if (count <= kKeptEstimates) {
      F kept[kKeptEstimates];
      for (std::uint32_t i = 0; i < count; ++i)
        kept[i] = estimate(table, i, at);
      return choose_by(
          table, [&](std::uint32_t i) { return kept[i]; },
          [&](int lane_index, std::uint32_t i) { return lane(kept[i], lane_index); }, u);
    }
    return choose_by(
        table, [&](std::uint32_t i) { return estimate(table, i, at); },
        [&](int lane_index, std::uint32_t i) {
          return estimate(table, i, point_of_lane(at, lane_index));
        },
        u);
  }

  static float probability(const EmitterTable& table, const EmitterChoicePoint<float>& at,
                           std::uint32_t index) {
    float total = 0.0f;
    float share = 0.0f;
    for (std::uint32_t i = 0; i < std::uint32_t(table.size()); ++i) {
      const float w = estimate(table, i, at);
      total += w;
      if (i == index) share = w;
    }
    return total > 0.0f ? share / total : 0.0f;
  }

  /// Up to this many emitters, choose() keeps each lane's estimates (on the stack, 4 KiB at
  /// width 16) for its second pass rather than computing them again.
  static constexpr std::uint32_t kKeptEstimates = 64;

 private:
  template <FloatType F>
  static EmitterChoicePoint<float> point_of_lane(const EmitterChoicePoint<F>& at, int i) {
    return {lane(at.point, i), lane(at.normal, i), lane(at.sphere, i), lane(at.from_inside, i) != 0,
            lane(at.two_sided, i) != 0};
  }

  /// choose() with the estimates of emitter i given by estimate_of(i) for all lanes and by
  /// lane_estimate(lane, i) for one, the same bits each call. The running sum never falls, and
  /// rises exactly at an emitter with an estimate, so the number of emitters at which it is not
  /// above u times the total is the first at which it is: the choice, counted in three
  /// operations per emitter.
  template <FloatType F, typename Estimates, typename LaneEstimate>
  static EmitterLanes<F> choose_by(const EmitterTable& table, Estimates&& estimate_of,
                                   LaneEstimate&& lane_estimate, F u) {
    using I = IntFor<F>;
    const auto count = std::uint32_t(table.size());
    F total = splat<F>(0.0f);
    for (std::uint32_t i = 0; i < count; ++i)
      total += estimate_of(i);
    const F target = u * total;
    F running = splat<F>(0.0f);
    I index = splat<I>(0);
    for (std::uint32_t i = 0; i < count; ++i) {
      running += estimate_of(i);
      if constexpr (kLanesOf<F> == 1)
        index += running <= target ? 1 : 0;
      else
        index -= running <= target;  // a comparison is -1 where true
    }
    F share = splat<F>(0.0f);
    for (int lane_index = 0; lane_index < kLanesOf<F>; ++lane_index) {
      if (!(lane(total, lane_index) > 0.0f)) {
        set_lane(index, lane_index, 0);
        continue;
      }
      auto chosen = std::uint32_t(lane(index, lane_index));
      float w = 0.0f;
      if (chosen < count) {
        w = lane_estimate(lane_index, chosen);
      } else {
        // Where u * total rounds up to total, the running sum never passes it: the last
        // emitter with an estimate is the choice there.
        do
          w = lane_estimate(lane_index, --chosen);
        while (!(w > 0.0f));
      }
      set_lane(index, lane_index, std::int32_t(chosen));
      set_lane(share, lane_index, w);
    }
    EmitterLanes<F> chosen = table.lanes_of<F>(index);
    chosen.probability = select(total > 0.0f, share / total, splat<F>(0.0f));
    return chosen;
  }
};

static_assert(EmitterChoice<EmitterChoiceByPower> && EmitterChoice<EmitterChoiceByContribution>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
