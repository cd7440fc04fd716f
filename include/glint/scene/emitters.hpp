#pragma once
// The emissive spheres of a scene: a table of the spheres' centres, radii and radiances that a
// Float's lanes of shading points read in one transpose, and the choice of one in proportion to
// its emitted power (area times mean radiance), which costs one binary search, needs no state per
// shading point and is exact for a scene with one lamp. How a sphere light is sampled is
// render/lights/sphere_light.hpp; the choice by each emitter's estimated light at the shading
// point, which a room of many lamps needs, is policy/emitter_choice.hpp.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Emitters chosen for a Float's lanes of shading points, with their probabilities.
template <typename F>
struct EmitterLanes {
  Vec3For<F> center;
  F radius;
  Vec3For<F> radiance;
  UIntFor<F> sphere;  ///< index of the sphere in the scene
  F probability;      ///< of the choice
};

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
    for (const SphereEmitter& e : emitters_) {
      power.push_back(double(e.radius) * e.radius * channel_mean(e.radiance));
      mean_radiance_.push_back(float(channel_mean(e.radiance)));
    }
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
    return lanes_of<F>(choice_index(u));
  }

  /// The emitters `index` (each a valid index) for a Float's lanes, with the probabilities of
  /// choosing them by power.
  template <FloatType F>
  EmitterLanes<F> lanes_of(IntFor<F> index) const {
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
      const EmitterLanes<FloatLanes> low = lanes_of<FloatLanes>(low_half(index));
      const EmitterLanes<FloatLanes> high = lanes_of<FloatLanes>(high_half(index));
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

  /// The mean of the channels of emitter `index`'s radiance, which a choice by contribution
  /// weighs it by.
  float mean_radiance(std::uint32_t index) const {
    return mean_radiance_[index];
  }

 private:
  std::vector<SphereEmitter> emitters_;
  std::vector<float> cdf_;  ///< cumulative probabilities, the last exactly 1
  std::vector<float> probability_;
  std::vector<float> mean_radiance_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
