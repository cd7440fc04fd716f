#pragma once
// The emissive spheres of a scene, as light sampling sees them: each one can draw a direction
// towards itself from a shading point and give the density of any direction that reaches it,
// and the table chooses one emitter per light sample.
//
// The choice is proportional to emitted power (area times mean radiance): it costs one binary
// search, needs no state per shading point and is exact for a scene with one lamp, which is the
// common case. Its weakness is a scene where a large dim emitter (a glowing sky dome) outshines
// small bright lamps in power but not at the points being shaded; a choice by estimated
// contribution at the point (pbrt-v4's light BVH) would serve that case better.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// How a shading point sees an emitter, which decides how directions towards it are drawn.
enum class EmitterView : std::uint8_t {
  outside,  ///< uniformly in the cone the sphere subtends (the visible cap, exactly)
  inside,   ///< through a uniform point on the sphere's area: every point of it is visible
  none,     ///< the point is on the emitter's outer surface: no direction from it reaches it
};

/// A direction towards an emitter and its density per unit solid angle at the shading point.
struct EmitterDirection {
  Vec3 direction;
  float pdf;
};

/// A direction towards an emissive sphere for a Float's lanes of shading points (F = float: one
/// point), with its density, and whether anything can arrive along it.
template <typename F>
struct BasicEmitterSample {
  Vec3For<F> direction;
  F pdf;
  MaskFor<F> valid;  ///< false where the point cannot see the emitter or the sample degenerates
};

namespace detail {
/// 1 - cos of the half-angle a sphere of radius `radius` subtends at distance `distance` from
/// its centre: sin^2 / (1 + cos), which keeps its precision for small, distant spheres.
template <FloatType F>
inline F cone_one_minus_cos_max(F radius, F distance) {
  const F sin2_max = min(splat<F>(1.0f), (radius / distance) * (radius / distance));
  const F cos2_max =
      max(splat<F>(0.0f), (distance - radius) * (distance + radius)) / (distance * distance);
  return sin2_max / (1.0f + sqrt(cos2_max));
}
}  // namespace detail

/// A direction from `point` towards the sphere (center, radius), lane by lane, from two
/// uniform numbers: uniformly in the cone it subtends where the point sees it from `outside`,
/// else through a uniform point of its area (every point of it is visible from inside), and
/// nothing where the point lies on its outer surface (`none`). Each branch is computed only
/// where some lane takes it.
template <typename V3>
inline BasicEmitterSample<FloatOf<V3>> sample_sphere_emitter(const V3& center, FloatOf<V3> radius,
                                                             const V3& point,
                                                             MaskFor<FloatOf<V3>> outside,
                                                             MaskFor<FloatOf<V3>> none,
                                                             const Vec2For<FloatOf<V3>>& u) {
  using F = FloatOf<V3>;
  BasicEmitterSample<F> sample{splat_vector<V3>(Vec3(0.0f)), splat<F>(0.0f), outside};
  if (any(outside)) {
    const V3 to_center = center - point;
    const F distance = sqrt(dot(to_center, to_center));
    const F one_minus_cos_max = detail::cone_one_minus_cos_max(radius, distance);
    sample.direction = BasicFrame<V3>::around(to_center / distance)
                           .to_world(sample_uniform_cone(u, one_minus_cos_max));
    sample.pdf = uniform_cone_pdf(one_minus_cos_max);
  }
  if (!all(outside)) {
    const V3 normal = sample_uniform_sphere(u);
    const V3 to_light = center + radius * normal - point;
    const F distance2 = dot(to_light, to_light);
    const V3 direction = to_light / sqrt(distance2);
    const F cosine = abs(dot(direction, normal));
    const F area_pdf = distance2 / ((4.0f * kPi * radius * radius) * cosine);
    sample.direction = select(outside, sample.direction, direction);
    sample.pdf = select(outside, sample.pdf, area_pdf);
    sample.valid = outside || (!none && distance2 > 0.0f && cosine > 0.0f);
  }
  return sample;
}

/// Emitters chosen for a Float's lanes of shading points, with their probabilities.
template <typename F>
struct EmitterLanes {
  Vec3For<F> center;
  F radius;
  Vec3For<F> radiance;
  UIntFor<F> sphere;  ///< index of the sphere in the scene
  F probability;      ///< of the choice
};

/// How a Float's lanes of points see their emitters (the EmitterView of each lane as masks):
/// `outside` where the point sees the sphere from outside, `none` where it lies on the sphere's
/// outer surface, inside otherwise. `point_sphere` is the sphere each point lies on and
/// `from_inside` the side of it the point is on: a point on the emitter itself sees it only
/// from inside.
template <typename F>
struct EmitterViews {
  MaskFor<F> outside;
  MaskFor<F> none;
};
template <typename V3>
EmitterViews<FloatOf<V3>> emitter_views(const V3& center, FloatOf<V3> radius,
                                        UIntFor<FloatOf<V3>> sphere, const V3& point,
                                        UIntFor<FloatOf<V3>> point_sphere,
                                        MaskFor<FloatOf<V3>> from_inside) {
  const auto on_emitter = point_sphere == sphere;
  const V3 offset = point - center;
  return {!on_emitter && dot(offset, offset) > radius * radius, on_emitter && !from_inside};
}

/// The mean of a colour's channels, in double: the power of a colour, as the choices by power
/// weigh it.
inline double channel_mean(const Color& c) {
  return (double(c.r) + double(c.g) + double(c.b)) / 3.0;
}

/// The cumulative probabilities `cdf` (the last exactly 1) and the probabilities `probability`
/// of choosing item i with probability weights[i] / sum of weights (the last item, if they sum to
/// zero). A probability is exactly the width of its step of the cdf
/// as stored in float, so that a choice and its probability agree to the last bit.
inline void cumulative_choice(const std::vector<double>& weights, std::vector<float>& cdf,
                              std::vector<float>& probability) {
  double total = 0.0;
  for (const double w : weights)
    total += w;
  cdf.resize(weights.size());
  probability.resize(weights.size());
  double sum = 0.0;
  float previous = 0.0f;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    sum += weights[i];
    cdf[i] = i + 1 == weights.size() ? 1.0f : float(total > 0.0 ? sum / total : 0.0);
    probability[i] = cdf[i] - previous;
    previous = cdf[i];
  }
}

/// The index of the choice for a uniform number u in [0, 1) by a cdf of cumulative_choice: the
/// number of cumulative probabilities that u is not below, at most the last index.
inline std::size_t choice_of(const std::vector<float>& cdf, float u) {
  const auto at = std::size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
  return at < cdf.size() ? at : cdf.size() - 1;
}

/// An emissive sphere. Its radiance leaves both sides of the surface, as every sphere's does.
struct SphereEmitter {
  Vec3 center;
  float radius;
  Color radiance;
  std::uint32_t sphere;  ///< index of the sphere in the scene

  float area() const { return 4.0f * kPi * radius * radius; }

  /// How `point` sees this emitter. `point_sphere` is the sphere the point lies on and
  /// `from_inside` the side of it the point is on (a point on this emitter sees it only from
  /// inside).
  EmitterView view_from(const Vec3& point, std::uint32_t point_sphere, bool from_inside) const {
    const EmitterViews<float> view =
        emitter_views(center, radius, sphere, point, point_sphere, from_inside);
    return view.outside ? EmitterView::outside
           : view.none  ? EmitterView::none
                        : EmitterView::inside;
  }

  /// A direction from `point` towards the sphere, from two uniform numbers; none when the
  /// point cannot see it or the sample degenerates (sample_sphere_emitter for one point).
  std::optional<EmitterDirection> sample_direction(const Vec3& point, EmitterView view,
                                                   Vec2 u) const {
    if (view == EmitterView::none) return std::nullopt;
    const BasicEmitterSample<float> sample =
        sample_sphere_emitter(center, radius, point, view == EmitterView::outside, false, u);
    if (!sample.valid) return std::nullopt;
    return EmitterDirection{sample.direction, sample.pdf};
  }

  /// The density with which sample_direction(point, view, .) gives `direction`, where the ray
  /// from `point` along it meets this sphere first at distance `distance`, with outward normal
  /// `normal` there.
  float direction_pdf(const Vec3& point, EmitterView view, const Vec3& direction, float distance,
                      const Vec3& normal) const {
    if (view == EmitterView::outside) {
      const Vec3 to_center = center - point;
      return uniform_cone_pdf(
          detail::cone_one_minus_cos_max(radius, std::sqrt(glm::dot(to_center, to_center))));
    }
    if (view == EmitterView::inside) {
      const float cosine = std::fabs(glm::dot(direction, normal));
      return cosine > 0.0f ? distance * distance / (area() * cosine) : 0.0f;
    }
    return 0.0f;
  }
};

/// The scene's emitters and the distribution light sampling chooses them from.
class EmitterTable {
 public:
  struct Choice {
    std::uint32_t index;
    float probability;
  };

  EmitterTable() = default;

  /// Chooses in proportion to power: area times the mean of the radiance's channels.
  explicit EmitterTable(std::vector<SphereEmitter> emitters) : emitters_(std::move(emitters)) {
    std::vector<double> power;
    for (const SphereEmitter& e : emitters_)
      power.push_back(double(e.radius) * e.radius * channel_mean(e.radiance));
    cumulative_choice(power, cdf_, probability_);
  }

  bool empty() const { return emitters_.empty(); }
  std::size_t size() const { return emitters_.size(); }
  const SphereEmitter& operator[](std::uint32_t index) const { return emitters_[index]; }
  const std::vector<SphereEmitter>& emitters() const { return emitters_; }

  /// The emitter for a uniform number u in [0, 1), and the probability of choosing it.
  /// Requires !empty().
  Choice choose(float u) const {
    const auto index = std::uint32_t(choice_index(u));
    return {index, probability_[index]};
  }

  /// The emitters chosen by each lane of `u`, and their probabilities (every lane's index is a
  /// valid one, whatever its u). Requires !empty().
  template <FloatType F>
  EmitterLanes<F> choose_lanes(F u) const {
    const IntFor<F> index = choice_index(u);
    EmitterLanes<F> chosen;
    if constexpr (kLanesOf<F> == 1) {
      const SphereEmitter& e = emitters_[std::size_t(index)];
      chosen = {e.center, e.radius, e.radiance, e.sphere, probability_[std::size_t(index)]};
#if defined(GLINT_AVX2)
    } else if constexpr (kLanesOf<F> == kLaneCount || kLanesOf<F> == kMaxColumnRows) {
      // The chosen emitters' eight words (centre, radius, radiance, sphere) as one transpose.
      static_assert(offsetof(SphereEmitter, center) == 0 && offsetof(SphereEmitter, radius) == 12 &&
                    offsetof(SphereEmitter, radiance) == 16 &&
                    offsetof(SphereEmitter, sphere) == 28 && sizeof(SphereEmitter) == 32);
      const float* records[kLanesOf<F>];
      for (int i = 0; i < kLanesOf<F>; ++i) {
        records[i] = reinterpret_cast<const float*>(&emitters_[std::size_t(index[i])]);
        chosen.probability[i] = probability_[std::size_t(index[i])];
      }
      F words[kLaneCount];
      load_columns(records, words);
      chosen.center = {words[0], words[1], words[2]};
      chosen.radius = words[3];
      chosen.radiance = {words[4], words[5], words[6]};
      chosen.sphere = std::bit_cast<UIntFor<F>>(words[7]);
    } else if constexpr (kLanesOf<F> == 2 * kLaneCount) {
      // Two transposes of eight.
      const EmitterLanes<FloatLanes> low = choose_lanes(low_half(u));
      const EmitterLanes<FloatLanes> high = choose_lanes(high_half(u));
      const auto both3 = [](const Vec3Lanes& a, const Vec3Lanes& b) {
        return Vector3<F>{join(a.x, b.x), join(a.y, b.y), join(a.z, b.z)};
      };
      chosen = {both3(low.center, high.center), join(low.radius, high.radius),
                both3(low.radiance, high.radiance), join(low.sphere, high.sphere),
                join(low.probability, high.probability)};
#endif
    } else {
      for (int i = 0; i < kLanesOf<F>; ++i) {
        const SphereEmitter& e = emitters_[std::size_t(index[i])];
        chosen.center.set_lane(i, e.center);
        chosen.radius[i] = e.radius;
        chosen.radiance.set_lane(i, e.radiance);
        chosen.sphere[i] = e.sphere;
        chosen.probability[i] = probability_[std::size_t(index[i])];
      }
    }
    return chosen;
  }

  /// choose()'s index for each lane of `u`: the number of cumulative probabilities that u is
  /// not below, at most size() - 1, which is the place upper_bound finds. Counted over the
  /// whole table up to kLinearChoices emitters, searched lane by lane beyond.
  template <FloatType F>
  IntFor<F> choice_index(F u) const {
    using I = IntFor<F>;
    const auto last = std::int32_t(cdf_.size()) - 1;
    I index = splat<I>(0);
    if (cdf_.size() <= kLinearChoices) {
      for (const float step : cdf_) {
        if constexpr (kLanesOf<F> == 1)
          index += u < step ? 0 : 1;
        else
          index -= ~(u < step);  // a comparison is -1 where true: this adds 1 where false
      }
    } else {
      for (int i = 0; i < kLanesOf<F>; ++i)
        set_lane(index, i, std::int32_t(choice_of(cdf_, lane(u, i))));
    }
    return select(index > last, splat<I>(last), index);
  }
  static constexpr std::size_t kLinearChoices = 64;

  /// The probability that choose() gives emitter `index`.
  float probability(std::uint32_t index) const {
    return probability_[index];
  }

 private:
  std::vector<SphereEmitter> emitters_;
  std::vector<float> cdf_;  ///< cumulative probabilities, the last exactly 1
  std::vector<float> probability_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
