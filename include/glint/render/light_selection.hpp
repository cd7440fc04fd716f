#pragma once
// How an estimator chooses one of a scene's lights (render/scene_lights.hpp) for a light path or
// a join to a light.

#include <cstddef>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/render/scene_lights.hpp"
#include "glint/scene/emitters.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The choice of a light in proportion to its power, which light paths and a bidirectional
/// path's joins to a light use: exact for a scene with one light, and blind to where the point
/// being lit is (a choice by contribution at the point would serve a room of many lamps better).
class LightSelectionByPower {
 public:
  struct Choice {
    LightId light;
    float probability;
  };

  explicit LightSelectionByPower(const SceneLights& lights) {
    std::vector<double> power;
    lights.for_each([&](const auto& light) { power.push_back(light.power()); });
    double total = 0.0;
    for (const double p : power)
      total += p;
    empty_ = !(total > 0.0);
    cumulative_choice(power, cdf_, probability_);
  }

  /// Whether no light has power: then no light path carries anything.
  bool empty() const { return empty_; }

  /// The light for a uniform number u in [0, 1). Requires !empty().
  Choice choose(float u) const {
    const std::size_t id = choice_of(cdf_, u);
    return {LightId(id), probability_[id]};
  }

  /// The probability that choose() gives light `id`.
  float probability(LightId id) const { return probability_[id]; }

 private:
  std::vector<float> cdf_;  ///< of the choice by power (cumulative_choice)
  std::vector<float> probability_;
  bool empty_ = true;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
