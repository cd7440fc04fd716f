#pragma once
// Light sampling policies: how a path finds the light of emissive spheres. Point lights are
// always gathered directly at diffuse hits (they cannot be hit by a bounce); these policies
// decide whether emissive spheres are also sampled there (next-event estimation) and, if so,
// which emitter a light sample goes to (policy/emitter_choice.hpp) and how a light sample and a
// bounce that lands on the same emitter share the work (multiple importance sampling, Veach
// 1997, chapter 9).
//
// Both weights are functions of two densities per unit solid angle at the shading point: that
// of the strategy that made the sample, and that of the other strategy for the same direction.
// For every direction the two weights sum to one, which keeps the estimate unbiased.

#include <limits>

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/emitter_choice.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's: emissive spheres are found only when a bounce happens to hit them.
struct PointLightsOnly {
  static constexpr bool samples_emitters = false;
  template <FloatType F>
  static F light_weight(F, F) {
    return splat<F>(0.0f);
  }
  template <FloatType F>
  static F bounce_weight(F, F) {
    return splat<F>(1.0f);
  }
};

namespace detail {
/// A heuristic's weight `w` for a sample of density `pdf`: none for a density that is not
/// positive (or NaN), all for an infinite one.
template <FloatType F>
inline F heuristic_weight(F pdf, F w) {
  return select(pdf > 0.0f,
                select(pdf == std::numeric_limits<float>::infinity(), splat<F>(1.0f), w),
                splat<F>(0.0f));
}
}  // namespace detail

/// Both heuristics are written in the ratio of the densities, 1 / (1 + (other/pdf)^k): the
/// densities may lie near the ends of the float range (the cone of a small distant lamp, the
/// area density at a grazing point), where pdf^2 or pdf + other_pdf would overflow or
/// underflow and the two weights would no longer sum to one, or be 0/0.

/// The balance heuristic: each strategy weighted by its share of the summed densities.
struct BalanceHeuristic {
  template <FloatType F>
  static F weight(F pdf, F other_pdf) {
    return detail::heuristic_weight(pdf, 1.0f / (1.0f + other_pdf / pdf));
  }
};

/// The power heuristic with exponent 2: closer to choosing the better strategy outright, which
/// Veach shows is rarely worse than the balance heuristic and often much better where one
/// strategy is poor (a small lamp seen from a diffuse surface).
struct PowerHeuristic {
  template <FloatType F>
  static F weight(F pdf, F other_pdf) {
    const F ratio = other_pdf / pdf;
    return detail::heuristic_weight(pdf, 1.0f / (1.0f + ratio * ratio));
  }
};

/// Next-event estimation with multiple importance sampling: at every diffuse hit from which a
/// bounce may follow, one emissive sphere is chosen and a direction towards it sampled and
/// tested with a shadow ray; a bounce that lands on an emitter is weighted against the density
/// with which light sampling would have chosen that direction. Delta lobes (mirror, refraction)
/// have no density to compare, so light reaching a path through them keeps weight one. The
/// emitter is chosen by `Choice`; its probability is part of the light sample's density.
template <MisHeuristic Heuristic, EmitterChoice Choice = EmitterChoiceByContribution>
struct EmitterSampling {
  using heuristic = Heuristic;
  using emitter_choice = Choice;
  static constexpr bool samples_emitters = true;
  /// Where the heuristic has the width's form (a user's may be written for one path only).
  template <FloatType F>
  static F light_weight(F light_pdf, F bounce_pdf) requires requires {
    Heuristic::weight(light_pdf, bounce_pdf);
  }
  { return Heuristic::weight(light_pdf, bounce_pdf); }
  template <FloatType F>
  static F bounce_weight(F bounce_pdf, F light_pdf) requires requires {
    Heuristic::weight(bounce_pdf, light_pdf);
  }
  { return Heuristic::weight(bounce_pdf, light_pdf); }
};

/// Next-event estimation alone: emitters are reached only by light samples, and a bounce that
/// lands on one from a diffuse hit counts nothing. Noisier than MIS where the lamp is large
/// or close; kept as the reference strategy the tests compare the others with.
template <EmitterChoice Choice = EmitterChoiceByContribution>
struct EmitterSamplingOnly {
  using emitter_choice = Choice;
  static constexpr bool samples_emitters = true;
  template <FloatType F>
  static F light_weight(F, F) {
    return splat<F>(1.0f);
  }
  template <FloatType F>
  static F bounce_weight(F, F) {
    return splat<F>(0.0f);
  }
};

static_assert(MisHeuristic<BalanceHeuristic> && MisHeuristic<PowerHeuristic>);
static_assert(LightSampling<PointLightsOnly> && LightSampling<EmitterSampling<PowerHeuristic>> &&
              LightSampling<EmitterSampling<BalanceHeuristic>> &&
              LightSampling<EmitterSampling<PowerHeuristic, EmitterChoiceByPower>> &&
              LightSampling<EmitterSamplingOnly<>>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
